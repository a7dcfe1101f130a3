/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: ellipsoid-cylinder wall contact (see ellipsoid_cylinder_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_cylinder_contact.h"

#include "ellipsoid_point_extremum.h"

namespace EllipsoidDep {

ContactGeometry ellipsoid_cylinder_contact(const Ellipsoid &e, const Vec3 &axis_point,
                                           const Vec3 &axis, double radius, bool inside)
{
  ContactGeometry g;
  g.status = Status::Degenerate;
  if (!valid(e) || !finite3(axis_point) || !finite3(axis) || !(axis.norm() > 0.0) ||
      !(radius > 0.0) || !std::isfinite(radius))
    return g;
  const Vec3 u = axis.normalized();
  // an orthonormal basis of the plane normal to the axis
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) = u.unitOrthogonal();
  basis.col(1) = u.cross(basis.col(0));
  // the projected ellipse: its principal frame, squared semi-axes, and the axis point in it
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> projection(
      basis.transpose() * e.inverse_form * basis);
  const Eigen::Matrix<double, 3, 2> frame = basis * projection.eigenvectors();
  const Eigen::Vector2d a2 = projection.eigenvalues();
  if (!(a2.minCoeff() > 0.0)) return g;
  const Eigen::Vector2d x = frame.transpose() * (axis_point - e.center);
  SurfaceExtremum<2> extremum;
  if (inside) {
    extremum = farthest_surface_point<2>(a2, x);
  } else {
    if (x.cwiseQuotient(a2.cwiseSqrt()).squaredNorm() <= 1.0) return g;
    extremum = nearest_surface_point<2>(a2, x);
  }
  const double distance = extremum.distance;
  if (!(distance > 0.0)) return g;
  const Eigen::Vector2d radial = (extremum.point - x) / distance;    // from the axis outwards
  const Vec3 m = frame * (inside ? radial : Eigen::Vector2d(-radial));
  const Vec3 mm = e.inverse_form * m;
  const Vec3 p = e.center + mm / std::sqrt(m.dot(mm));    // support point along m
  g.normal = m;
  g.overlap = inside ? distance - radius : radius - distance;
  g.point_a = p;
  g.point_b = p - g.overlap * m;
  g.point = 0.5 * (g.point_a + g.point_b);
  g.effective_radius =
      wall_effective_radius(gaussian_radius(e, m), inside ? -2.0 * radius : 2.0 * radius);
  g.status = surface_status(extremum.converged, g.overlap);
  return g;
}

}    // namespace EllipsoidDep
