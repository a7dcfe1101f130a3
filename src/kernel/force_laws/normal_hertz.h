/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws, normal model "hertz kn K" (the paper's law):

     F_n = kn xi^(3/2) + K xi^(1/2) dxi/dt

   kn and K are given per type pair; they do not depend on the curvature or the masses.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_NORMAL_HERTZ_H
#define ELLIPSOID_DEP_NORMAL_HERTZ_H

#include "force_law_model.h"
#include "hertz_elastic.h"

namespace EllipsoidDep {

struct HertzNormal : HertzElastic<HertzNormal> {
  static constexpr const char *NAME = "hertz";
  double kn = 0.0;         // stiffness
  double damping = 0.0;    // K

  using Row = ParameterRow<HertzNormal>;
  static constexpr std::array ROWS{Row{"kn", &HertzNormal::kn, POSITIVE, Mix::Geometric},
                                   Row{"K", &HertzNormal::damping, NON_NEGATIVE, Mix::Geometric}};

  double stiffness(double /*effective_radius*/) const { return kn; }
  double damping_coefficient(double /*effective_radius*/, double sqrt_overlap,
                             double /*effective_mass*/) const
  {
    return damping * sqrt_overlap;
  }
};

}    // namespace EllipsoidDep

#endif
