/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: fix damping/cundall/ellipsoid, Cundall's local damping for ellipsoids: LAMMPS's
   fix damping/cundall (which needs atom attribute omega, so refuses atom_style ellipsoid) with
   the angular velocity from the angular momentum. A settling aid: each force and torque
   component is scaled by 1 - gamma sign(component x velocity component), which takes out a
   fixed share of the force per cycle at any frequency and vanishes with the forces, so a bed
   settles without a time-step bound; it is not physics: switch it off before measuring (see
   doc/fix_damping_cundall_ellipsoid.rst).
------------------------------------------------------------------------- */

#ifndef LMP_FIX_DAMPING_CUNDALL_ELLIPSOID_H
#define LMP_FIX_DAMPING_CUNDALL_ELLIPSOID_H

#include "fix.h"

namespace LAMMPS_NS {

class FixDampingCundallEllipsoid : public Fix {
 public:
  FixDampingCundallEllipsoid(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void min_setup(int) override;
  void post_force(int) override;
  void min_post_force(int) override;

 private:
  double gamma_linear, gamma_angular;
};

}    // namespace LAMMPS_NS

#endif
