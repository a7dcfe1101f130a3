/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws, tangential model "tangential history kt mu": a spring on the
   tangential displacement s with a Coulomb limit,

     s <- s turned onto the current tangent plane (at its length) + v_t dt
     F_t = -kt s,  |F_t| <= mu max(F_n, 0); sliding: F_t at the limit, s = -F_t / kt

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

  using Row = ParameterRow<HistoryTangential>;
  static constexpr std::array ROWS{Row{"kt", &HistoryTangential::kt, POSITIVE, Mix::Geometric},
                                   Row{"mu", &HistoryTangential::mu, NON_NEGATIVE, Mix::Geometric}};
  static constexpr int DISPLACEMENT = 0;    // s, a Vec3
  static constexpr int HISTORY_SIZE = DISPLACEMENT + Vec3::SizeAtCompileTime;

  double damping_coefficient(double /*normal_force*/) const { return 0.0; }    // no dashpot

  void add_force(const Vec3 &n, const Vec3 &v_tangent, double fn_friction, double dt,
                 double *history, Vec3 &force) const
  {
    Eigen::Map<Vec3> shear(history + DISPLACEMENT);
    // keep the stored displacement on the current tangent plane, at its length, as the
    // contact normal turns
    const double length = shear.norm();
    shear -= shear.dot(n) * n;
    const double projected = shear.norm();
    if (projected > 0.0) shear *= length / projected;
    shear += v_tangent * dt;
    Vec3 ft = -kt * shear;
    const double limit = mu * fn_friction;
    const double ft_norm = ft.norm();
    if (ft_norm > limit) {
      ft *= limit / ft_norm;    // sliding: the spring follows the Coulomb force
      shear = -ft / kt;
    }
    force += ft;
  }
};

}    // namespace EllipsoidDep

#endif
