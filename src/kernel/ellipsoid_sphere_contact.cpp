/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: ellipsoid-sphere wall contact (see ellipsoid_sphere_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_sphere_contact.h"

#include "ellipsoid_point_extremum.h"

#include <algorithm>

namespace EllipsoidDep {

namespace {

  // the contact at the ellipsoid's surface point p
  ContactGeometry contact_at(const Ellipsoid &e, const Vec3 &center, double radius, bool inside,
                             const Vec3 &p, double distance, bool converged)
  {
    ContactGeometry g;
    const Vec3 outward = (p - center) / distance;    // from the sphere's centre through p
    g.normal = inside ? outward : Vec3(-outward);
    g.overlap = inside ? distance - radius : radius - distance;
    g.point_a = p;
    g.point_b = center + radius * outward;
    g.point = 0.5 * (g.point_a + g.point_b);
    g.effective_radius =
        wall_effective_radius(gaussian_radius(e, g.normal), inside ? -radius : radius);
    g.status = surface_status(converged, g.overlap);
    return g;
  }

  bool usable(const Ellipsoid &e, const Vec3 &center, double radius)
  {
    return valid(e) && finite3(center) && radius > 0.0 && std::isfinite(radius);
  }

}    // namespace

ContactGeometry ellipsoid_sphere_contact(const Ellipsoid &e, const Vec3 &center, double radius,
                                         bool inside)
{
  ContactGeometry g;
  g.status = Status::Degenerate;
  if (!usable(e, center, radius)) return g;
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
  return contact_at(e, center, radius, inside, p, distance, extremum.converged);
}

int sphere_inside_contacts(const Ellipsoid &e, const Vec3 &center, double radius,
                           ContactGeometry contacts[2], double &neck)
{
  if (!usable(e, center, radius)) return 0;
  const Vec3 a2 = e.semi_axes.cwiseProduct(e.semi_axes);
  const std::vector<StationaryPoint<3>> points =
      stationary_surface_points<3>(a2, e.rotation.transpose() * (center - e.center));
  std::vector<const StationaryPoint<3> *> maxima;
  double lowest = HUGE_VAL;
  for (const StationaryPoint<3> &s : points) {
    if (s.maximum) maxima.push_back(&s);
    lowest = std::min(lowest, s.distance);
  }
  std::sort(maxima.begin(), maxima.end(), [](const auto *a, const auto *b) {
    return a->distance > b->distance;
  });
  if (maxima.size() < 2 || maxima[0]->point == maxima[1]->point) return 0;
  // the neck: the highest stationary value that is neither a maximum nor the lowest (the
  // saddles one crosses from one maximum to the other)
  neck = -HUGE_VAL;
  for (const StationaryPoint<3> &s : points)
    if (!s.maximum && s.distance > lowest) neck = std::max(neck, s.distance - radius);
  for (int k = 0; k < 2; k++) {
    const StationaryPoint<3> &m = *maxima[k];
    if (!(m.distance > 0.0)) return 0;
    contacts[k] = contact_at(e, center, radius, true, e.center + e.rotation * m.point,
                             m.distance, m.converged);
  }
  return 2;
}

}    // namespace EllipsoidDep
