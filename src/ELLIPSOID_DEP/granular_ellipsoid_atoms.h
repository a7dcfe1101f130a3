/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: read access to the ellipsoid bonus data of atoms (semi-axes, quaternion,
   principal inertia, angular velocity, the kernel's Ellipsoid) for atom_style ellipsoid
   and atom_style ellipsoid superellipsoid alike. Shared by the pair style, the fixes and
   the computes. EllipsoidAtomsWriter adds the one write a creating fix needs.
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

 protected:
  double *stored_quat(int i) const;    // the bonus entry behind quat(i)
};

// write access for a fix that creates ellipsoid atoms
class EllipsoidAtomsWriter : public EllipsoidAtoms {
 public:
  using EllipsoidAtoms::EllipsoidAtoms;
  // gives atom i (whose rmass is set: the superellipsoid style derives its inertia from it)
  // semi-axes along its body axes and its orientation (w, x, y, z), body -> box
  void set_ellipsoid(int i, const double *semi_axes, const double *quat);
};

}    // namespace LAMMPS_NS

#endif
