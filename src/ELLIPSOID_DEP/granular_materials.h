/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: named material parameter sets for hertz/material.
   Read from potentials/ellipsoid_dep.materials (found through LAMMPS_POTENTIALS).
------------------------------------------------------------------------- */

#ifndef LMP_GRANULAR_MATERIALS_H
#define LMP_GRANULAR_MATERIALS_H

#include "ellipsoid_force_law.h"

namespace LAMMPS_NS {
class LAMMPS;

// File searched for names given to hertz/material instead of numbers.
constexpr const char *MATERIALS_FILE = "ellipsoid_dep.materials";

// A lookup for parse_force_law: rank 0 reads the file once and broadcasts it; unknown
// names and a missing file make the lookup answer false (the caller reports the name).
EllipsoidDep::MaterialLookup material_lookup(LAMMPS *lmp);
}    // namespace LAMMPS_NS

#endif
