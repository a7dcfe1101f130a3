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
const char *const SUPPORTED = "block, cylinder, sphere and plane";

}    // namespace

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
  if (shape != "block" && shape != "cylinder" && shape != "sphere" && shape != "plane")
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

  // a probe point inside the region's shape, off its centre and axes: a grid over the box
  // at irrational fractions, in the region's own frame
  double probe[3] = {0.0, 0.0, 0.0};
  bool found = false;
  for (int i = 0; i < 9 && !found; i++)
    for (int j = 0; j < 9 && !found; j++)
      for (int k = 0; k < 9 && !found; k++) {
        const int index[3] = {i, j, k};
        for (int d = 0; d < 3; d++)
          probe[d] = domain->boxlo[d] + (index[d] + 0.5 + 0.1 * M_SQRT2 * (d + 1)) / 9.0 *
                  domain->prd[d];
        region->inverse_transform(probe[0], probe[1], probe[2]);
        found = region->inside(probe[0], probe[1], probe[2]) != 0;
      }
  if (!found)
    error->all(FLERR, "Fix wall/gran/region/ellipsoid: region {}'s shape lies outside the box",
               region_id);
  const int ncontact = region->surface_interior(probe, PROBE_CUTOFF);

  std::vector<std::pair<int, WallSurface>> found_faces;
  for (int c = 0; c < ncontact; c++) {
    const Region::Contact &contact = region->contact[c];
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
      // outside a block or a cylinder, a face beyond the box holds nothing in it (its plane
      // would reach into the box)
      if (!inside && shape != "plane" && !within_box(w)) continue;
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
      }
    }
    found_faces.emplace_back(contact.iwall, w);
  }
  std::sort(found_faces.begin(), found_faces.end(),
            [](const auto &a, const auto &b) { return a.first < b.first; });

  // outside a shape with edges (two faces meeting inside the box), a particle touches edges
  // and corners that the face-by-face contact does not hold
  if (!inside) {
    int flat_dims = 0, curved = 0;
    bool dim_seen[3] = {false, false, false};
    for (const auto &face : found_faces) {
      const WallSurface &w = face.second;
      if (w.shape != WallShape::Plane) {
        curved++;
        continue;
      }
      for (int d = 0; d < 3; d++) {
        if (w.normal[d] == 0.0 || shape == "plane") continue;
        if (!dim_seen[d]) {
          dim_seen[d] = true;
          flat_dims++;
        }
      }
    }
    if (flat_dims + (curved > 0 ? 1 : 0) > 1)
      error->all(FLERR,
                 "Fix wall/gran/region/ellipsoid: region {} side out has faces that meet at "
                 "edges inside the box; outside a region only a sphere, a plane, a cylinder "
                 "without caps in the box and a block's faces normal to one axis are supported",
                 region_id);
  }
  std::vector<WallSurface> walls_found;
  for (const auto &face : found_faces) walls_found.push_back(face.second);
  if (walls_found.empty())
    error->all(FLERR, "Fix wall/gran/region/ellipsoid: region {} has no closed face", region_id);
  return walls_found;
}
