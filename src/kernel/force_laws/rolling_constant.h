/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws, rolling model "rolling constant mu_r": a torque of constant size
   against relative rolling,

     M_r = -mu_r R* max(F_n, 0) w_roll / |w_roll|   on i (-M_r on j)

   w_roll the part of omega_i - omega_j perpendicular to the normal. No history. The torque is
   discontinuous at w_roll = 0: its full size switches on for any rolling speed, so at rest it
   points where round-off turns w_roll (two runs whose positions differ by 5e-16 differ in
   torque by 1e-2 of the largest after two steps). `rolling sds` is the continuous model.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ROLLING_CONSTANT_H
#define ELLIPSOID_DEP_ROLLING_CONSTANT_H

#include "force_law_model.h"

namespace EllipsoidDep {

// mu_r: its torque arm mu_r R* cannot exceed the contact's radius R* (beyond, one step's
// torque spins a particle at rest past what its orientation survives)
inline constexpr Range ROLLING_ARM = {0.0, 1.0, true, true};

struct ConstantRolling {
  static constexpr const char *NAME = "constant";
  double mu_roll = 0.0;

  using Row = ParameterRow<ConstantRolling>;
  static constexpr std::array ROWS{
      Row{"mu_r", &ConstantRolling::mu_roll, ROLLING_ARM, Mix::Geometric}};
  static constexpr int HISTORY_SIZE = 0;

  void add_torque(const Vec3 &n, const ContactMotion &motion, double effective_radius,
                  double fn_friction, double /*dt*/, double * /*history*/,
                  ContactForce &out) const
  {
    if (!(fn_friction > 0.0)) return;
    const Vec3 omega_rel = motion.omega_i - motion.omega_j;
    const Vec3 omega_roll = omega_rel - omega_rel.dot(n) * n;
    const double w = omega_roll.norm();
    if (w > 0.0) {
      const Vec3 torque = -mu_roll * effective_radius * fn_friction / w * omega_roll;
      out.torque_i += torque;
      out.torque_j -= torque;
    }
  }
};

}    // namespace EllipsoidDep

#endif
