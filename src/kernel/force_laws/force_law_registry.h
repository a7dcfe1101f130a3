/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws: the models of each family. Add a model here: its header (see
   force_law_model.h for what it declares) and its type at the end of its family's list.

   A model's place in its list is its code in restart files, and the restart record holds
   the parameters of every model of a family in list order, then the optional rows
   (ellipsoid_force_law_table.cpp): append, never reorder or remove, or old restart files
   misread. The pair reads a record of an earlier version when it is the start of this one's
   (its APPENDED_LAW_VALUES): a new optional row keeps that, a new model's rows (now before the
   optional rows) do not. The first model of a list is a law's default.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_FORCE_LAW_REGISTRY_H
#define ELLIPSOID_DEP_FORCE_LAW_REGISTRY_H

#include "normal_hertz.h"
#include "normal_hertz_material.h"
#include "rolling_constant.h"
#include "rolling_none.h"
#include "rolling_sds.h"
#include "tangential_history.h"
#include "tangential_none.h"
#include "tangential_viscous.h"

#include <variant>

namespace EllipsoidDep {

using NormalModel = std::variant<HertzNormal, HertzMaterialNormal>;
using TangentialModel = std::variant<NoTangential, ViscousTangential, HistoryTangential>;
using RollingModel = std::variant<NoRolling, ConstantRolling, SdsRolling>;

}    // namespace EllipsoidDep

#endif
