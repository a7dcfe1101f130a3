/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws, rolling model "rolling none" (the default): no rolling torque.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ROLLING_NONE_H
#define ELLIPSOID_DEP_ROLLING_NONE_H

#include "force_law_model.h"

namespace EllipsoidDep {

struct NoRolling {
  static constexpr const char *NAME = "none";
  static constexpr std::array<ParameterRow<NoRolling>, 0> ROWS{};
  static constexpr int HISTORY_SIZE = 0;

  void add_torque(const Vec3 & /*normal*/, const ContactMotion & /*motion*/,
                  double /*effective_radius*/, double /*fn_friction*/, double /*dt*/,
                  double * /*history*/, ContactForce & /*out*/) const
  {
  }
};

}    // namespace EllipsoidDep

#endif
