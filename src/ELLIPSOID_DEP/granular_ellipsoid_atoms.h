/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: read access to the ellipsoid bonus data of atoms (semi-axes, quaternion,
   principal inertia, angular velocity, the kernel's Ellipsoid) for atom_style ellipsoid
   and atom_style ellipsoid superellipsoid alike. Shared by the pair style, the fixes and
   the computes.
------------------------------------------------------------------------- */

#ifndef LMP_GRANULAR_ELLIPSOID_ATOMS_H
#define LMP_GRANULAR_ELLIPSOID_ATOMS_H

#include "ellipsoid_contact.h"

namespace LAMMPS_NS {
class Atom;
class AtomVecEllipsoid;

class EllipsoidAtoms {
 public:
  explicit EllipsoidAtoms(Atom *atom);

  bool has_shape(int i) const;                   // atom i carries ellipsoid bonus data
  const double *shape(int i) const;              // semi-axes along the body axes
  const double *quat(int i) const;               // (w, x, y, z), body -> box
  void inertia(int i, double *moments) const;    // principal moments (body frame)
  void omega(int i, double *w) const;            // angular velocity (box frame)
  EllipsoidDep::Ellipsoid ellipsoid(int i) const;

  Atom *atom;
  AtomVecEllipsoid *avec;
  bool super;    // atom_style ellipsoid superellipsoid (bonus_super)
};

}    // namespace LAMMPS_NS

#endif
