/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws, tangential model "tangential viscous mu" (the paper's
   F_t = mu F_n v_t, with the sign that opposes sliding):

     F_t = -mu max(F_n, 0) v_t

   v_t the tangential part of the velocity of i relative to j at the contact; mu in
   time/length: a viscous friction whose coefficient grows with the load. No history.
   Its damping coefficient mu F_n is largest at an impact's peak force: the time step must stay
   below the tangential damping time m_t / (mu F_n) there (ForceLaw::tangential_damping_time),
   or the explicit update turns the friction into a source of energy.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_TANGENTIAL_VISCOUS_H
#define ELLIPSOID_DEP_TANGENTIAL_VISCOUS_H

#include "force_law_model.h"

namespace EllipsoidDep {

struct ViscousTangential {
  static constexpr const char *NAME = "viscous";
  double mu = 0.0;

  using Row = ParameterRow<ViscousTangential>;
  static constexpr std::array ROWS{Row{"mu", &ViscousTangential::mu, NON_NEGATIVE, Mix::Geometric}};
  static constexpr int HISTORY_SIZE = 0;

  // dF_t / dv_t at the normal force F_n
  double damping_coefficient(double normal_force, double /*normal_damping*/) const
  {
    return mu * normal_force;
  }

  void add_force(const Vec3 & /*normal*/, const Vec3 &v_tangent, double fn_friction,
                 double /*normal_damping*/, double /*dt*/, double * /*history*/, Vec3 &force) const
  {
    force -= mu * fn_friction * v_tangent;
  }
};

}    // namespace EllipsoidDep

#endif
