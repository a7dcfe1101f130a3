/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: the wall shapes' dispatch (see ellipsoid_wall_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_wall_contact.h"

#include "ellipsoid_box_contact.h"
#include "ellipsoid_capped_cylinder_contact.h"
#include "ellipsoid_cone_contact.h"
#include "ellipsoid_cylinder_contact.h"
#include "ellipsoid_plane_contact.h"
#include "ellipsoid_rim_contact.h"
#include "ellipsoid_sphere_contact.h"

namespace EllipsoidDep {

namespace {

  // a side's radius at s along its axis
  double side_radius(const WallSurface &w, double s)
  {
    return w.shape == WallShape::Cone ? w.radius + w.slope * s : w.radius;
  }

  // the distance of x from the infinite side met from inside, normal to it (a cone's:
  // cos(alpha) = 1 / sqrt(1 + slope^2)), positive inside
  double side_clearance(const WallSurface &w, const Vec3 &x)
  {
    const Vec3 d = x - w.center;
    const double s = w.axis.dot(d);
    const double radial = side_radius(w, s) - (d - s * w.axis).norm();
    return w.shape == WallShape::Cone ? radial / std::sqrt(1.0 + w.slope * w.slope) : radial;
  }

  // the end of a finite side that x lies past (NAN: between the ends)
  double end_passed(const WallSurface &w, const Vec3 &x)
  {
    const double s = w.axis.dot(x - w.center);
    return s < w.cap_lo ? w.cap_lo : s > w.cap_hi ? w.cap_hi : NAN;
  }

  // the rim at s; beyond: the particle's centre lies past that end. The wall's contact
  // radius is LAMMPS's: the side's -2 rho (its segment clamped to the end), but a cylinder
  // met from beyond an open end takes surface_exterior's 2R radially outside it, flat within
  ContactGeometry rim(const Ellipsoid &e, const WallSurface &w, double s, bool beyond)
  {
    double wall_radius = -2.0 * side_radius(w, s);
    if (beyond && w.shape == WallShape::Cylinder)
      wall_radius = side_clearance(w, e.center) < 0.0 ? 2.0 * w.radius : 0.0;
    return ellipsoid_rim_contact(e, w.center + s * w.axis, w.axis, side_radius(w, s),
                                 wall_radius);
  }

  // a side's contact whose wall point lies past an end: that end's rim's instead
  ContactGeometry clamped(const Ellipsoid &e, const WallSurface &w, const ContactGeometry &g)
  {
    if (g.status == Status::Separated || g.status == Status::Degenerate) return g;
    const double end = end_passed(w, g.point_b);
    if (std::isnan(end)) return g;
    return rim(e, w, end, end == end_passed(w, e.center));
  }

  // a centre past an end and outside the infinite side meets that end's rim only
  bool rim_only(const Ellipsoid &e, const WallSurface &w)
  {
    return !std::isnan(end_passed(w, e.center)) && side_clearance(w, e.center) <= 0.0;
  }

