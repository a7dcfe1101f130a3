/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: ellipsoid-sphere wall contact (see ellipsoid_sphere_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_sphere_contact.h"

#include "ellipsoid_point_extremum.h"

namespace EllipsoidDep {

ContactGeometry ellipsoid_sphere_contact(const Ellipsoid &e, const Vec3 &center, double radius,
                                         bool inside)
{
  ContactGeometry g;
  g.status = Status::Degenerate;
  if (!valid(e) || !finite3(center) || !(radius > 0.0) || !std::isfinite(radius)) return g;
  // the ellipsoid's principal frame, the sphere's centre in it
  const Vec3 a2 = e.semi_axes.cwiseProduct(e.semi_axes);
  const Vec3 x = e.rotation.transpose() * (center - e.center);
  SurfaceExtremum<3> extremum;
  if (inside) {
    extremum = farthest_surface_point<3>(a2, x);
  } else {
    if (x.cwiseQuotient(e.semi_axes).squaredNorm() <= 1.0) return g;
    extremum = nearest_surface_point<3>(a2, x);
  }
  const Vec3 p = e.center + e.rotation * extremum.point;
  const double distance = extremum.distance;
  if (!(distance > 0.0)) return g;
  const Vec3 outward = (p - center) / distance;    // from the sphere's centre through p
  g.normal = inside ? outward : Vec3(-outward);
  g.overlap = inside ? distance - radius : radius - distance;
  g.point_a = p;
  g.point_b = center + radius * outward;
  g.point = 0.5 * (g.point_a + g.point_b);
  g.effective_radius =
      wall_effective_radius(gaussian_radius(e, g.normal), inside ? -radius : radius);
  g.status = surface_status(extremum.converged, g.overlap);
  return g;
}

}    // namespace EllipsoidDep
