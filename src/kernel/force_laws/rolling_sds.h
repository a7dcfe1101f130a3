/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws, rolling model "rolling sds k_r gamma_r mu_r": a spring, a dashpot
   and a slider on the relative rolling (LAMMPS pair granular's `rolling sds`, Luding 2008),
   as a torque on the rolling angle,

     theta <- theta turned onto the current tangent plane (at its length) + w_roll dt
     M_r = -R*^2 (k_r theta + gamma_r w_roll),  |M_r| <= mu_r R* max(F_n, 0)   on i (-M_r on j)
     rolling on the slider: M_r at the limit, theta = -(M_r / R*^2 + gamma_r w_roll) / k_r

   w_roll the part of omega_i - omega_j perpendicular to the normal. LAMMPS's spring acts on
   the rolling displacement R* (w_roll x n) dt with the force arm R*: the same torque, so its
   coefficients carry over unchanged. Unlike `rolling constant` the torque is continuous in
   the motion: it vanishes with w_roll and theta, so round-off stays round-off at rest.

   Its history, per contact: theta (ANGLE, 3 doubles). theta changes sign when i and j swap,
   as w_roll does.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ROLLING_SDS_H
#define ELLIPSOID_DEP_ROLLING_SDS_H

#include "force_law_model.h"

namespace EllipsoidDep {

struct SdsRolling {
  static constexpr const char *NAME = "sds";
  double k_roll = 0.0, gamma_roll = 0.0, mu_roll = 0.0;

  using Row = ParameterRow<SdsRolling>;
  static constexpr std::array ROWS{
      Row{"k_r", &SdsRolling::k_roll, NON_NEGATIVE, Mix::Geometric},
      Row{"gamma_r", &SdsRolling::gamma_roll, NON_NEGATIVE, Mix::Geometric},
      Row{"mu_r", &SdsRolling::mu_roll, NON_NEGATIVE, Mix::Geometric}};
  static constexpr int ANGLE = 0;    // theta, a Vec3
  static constexpr int HISTORY_SIZE = ANGLE + Vec3::SizeAtCompileTime;

  void add_torque(const Vec3 &n, const ContactMotion &motion, double effective_radius,
                  double fn_friction, double dt, double *history, ContactForce &out) const
  {
    Eigen::Map<Vec3> angle(history + ANGLE);
    const Vec3 omega_rel = motion.omega_i - motion.omega_j;
    const Vec3 omega_roll = omega_rel - omega_rel.dot(n) * n;
    // keep the stored angle on the current tangent plane, at its length, as the normal turns
    const double length = angle.norm();
    angle -= angle.dot(n) * n;
    const double projected = angle.norm();
    if (projected > 0.0) angle *= length / projected;
    angle += omega_roll * dt;
    const double arm2 = effective_radius * effective_radius;
    Vec3 torque = -arm2 * (k_roll * angle + gamma_roll * omega_roll);
    const double limit = mu_roll * effective_radius * fn_friction, size = torque.norm();
    if (size > limit) {
      torque *= size > 0.0 ? limit / size : 0.0;
      // on the slider: the spring holds what the limit leaves after the dashpot (a rigid
      // spring, k_r 0, keeps no angle)
      angle = k_roll > 0.0 ? Vec3(-(torque / arm2 + gamma_roll * omega_roll) / k_roll)
                           : Vec3::Zero();
    }
    out.torque_i += torque;
    out.torque_j -= torque;
  }
};

}    // namespace EllipsoidDep

#endif
