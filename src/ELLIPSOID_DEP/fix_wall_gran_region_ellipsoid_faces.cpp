/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/region/ellipsoid, the region's faces as kernel wall surfaces

   A region's shape parameters are private to it; its public surface_interior() answers, for a
   point inside its shape, every closed face with the point's distance vector from it and the
   face's contact radius. One such answer from a point off every axis and centre gives each
   face exactly (a face's point is the probe minus the distance vector; a cylinder's and a
   sphere's radius are the contact radius, -2R and -R), in the region's own frame.
------------------------------------------------------------------------- */

#include "fix_wall_gran_region_ellipsoid.h"

#include "domain.h"
#include "error.h"
#include "region.h"

#include <algorithm>
#include <cmath>
#include <string>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

namespace {

// LAMMPS's regions put a face given as INF at +-1e20
constexpr double AT_INFINITY = 1.0e19;
constexpr double PROBE_CUTOFF = 1.0e30;
const char *const SUPPORTED = "block, cylinder, cone (side in), sphere and plane";

// a cone's side from two lateral contacts (the point on the side, the unit normal into the
// cone, the local radius) seen from two probes: the axis is the coordinate for which both
// give the same axis point; false when none does (a probe's foot fell on a rim)
bool cone_side(const Vec3 xs[2], const Vec3 inwards[2], const double local_radius[2],
               WallSurface &w)
{
  for (int k = 0; k < 3; k++) {
    Vec3 axis_point[2];
    for (int p = 0; p < 2; p++) {
      Vec3 radial = -inwards[p];
      radial[k] = 0.0;
      const double length = radial.norm();
      if (!(length > 0.0)) break;
      axis_point[p] = xs[p] - local_radius[p] * radial / length;
      axis_point[p][k] = xs[p][k];
      if (p == 1) {
        Vec3 mismatch = axis_point[1] - axis_point[0];
        mismatch[k] = 0.0;
        if (mismatch.norm() > 1e-9 * (1.0 + axis_point[0].norm())) break;
        Vec3 perpendicular = inwards[0];
        perpendicular[k] = 0.0;
        w.shape = WallShape::Cone;
        w.center = axis_point[0];
        w.axis = Vec3::Unit(k);
        w.radius = local_radius[0];
        w.slope = inwards[0][k] / perpendicular.norm();
        return true;
      }
    }
  }
  return false;
}

}    // namespace

// where a side ends along its axis (a coordinate axis), both ways from its axis point in the
// region's shape: the last coordinate inside() takes, by bisection to adjacent doubles
// (LAMMPS's lo and hi exactly); past AT_INFINITY none. An open end has no face of its own.
void FixWallGranRegionEllipsoid::side_extent(WallSurface &w)
{
  int k = 0;
  while (w.axis[k] == 0.0) k++;
  auto inside_at = [&](double coordinate) {
    Vec3 p = w.center;
    p[k] = coordinate;
    return region->inside(p[0], p[1], p[2]) != 0;
  };
  for (const double sign : {-1.0, 1.0}) {
    double in = w.center[k], step = std::max(1.0, std::fabs(in)), out = in + sign * step;
    while (inside_at(out) && std::fabs(out) < PROBE_CUTOFF) step *= 2.0, out = in + sign * step;
    double end = sign * INFINITY;
    if (std::fabs(out) < PROBE_CUTOFF) {
      for (;;) {
        const double mid = 0.5 * (in + out);
        if (mid == in || mid == out) break;
        (inside_at(mid) ? in : out) = mid;
      }
      if (std::fabs(in) < AT_INFINITY) end = in - w.center[k];
    }
    (sign < 0.0 ? w.cap_lo : w.cap_hi) = end;
  }
}

// a centre (in the region's own frame) that left a side through an open end: LAMMPS's
// fix wall/gran/region meets it with the rim there (region surface_exterior)
bool FixWallGranRegionEllipsoid::past_open_end(const Vec3 &x) const
{
  if (!region->openflag || !region->interior) return false;
  for (const WallSurface &w : faces) {
    if (w.shape != WallShape::Cone && !(w.shape == WallShape::Cylinder && w.inside)) continue;
    const double s = w.axis.dot(x - w.center);
    return (s < w.cap_lo && region->open_faces[0]) || (s > w.cap_hi && region->open_faces[1]);
  }
  return false;
}

// the cone's side from the lateral contacts of probe pairs (the first with each other)
bool FixWallGranRegionEllipsoid::cone_from_probes(const std::vector<Vec3> &probes,
                                                  WallSurface &w)
{
  auto lateral = [this](const Vec3 &p, Vec3 &xs, Vec3 &inwards, double &local_radius) {
    double x[3] = {p[0], p[1], p[2]};
    const int n = region->surface_interior(x, PROBE_CUTOFF);
    for (int c = 0; c < n; c++) {
      const Region::Contact &contact = region->contact[c];
      if (contact.iwall != 2) continue;
      const Vec3 del(contact.delx, contact.dely, contact.delz);
      xs = p - del;
      inwards = del.normalized();
      local_radius = -0.5 * contact.radius;
      return true;
    }
    return false;
  };
  Vec3 xs[2], inwards[2];
  double local_radius[2];
  if (!lateral(probes[0], xs[0], inwards[0], local_radius[0])) return false;
  for (std::size_t p = 1; p < probes.size() && p < 64; p++)
    if (lateral(probes[p], xs[1], inwards[1], local_radius[1]) &&
        cone_side(xs, inwards, local_radius, w))
      return true;
  return false;
}

std::vector<WallSurface> FixWallGranRegionEllipsoid::region_faces()
{
  // an axis-aligned flat face strictly inside the box
  auto within_box = [this](const WallSurface &w) {
    for (int d = 0; d < 3; d++)
      if (w.normal[d] != 0.0) {
        const double coord = w.offset / w.normal[d];
        return coord > domain->boxlo[d] && coord < domain->boxhi[d];
      }
    return false;
  };
  const std::string shape = region->style;
  if (shape != "block" && shape != "cylinder" && shape != "cone" && shape != "sphere" &&
      shape != "plane")
    error->all(FLERR,
               "Fix wall/gran/region/ellipsoid: region {} is of style {}; the supported region "
               "styles are {}",
               region_id, shape, SUPPORTED);
  if (region->varshape)
    error->all(FLERR,
               "Fix wall/gran/region/ellipsoid: region {} changes its shape with variables, not "
               "supported (move and rotate are)",
               region_id);
  const bool inside = region->interior != 0;

  // probe points inside the region's shape, off its centre and axes: a grid over the box
  // at irrational fractions, in the region's own frame
  std::vector<Vec3> probes;
  constexpr int GRID = 25;
  for (int i = 0; i < GRID; i++)
    for (int j = 0; j < GRID; j++)
      for (int k = 0; k < GRID; k++) {
        const int index[3] = {i, j, k};
        double x[3];
        for (int d = 0; d < 3; d++)
          x[d] = domain->boxlo[d] +
              (index[d] + 0.5 + 0.03 * M_SQRT2 * (d + 1)) / GRID * domain->prd[d];
        region->inverse_transform(x[0], x[1], x[2]);
        if (region->inside(x[0], x[1], x[2])) probes.emplace_back(x[0], x[1], x[2]);
      }
  if (probes.empty())
    error->all(FLERR,
               "Fix wall/gran/region/ellipsoid: no point of a 25^3 grid over the box lies in "
               "region {}'s shape (outside the box, or smaller than the grid's spacing)",
               region_id);
  if (!inside && region->openflag)
    error->all(FLERR,
               "Fix wall/gran/region/ellipsoid: region {} has side out and open faces; a "
               "region met from outside must be closed",
               region_id);
  if (shape == "cone" && !inside)
    error->all(FLERR,
               "Fix wall/gran/region/ellipsoid: region {} is a cone with side out; a cone is "
               "supported with side in (a hopper)",
               region_id);
  double probe[3] = {probes[0][0], probes[0][1], probes[0][2]};
  // a copy: the cone's probes below ask the region again
  const std::vector<Region::Contact> contacts(
      region->contact, region->contact + region->surface_interior(probe, PROBE_CUTOFF));

  std::vector<std::pair<int, WallSurface>> found_faces;
  for (const Region::Contact &contact : contacts) {
    const Vec3 del(contact.delx, contact.dely, contact.delz);
    const Vec3 point = Vec3(probe[0], probe[1], probe[2]) - del;    // on the face
    const Vec3 inwards = del.normalized();
    WallSurface w;
    if (contact.radius == 0.0) {
      // a flat face: the particles' side is the shape's inside for side in
      w.shape = WallShape::Plane;
      w.normal = inside ? inwards : Vec3(-inwards);
      // a block's or a cylinder's flat face lies along a coordinate axis: exactly
      for (int d = 0; d < 3; d++)
        if (shape != "plane" && del[d] == 0.0) w.normal[d] = 0.0;
      w.normal.normalize();
      w.offset = w.normal.dot(point);
      if (std::fabs(w.offset) > AT_INFINITY) continue;    // a face at INF
      // outside a block or a cylinder, a face beyond the box is none (the solid runs on
      // through the box's side, periodic or not)
      if (!inside && shape != "plane" && !within_box(w)) continue;
    } else if (shape == "cone") {
      if (!cone_from_probes(probes, w))
        error->all(FLERR, "Fix wall/gran/region/ellipsoid: cannot find region {}'s cone axis",
                   region_id);
      side_extent(w);
    } else {
      // LAMMPS's interior contact radius: -R for a sphere, -2R for a cylinder's side
      w.shape = shape == "sphere" ? WallShape::Sphere : WallShape::Cylinder;
      w.radius = shape == "sphere" ? -contact.radius : -0.5 * contact.radius;
      w.inside = inside;
      w.center = point + w.radius * inwards;
      if (w.shape == WallShape::Cylinder) {
        // the axis: the coordinate the lateral distance vector has no component along
        w.axis = Vec3::Zero();
        for (int d = 0; d < 3; d++)
          if (del[d] == 0.0) w.axis[d] = 1.0;
        if (w.axis.norm() != 1.0)
          error->all(FLERR, "Fix wall/gran/region/ellipsoid: cannot find region {}'s axis",
                     region_id);
        if (inside) side_extent(w);
      }
    }
    found_faces.emplace_back(contact.iwall, w);
  }
  std::sort(found_faces.begin(), found_faces.end(),
            [](const auto &a, const auto &b) { return a.first < b.first; });

  // outside a block or a capped cylinder the particle meets one convex solid: its faces,
  // edges, corners and rims together (LAMMPS's surface_exterior: one contact)
  if (!inside && (shape == "block" || shape == "cylinder")) {
    WallSurface solid;
    if (shape == "block") {
      solid.shape = WallShape::Box;
      solid.center = Vec3::Zero();
    } else {
      solid = found_faces.front().second;    // the side (iwall 2 sorts after the caps)
      for (const auto &face : found_faces)
        if (face.second.shape == WallShape::Cylinder) solid = face.second;
    }
    for (const auto &face : found_faces) {
      const WallSurface &w = face.second;
      if (w.shape != WallShape::Plane) continue;
      // a face's plane w.normal.x = w.offset, the normal along one coordinate, out of the
      // solid
      int d = 0;
      while (w.normal[d] == 0.0) d++;
      const bool upper = w.normal[d] > 0.0;
      const double at = w.offset / w.normal[d];
      if (shape == "block") {
        (upper ? solid.upper : solid.lower)[d] = at;
      } else {
        const double along = at - solid.center[d];    // the axis is coordinate d
        (upper ? solid.cap_hi : solid.cap_lo) = along;
      }
    }
    return {solid};
  }
  std::vector<WallSurface> walls_found;
  for (const auto &face : found_faces) walls_found.push_back(face.second);
  if (walls_found.empty())
    error->all(FLERR, "Fix wall/gran/region/ellipsoid: region {} has no closed face", region_id);
  return walls_found;
}