  // a side met from inside, between its ends (ellipsoid_rim_contact.h): the infinite side's
  // contact while its wall point lies between them, else the rim of the end it passed
  ContactGeometry finite_side(const Ellipsoid &e, const WallSurface &w)
  {
    if (rim_only(e, w)) return rim(e, w, end_passed(w, e.center), true);
    return clamped(e, w,
                   w.shape == WallShape::Cone
                       ? ellipsoid_cone_contact(e, w.center, w.axis, w.radius, w.slope)
                       : ellipsoid_cylinder_contact(e, w.center, w.axis, w.radius, true));
  }

}    // namespace

double shaped_wall_clearance(const WallSurface &w, const Vec3 &x)
{
  switch (w.shape) {
    case WallShape::Plane:
      return wall_clearance(w, x);
    case WallShape::Sphere: {
      const double r = (x - w.center).norm();
      return w.inside ? w.radius - r : r - w.radius;
    }
    case WallShape::Cylinder:
      if (!w.inside)
        return capped_cylinder_clearance(w.center, w.axis, w.radius, w.cap_lo, w.cap_hi, x);
      [[fallthrough]];
    case WallShape::Cone: {
      // past an end and outside the side: the distance from that end's rim (on the side)
      const double side = side_clearance(w, x), end = end_passed(w, x);
      if (std::isnan(end) || side > 0.0) return side;
      const Vec3 d = x - w.center;
      const double s = w.axis.dot(d);
      return std::hypot((d - s * w.axis).norm() - side_radius(w, end), s - end);
    }
    case WallShape::Box:
      return box_clearance(w.center, w.frame, w.lower, w.upper, x);
  }
  return 0.0;
}

ContactGeometry wall_contact(const Ellipsoid &e, const WallSurface &w)
{
  switch (w.shape) {
    case WallShape::Plane:
      return ellipsoid_plane_contact(e, w.normal, w.offset);
    case WallShape::Sphere:
      return ellipsoid_sphere_contact(e, w.center, w.radius, w.inside);
    case WallShape::Cylinder:
      if (w.inside) return finite_side(e, w);
      if (std::isinf(w.cap_lo) && std::isinf(w.cap_hi))
        return ellipsoid_cylinder_contact(e, w.center, w.axis, w.radius, false);
      return ellipsoid_capped_cylinder_contact(e, w.center, w.axis, w.radius, w.cap_lo,
                                               w.cap_hi);
    case WallShape::Cone:
      return finite_side(e, w);
    case WallShape::Box:
      return ellipsoid_box_contact(e, w.center, w.frame, w.lower, w.upper);
  }
  ContactGeometry degenerate;
  degenerate.status = Status::Degenerate;
  return degenerate;
}

bool operator==(const WallSurface &a, const WallSurface &b)
{
  return a.shape == b.shape && a.normal == b.normal && a.offset == b.offset &&
      a.center == b.center && a.axis == b.axis && a.radius == b.radius && a.slope == b.slope &&
      a.inside == b.inside && a.cap_lo == b.cap_lo && a.cap_hi == b.cap_hi &&
      a.frame == b.frame && a.lower == b.lower && a.upper == b.upper;
}

bool several_contacts(const WallSurface &w)
{
  return w.inside && w.shape != WallShape::Plane && w.shape != WallShape::Box;
}

FaceContacts wall_contacts(const Ellipsoid &e, const WallSurface &w)
{
  FaceContacts found;
  ContactGeometry side[2];
  double neck = -HUGE_VAL;
  found.count = 1;
  if (!several_contacts(w) || (w.shape != WallShape::Sphere && rim_only(e, w))) {
    found.contact[0] = wall_contact(e, w);
    return found;
  }
  int count = 0;
  if (w.shape == WallShape::Cone) {
    count = concave_side_contacts(e, w.center, w.axis, w.radius, w.slope, side, neck);
    if (count == 1) {    // its one contact, found already
      found.contact[0] = clamped(e, w, side[0]);
      return found;
    }
  } else {
    // a second region only where the deepest point overlaps
    found.contact[0] = wall_contact(e, w);
    if (found.contact[0].status == Status::Separated ||
        found.contact[0].status == Status::Degenerate)
      return found;
    // a cylinder's side: the cone's profile of slope 0
    count = w.shape == WallShape::Sphere
        ? sphere_inside_contacts(e, w.center, w.radius, side, neck)
        : concave_side_contacts(e, w.center, w.axis, w.radius, 0.0, side, neck);
  }
  if (count < 2) {
    if (count == 0 && w.shape == WallShape::Cone) found.contact[0] = wall_contact(e, w);
    return found;
  }
  share_neck(side[0], side[1], neck);
  if (w.shape == WallShape::Sphere) {
    found.count = 2;
    found.contact[0] = side[0], found.contact[1] = side[1];
    return found;
  }
  // both past the same end: that rim is one contact
  const double end0 = end_passed(w, side[0].point_b), end1 = end_passed(w, side[1].point_b);
  const bool one_rim = side[0].overlap > 0.0 && side[1].overlap > 0.0 && end0 == end1;
  found.count = one_rim ? 1 : 2;
  for (int k = 0; k < found.count; k++) found.contact[k] = clamped(e, w, side[k]);
  return found;
}

void share_neck(ContactGeometry &deeper, ContactGeometry &other, double neck)
{
  if (!(neck > 0.0)) return;
  const double excess_deeper = deeper.overlap - neck, excess_other = other.overlap - neck;
  const double share = excess_deeper > 0.0 ? std::min(1.0, excess_other / excess_deeper) : 1.0;
  auto lower = [](ContactGeometry &g, double by) {
    g.overlap -= by;
    g.point_b = g.point_a - g.overlap * g.normal;
    g.point = 0.5 * (g.point_a + g.point_b);
    if (g.status != Status::NotConverged) g.status = surface_status(true, g.overlap);
  };
  lower(deeper, neck * share);
  lower(other, neck);
}

bool wall_clear(const Ellipsoid &e, const WallSurface &w)
{
  const double clearance = wall_clearance(w, e.center);
  if (clearance > e.bounding_radius) return true;
  if (!(clearance > 0.0)) return false;    // the centre is beyond the surface
  const ContactGeometry g = wall_contact(e, w);
  return g.status == Status::Separated && g.overlap < 0.0;
}

}    // namespace EllipsoidDep
