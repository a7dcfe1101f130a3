/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: the wall shapes' dispatch (see ellipsoid_wall_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_wall_contact.h"

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
      const Vec3 d = x - w.center;
      const double r = (d - w.axis.dot(d) * w.axis).norm();
      return w.inside ? w.radius - r : r - w.radius;
    }
    case WallShape::Cone: {
      // the distance from the side, normal to it (cos(alpha) = 1 / sqrt(1 + slope^2))
      const Vec3 d = x - w.center;
      const double s = w.axis.dot(d);
      const double r = (d - s * w.axis).norm();
      return (w.radius + w.slope * s - r) / std::sqrt(1.0 + w.slope * w.slope);
    }
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
      return ellipsoid_cylinder_contact(e, w.center, w.axis, w.radius, w.inside);
    case WallShape::Cone:
      return ellipsoid_cone_contact(e, w.center, w.axis, w.radius, w.slope);
  }
  ContactGeometry degenerate;
  degenerate.status = Status::Degenerate;
  return degenerate;
}

}    // namespace EllipsoidDep
