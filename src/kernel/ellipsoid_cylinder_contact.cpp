/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: ellipsoid-cylinder wall contact (see ellipsoid_cylinder_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_cylinder_contact.h"

#include "ellipsoid_point_extremum.h"

#include <algorithm>

namespace EllipsoidDep {

namespace {

  // the ellipse the ellipsoid projects onto in the plane normal to the axis: its principal
  // frame (3 x 2), squared semi-axes, and the axis point in it; false if degenerate
  struct Projection {
    Eigen::Matrix<double, 3, 2> frame;
    Eigen::Vector2d a2, x;
  };

  bool project(const Ellipsoid &e, const Vec3 &axis_point, const Vec3 &axis, double radius,
               Projection &out)
  {
    if (!valid(e) || !finite3(axis_point) || !finite3(axis) || !(axis.norm() > 0.0) ||
        !(radius > 0.0) || !std::isfinite(radius))
      return false;
    const Vec3 u = axis.normalized();
    // an orthonormal basis of the plane normal to the axis
    Eigen::Matrix<double, 3, 2> basis;
    basis.col(0) = u.unitOrthogonal();
    basis.col(1) = u.cross(basis.col(0));
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> projection(
        basis.transpose() * e.inverse_form * basis);
    out.frame = basis * projection.eigenvectors();
    out.a2 = projection.eigenvalues();
    if (!(out.a2.minCoeff() > 0.0)) return false;
    out.x = out.frame.transpose() * (axis_point - e.center);
    return true;
  }

  // the contact at the ellipse's point y, |y - x| = distance
  ContactGeometry contact_at(const Ellipsoid &e, const Projection &pr, double radius, bool inside,
                             const Eigen::Vector2d &y, double distance, bool converged)
  {
    ContactGeometry g;
    const Eigen::Vector2d radial = (y - pr.x) / distance;    // from the axis outwards
    const Vec3 m = pr.frame * (inside ? radial : Eigen::Vector2d(-radial));
    const Vec3 mm = e.inverse_form * m;
    const Vec3 p = e.center + mm / std::sqrt(m.dot(mm));    // support point along m
    g.normal = m;
    g.overlap = inside ? distance - radius : radius - distance;
    g.point_a = p;
    g.point_b = p - g.overlap * m;
    g.point = 0.5 * (g.point_a + g.point_b);
    g.effective_radius =
        wall_effective_radius(gaussian_radius(e, m), inside ? -2.0 * radius : 2.0 * radius);
    g.status = surface_status(converged, g.overlap);
    return g;
  }

}    // namespace

ContactGeometry ellipsoid_cylinder_contact(const Ellipsoid &e, const Vec3 &axis_point,
                                           const Vec3 &axis, double radius, bool inside)
{
  ContactGeometry g;
  g.status = Status::Degenerate;
  Projection pr;
  if (!project(e, axis_point, axis, radius, pr)) return g;
  SurfaceExtremum<2> extremum;
  if (inside) {
    extremum = farthest_surface_point<2>(pr.a2, pr.x);
  } else {
    if (pr.x.cwiseQuotient(pr.a2.cwiseSqrt()).squaredNorm() <= 1.0) return g;
    extremum = nearest_surface_point<2>(pr.a2, pr.x);
  }
  if (!(extremum.distance > 0.0)) return g;
  return contact_at(e, pr, radius, inside, extremum.point, extremum.distance, extremum.converged);
}

int cylinder_inside_contacts(const Ellipsoid &e, const Vec3 &axis_point, const Vec3 &axis,
                             double radius, ContactGeometry contacts[2], double &neck)
{
  Projection pr;
  if (!project(e, axis_point, axis, radius, pr)) return 0;
  const std::vector<StationaryPoint<2>> points = stationary_surface_points<2>(pr.a2, pr.x);
  std::vector<const StationaryPoint<2> *> maxima;
  double lowest = HUGE_VAL;
  for (const StationaryPoint<2> &s : points) {
    if (s.maximum) maxima.push_back(&s);
    lowest = std::min(lowest, s.distance);
  }
  std::sort(maxima.begin(), maxima.end(), [](const auto *a, const auto *b) {
    return a->distance > b->distance;
  });
  if (maxima.size() < 2 || maxima[0]->point == maxima[1]->point) return 0;
  // the neck: the higher minimum between the maxima (the lower is the nearest point)
  neck = -HUGE_VAL;
  for (const StationaryPoint<2> &s : points)
    if (!s.maximum && s.distance > lowest) neck = std::max(neck, s.distance - radius);
  for (int k = 0; k < 2; k++) {
    if (!(maxima[k]->distance > 0.0)) return 0;
    contacts[k] = contact_at(e, pr, radius, true, maxima[k]->point, maxima[k]->distance,
                             maxima[k]->converged);
  }
  return 2;
}

}    // namespace EllipsoidDep
