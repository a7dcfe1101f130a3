/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: fix nve/ellipsoid
   Velocity Verlet for ellipsoids, as LAMMPS's nve/asphere (the same arithmetic, so an
   ellipsoid's trajectory is identical), except that a sphere is not rotated: its contacts do
   not depend on its orientation, so it skips the Richardson quaternion update, the most
   expensive part of a sphere's step. See doc/fix_nve_ellipsoid.rst.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_NVE_ELLIPSOID_H
#define LMP_FIX_NVE_ELLIPSOID_H

#include "fix_nve.h"

namespace LAMMPS_NS {

class FixNVEEllipsoid : public FixNVE {
 public:
  FixNVEEllipsoid(class LAMMPS *, int, char **);
  void init() override;
  void initial_integrate(int) override;
  void final_integrate() override;
};

}    // namespace LAMMPS_NS

#endif
