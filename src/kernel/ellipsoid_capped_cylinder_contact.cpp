/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: ellipsoid outside a capped cylinder (see
   ellipsoid_capped_cylinder_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_capped_cylinder_contact.h"

#include "ellipsoid_cylinder_contact.h"
#include "ellipsoid_normal_patch.h"

namespace EllipsoidDep {

namespace {

  constexpr int SIDE_SAMPLES = 64;
  constexpr int RIM_ANGLE_SAMPLES = 64;
  constexpr int RIM_TILT_SAMPLES = 16;

}    // namespace

ContactGeometry ellipsoid_capped_cylinder_contact(const Ellipsoid &e, const Vec3 &axis_point,
                                                  const Vec3 &axis, double radius, double cap_lo,
                                                  double cap_hi)
{
  ContactGeometry g;
  g.status = Status::Degenerate;
  if (!valid(e) || !finite3(axis_point) || !finite3(axis) || !(axis.norm() > 0.0) ||
      !(radius > 0.0) || !std::isfinite(radius) || std::isnan(cap_lo) || std::isnan(cap_hi) ||
      cap_lo > cap_hi)
    return g;
  const Vec3 u = axis.normalized();
  const Vec3 e1 = u.unitOrthogonal(), e2 = u.cross(e1);
  const Mat3 &m = e.inverse_form;
  const Vec3 to_axis = axis_point - e.center;

  // the side: its smallest overlap over the radial directions
  double best = HUGE_VAL, wall_radius = 2.0 * radius;
  Vec3 best_n;
  bool converged = true;
  const ContactGeometry side = ellipsoid_cylinder_contact(e, axis_point, u, radius, false);
  if (side.status != Status::Degenerate) {
    best = side.overlap, best_n = -side.normal, converged = side.status != Status::NotConverged;
  } else {
    const NormalPatch radial{m, u, e1, e2, to_axis, radius};
    const IntervalMinimum around =
        minimise_on_interval(NormalArc{radial}, 0.0, 2.0 * PI, true, SIDE_SAMPLES);
    best = around.value, best_n = radial.normal(around.x, 0.5 * PI);
    converged = around.converged;
  }

  // the caps (s = cap_lo: outward normal -u; s = cap_hi: +u)
  const double caps[2] = {cap_lo, cap_hi}, outward[2] = {-1.0, 1.0};
  for (int k = 0; k < 2; k++) {
    if (!std::isfinite(caps[k])) continue;
    const Vec3 n = outward[k] * u;
    const double value = support(m, n) + n.dot(to_axis + caps[k] * u);
    if (value < best) best = value, best_n = n, converged = true, wall_radius = 0.0;
  }

  // the rims
  const double reach = e.bounding_radius +
      std::max(0.0, capped_cylinder_clearance(axis_point, u, radius, cap_lo, cap_hi, e.center));
  for (int k = 0; k < 2 && best > 0.0; k++) {
    if (!std::isfinite(caps[k])) continue;
    const Vec3 d = to_axis + caps[k] * u;    // the cap's centre from the particle's
    const double along = d.dot(u), across = (d - along * u).norm();
    if (std::hypot(along, across - radius) > reach + best) continue;
    const NormalPatch rim{m, outward[k] * u, e1, e2, d, radius};
    const PatchMinimum tilt = minimise_on_patch(rim, 2.0 * PI, RIM_ANGLE_SAMPLES, RIM_TILT_SAMPLES);
    if (tilt.value < best) {
      best = tilt.value, best_n = tilt.n;
      converged = tilt.converged, wall_radius = 2.0 * radius;
    }
  }

  // an overlap <= 0 along any direction separates the bodies, converged or not
  return solid_contact(e, best_n, best, wall_radius, converged || best <= 0.0);
}

double capped_cylinder_clearance(const Vec3 &axis_point, const Vec3 &axis, double radius,
                                 double cap_lo, double cap_hi, const Vec3 &x)
{
  const Vec3 d = x - axis_point;
  const double s = axis.dot(d);
  const double radial = (d - s * axis).norm() - radius, axial = std::max(cap_lo - s, s - cap_hi);
  if (radial > 0.0 || axial > 0.0) return std::hypot(std::max(radial, 0.0), std::max(axial, 0.0));
  return std::max(radial, axial);
}

}    // namespace EllipsoidDep
