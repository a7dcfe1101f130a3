/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: named material parameter sets for hertz/material.
   Read from potentials/ellipsoid_dep.materials (found through LAMMPS_POTENTIALS). The file
   holds SI values; Young's modulus is converted to the simulation's force/area unit.
------------------------------------------------------------------------- */

#ifndef LMP_GRANULAR_MATERIALS_H
#define LMP_GRANULAR_MATERIALS_H

#include "ellipsoid_force_law.h"

#include <map>
#include <string>

namespace LAMMPS_NS {
class LAMMPS;

// File searched for names given to hertz/material instead of numbers.
constexpr const char *MATERIALS_FILE = "ellipsoid_dep.materials";

// The materials file, read once: rank 0 reads and parses it, one broadcast hands the
// numbers to every rank (construct it on every rank). A missing file is an empty table.
class MaterialTable {
 public:
  explicit MaterialTable(LAMMPS *lmp);
  // for parse_force_law: the material in the simulation's units, or why there is none
  EllipsoidDep::MaterialLookup lookup() const;

 private:
  std::map<std::string, EllipsoidDep::Material> materials;    // SI
  std::string unit_style;
  double pascal_per_unit;    // SI pressure of one force/area unit; 0 when undefined (lj)
};

// Whether command words name a material (only then the file is worth reading).
bool names_a_material(const std::vector<std::string> &words);
}    // namespace LAMMPS_NS

#endif
