/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws, tangential model "tangential history kt mu [xt X]": a spring on
   the tangential displacement s, optionally with a dashpot, and a Coulomb limit,

     s <- s turned onto the current tangent plane (at its length) + v_t dt
     F_t = -kt s - xt gamma_n v_t,  |F_t| <= mu max(F_n, 0);
     sliding: F_t at the limit, s = -(F_t + xt gamma_n v_t) / kt (the spring's share)

   gamma_n the normal model's damping coefficient at the contact (hertz: K xi^(1/2);
   hertz/material: the restitution damping): LAMMPS pair granular's tangential linear_history
   kt xt mu, whose dashpot is xt times the normal damping prefactor. xt 0 (the default): the
   spring alone, whose oscillations only the Coulomb slider and the normal dashpot, through
   the contacts' coupling, dissipate. The dashpot bounds the time step as a viscous law does
   (ForceLaw::tangential_damping_time).

   Its history, per contact: s (DISPLACEMENT, 3 doubles). s changes sign when i and j swap,
   as v_t (the velocity of i relative to j) does.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_TANGENTIAL_HISTORY_H
#define ELLIPSOID_DEP_TANGENTIAL_HISTORY_H

#include "force_law_model.h"

namespace EllipsoidDep {

struct HistoryTangential {
  static constexpr const char *NAME = "history";
  double kt = 0.0;    // spring
  double mu = 0.0;    // Coulomb coefficient
  double xt = 0.0;    // dashpot, in units of the normal damping coefficient

  using Row = ParameterRow<HistoryTangential>;
  static constexpr std::array ROWS{
      Row{"kt", &HistoryTangential::kt, POSITIVE, Mix::Geometric},
      Row{"mu", &HistoryTangential::mu, NON_NEGATIVE, Mix::Geometric},
      Row{"xt", &HistoryTangential::xt, NON_NEGATIVE, Mix::Geometric, nullptr, true}};
  static constexpr int DISPLACEMENT = 0;    // s, a Vec3
  static constexpr int HISTORY_SIZE = DISPLACEMENT + Vec3::SizeAtCompileTime;

  double damping_coefficient(double /*normal_force*/, double normal_damping) const
  {
    return xt * normal_damping;
  }

  void add_force(const Vec3 &n, const Vec3 &v_tangent, double fn_friction, double normal_damping,
                 double dt, double *history, Vec3 &force) const
  {
    // mu 0: the Coulomb limit cancels the whole tangential force, spring and dashpot, at any
    // displacement: a frictionless contact, whose displacement nothing reads (left at zero)
    if (mu == 0.0) return;
    Eigen::Map<Vec3> shear(history + DISPLACEMENT);
    // keep the stored displacement on the current tangent plane, at its length, as the
    // contact normal turns
    const double length = shear.norm();
    shear -= shear.dot(n) * n;
    const double projected = shear.norm();
    if (projected > 0.0) shear *= length / projected;
    shear += v_tangent * dt;
    const Vec3 dashpot = xt * normal_damping * v_tangent;
    Vec3 ft = -kt * shear - dashpot;
    const double limit = mu * fn_friction;
    const double ft_norm = ft.norm();
    if (ft_norm > limit) {
      ft *= limit / ft_norm;    // sliding: the spring follows the Coulomb force
      shear = -(ft + dashpot) / kt;
    }
    force += ft;
  }
};

}    // namespace EllipsoidDep

#endif
