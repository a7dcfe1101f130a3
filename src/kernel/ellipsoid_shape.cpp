/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: construction, volume and slab volume of an ellipsoid
   (see ellipsoid_shape.h for the conventions).
------------------------------------------------------------------------- */

#include "ellipsoid_shape.h"

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <utility>

namespace EllipsoidDep {

namespace {

  inline Mat3 rotation_of(const double quat[4])
  {
    Eigen::Quaterniond q(quat[0], quat[1], quat[2], quat[3]);
    Mat3 r = Mat3::Identity();
    if (usable_quaternion(quat)) {
      q.coeffs() /= q.norm();
      r = q.toRotationMatrix();
    } else {
      r.setConstant(std::numeric_limits<double>::quiet_NaN());    // flagged Degenerate later
    }
    return r;
  }

  // R diag(s^2) R^T = U U^T for the scaled columns U = R diag(s): entry (i, j) is the sum of
  // U_ik U_jk over k, and the same sum for (j, i), so both triangles agree bit for bit
  inline Mat3 rotated_diagonal(const Mat3 &r, const Vec3 &s)
  {
    const Mat3 u = r * s.asDiagonal();
    auto entry = [&u](int i, int j) {
      return u(i, 0) * u(j, 0) + u(i, 1) * u(j, 1) + u(i, 2) * u(j, 2);
    };
    Mat3 m;
    m(0, 0) = entry(0, 0);
    m(1, 1) = entry(1, 1);
    m(2, 2) = entry(2, 2);
    m(0, 1) = m(1, 0) = entry(0, 1);
    m(0, 2) = m(2, 0) = entry(0, 2);
    m(1, 2) = m(2, 1) = entry(1, 2);
    return m;
  }
}    // namespace

Mat4 Ellipsoid::homogeneous() const
{
  Mat4 h;
  const Vec3 qc = form * center;
  h.topLeftCorner<3, 3>() = form;
  h.topRightCorner<3, 1>() = -qc;
  h.bottomLeftCorner<1, 3>() = -qc.transpose();
  h(3, 3) = center.dot(qc) - 1.0;
  return h;
}

double Ellipsoid::volume() const
{
  return 4.0 / 3.0 * PI * semi_axes[0] * semi_axes[1] * semi_axes[2];
}

Ellipsoid make_ellipsoid(const Vec3 &center, const Mat3 &rotation, const Vec3 &semi_axes)
{
  Ellipsoid e;
  e.center = center;
  e.rotation = rotation;
  e.semi_axes = semi_axes;
  e.form = rotated_diagonal(rotation, semi_axes.cwiseInverse());
  e.inverse_form = rotated_diagonal(rotation, semi_axes);
  e.bounding_radius = bounding_radius_of(semi_axes);
  e.sphere = is_sphere(semi_axes);
  e.finite = finite3(center) && finite3(semi_axes) && semi_axes.minCoeff() > 0.0 &&
      e.form.allFinite() && e.inverse_form.allFinite();
  return e;
}

Mat3 quaternion_rotation(const double quat[4])
{
  return rotation_of(quat);
}

Ellipsoid make_ellipsoid(const Vec3 &center, const double quat[4], const Vec3 &semi_axes)
{
  const Mat3 r = rotation_of(quat);
  return make_ellipsoid(center, r, semi_axes);
}

double ellipsoid_slab_volume(const Ellipsoid &e, double zlo, double zhi)
{
  if (!valid(e) || !(zhi > zlo)) return 0.0;
  // z half-extent h = sqrt(M_zz); section area(z) = (3V/4h)(1 - ((z-cz)/h)^2)
  const double h = std::sqrt(e.inverse_form(2, 2));
  const double t1 = std::clamp((zlo - e.center[2]) / h, -1.0, 1.0);
  const double t2 = std::clamp((zhi - e.center[2]) / h, -1.0, 1.0);
  if (!(t2 > t1)) return 0.0;
  const double integral = (t2 - t1) - (t2 * t2 * t2 - t1 * t1 * t1) / 3.0;    // in [0, 4/3]
  return 0.75 * e.volume() * integral;
}

double rotational_compliance(double a, double b, double c)
{
  // In the body frame I_k = m (s_j^2 + s_l^2) / 5 and q = sum_k 5 w_k^2 / (s_j^2 + s_l^2), w =
  // r x t. Each w_k^2 <= r_j^2 + r_l^2 <= max(s_j, s_l)^2 (r on the surface, |t| = 1), and
  // sum_k w_k^2 <= |r|^2 <= max(s)^2: filling the largest weights first bounds q.
  const double s2[3] = {a * a, b * b, c * c};
  std::array<std::pair<double, double>, 3> axes;    // (weight, cap) per axis of rotation
  for (int k = 0; k < 3; k++) {
    const double sj = s2[(k + 1) % 3], sl = s2[(k + 2) % 3];
    axes[k] = {5.0 / (sj + sl), std::max(sj, sl)};
  }
  std::sort(axes.begin(), axes.end(), std::greater<>());
  double budget = std::max(s2[0], std::max(s2[1], s2[2])), q = 0.0;
  for (const auto &[weight, cap] : axes) {
    const double take = std::min(cap, budget);
    q += weight * take;
    budget -= take;
  }
  return q;
}

}    // namespace EllipsoidDep
