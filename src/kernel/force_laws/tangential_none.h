/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws, tangential model "tangential none" (the default): F_t = 0.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_TANGENTIAL_NONE_H
#define ELLIPSOID_DEP_TANGENTIAL_NONE_H

#include "force_law_model.h"

namespace EllipsoidDep {

struct NoTangential {
  static constexpr const char *NAME = "none";
  static constexpr std::array<ParameterRow<NoTangential>, 0> ROWS{};
  static constexpr int HISTORY_SIZE = 0;

  double damping_coefficient(double /*normal_force*/, double /*normal_damping*/) const
  {
    return 0.0;
  }

  void add_force(const Vec3 & /*normal*/, const Vec3 & /*v_tangent*/, double /*fn_friction*/,
                 double /*normal_damping*/, double /*dt*/, double * /*history*/,
                 Vec3 & /*force*/) const
  {
  }
};

}    // namespace EllipsoidDep

#endif
