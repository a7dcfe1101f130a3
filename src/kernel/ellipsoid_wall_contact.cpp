/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: the wall shapes' dispatch (see ellipsoid_wall_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_wall_contact.h"

#include "ellipsoid_box_contact.h"
#include "ellipsoid_capped_cylinder_contact.h"
#include "ellipsoid_cone_contact.h"
#include "ellipsoid_cylinder_contact.h"
#include "ellipsoid_plane_contact.h"
#include "ellipsoid_sphere_contact.h"

namespace EllipsoidDep {

double wall_clearance(const WallSurface &w, const Vec3 &x)
{
  switch (w.shape) {
    case WallShape::Plane:
      return w.normal.dot(x) - w.offset;
    case WallShape::Sphere: {
      const double r = (x - w.center).norm();
      return w.inside ? w.radius - r : r - w.radius;
    }
    case WallShape::Cylinder: {
      if (!w.inside)
        return capped_cylinder_clearance(w.center, w.axis, w.radius, w.cap_lo, w.cap_hi, x);
      const Vec3 d = x - w.center;
      return w.radius - (d - w.axis.dot(d) * w.axis).norm();
    }
    case WallShape::Cone: {
      // the distance from the side, normal to it (cos(alpha) = 1 / sqrt(1 + slope^2))
      const Vec3 d = x - w.center;
      const double s = w.axis.dot(d);
      const double r = (d - s * w.axis).norm();
      return (w.radius + w.slope * s - r) / std::sqrt(1.0 + w.slope * w.slope);
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
      if (w.inside || (std::isinf(w.cap_lo) && std::isinf(w.cap_hi)))
        return ellipsoid_cylinder_contact(e, w.center, w.axis, w.radius, w.inside);
      return ellipsoid_capped_cylinder_contact(e, w.center, w.axis, w.radius, w.cap_lo,
                                               w.cap_hi);
    case WallShape::Cone:
      return ellipsoid_cone_contact(e, w.center, w.axis, w.radius, w.slope);
    case WallShape::Box:
      return ellipsoid_box_contact(e, w.center, w.frame, w.lower, w.upper);
  }
  ContactGeometry degenerate;
  degenerate.status = Status::Degenerate;
  return degenerate;
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
