/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: read access to ellipsoid atoms for every style of the package, for
   atom_style ellipsoid and atom_style ellipsoid superellipsoid alike: the bonus data
   (semi-axes, quaternion, principal inertia), the per-atom state a contact needs (the
   kernel's Ellipsoid, velocity, angular velocity, mass), the motion at a contact built from
   two such states (or one state and a resting wall), and the atom-style checks.
   EllipsoidAtomsWriter adds the one write a creating fix needs.
------------------------------------------------------------------------- */

#ifndef LMP_GRANULAR_ELLIPSOID_ATOMS_H
#define LMP_GRANULAR_ELLIPSOID_ATOMS_H

#include "atom.h"
#include "atom_vec_ellipsoid.h"

#include "ellipsoid_force_law.h"
#include "ellipsoid_kernel.h"

#include <cstring>

namespace LAMMPS_NS {

// What one atom brings to a contact.
struct EllipsoidState {
  EllipsoidDep::Ellipsoid shape;
  EllipsoidDep::Vec3 velocity;
  EllipsoidDep::Vec3 omega;    // angular velocity, box frame
  double mass;
};

// The bonus values an atom's shape matrices are built from. Equal keys (bit for bit) give
// identical matrices, so a state whose key is unchanged keeps them and only moves its centre.
struct ShapeKey {
  double values[7] = {};    // quaternion (w, x, y, z), semi-axes
  bool valid = false;       // false: never built, or built from a non-finite centre
};

class EllipsoidAtoms {
 public:
  explicit EllipsoidAtoms(Atom *atom);

  // ERROR naming who ("Pair granular/ellipsoid") unless the atom style is ellipsoid with
  // per-atom mass, angular momentum and torque
  static void require_granular_style(LAMMPS *lmp, const char *who);
  // ERROR naming who unless every atom in [0, n) (of the group of groupbit; 0: every atom)
  // has a shape: n = nlocal, or nlocal + nghost where ghosts are read (a ghost's ID is its
  // owner's). missing_shape() is the ERROR for atom i, for loops that check atoms themselves
  void require_shapes(LAMMPS *lmp, const char *who, int n, int groupbit = 0) const;
  [[noreturn]] void missing_shape(LAMMPS *lmp, const char *who, int i, int groupbit = 0) const;

  bool has_shape(int i) const { return atom->ellipsoid[i] >= 0; }    // carries bonus data
  const double *shape(int i) const;      // semi-axes along the body axes
  const double *quat(int i) const;       // (w, x, y, z), body -> box
  double bounding_radius(int i) const    // largest semi-axis
  {
    const double *s = shape(i);
    return EllipsoidDep::bounding_radius_of(EllipsoidDep::Vec3(s[0], s[1], s[2]));
  }
  bool sphere(int i) const    // semi-axes equal (EllipsoidDep::is_sphere)
  {
    const double *s = shape(i);
    return EllipsoidDep::is_sphere(EllipsoidDep::Vec3(s[0], s[1], s[2]));
  }
  // a superellipsoid with block exponents above 2 (ignored by this package's contacts, read by
  // other styles)
  bool blocky(int i) const
  {
    return super && avec->bonus_super[atom->ellipsoid[i]].type != AtomVecEllipsoid::ELLIPSOID;
  }
  void inertia(int i, double *moments) const;    // principal moments (body frame)
  // angular velocity (box frame) from the angular momentum, rotation: body -> box of atom i
  EllipsoidDep::Vec3 omega(int i, const EllipsoidDep::Mat3 &rotation) const;
  // angular velocity along atom i's principal axes from its angular momentum there
  EllipsoidDep::Vec3 principal_omega(int i, EllipsoidDep::Vec3 body) const;
  EllipsoidDep::Vec3 angmom(int i) const
  {
    return EllipsoidDep::Vec3(atom->angmom[i][0], atom->angmom[i][1], atom->angmom[i][2]);
  }
  // atom i's ellipsoid by EllipsoidDep::make_particle (a sphere in the identity frame)
  EllipsoidDep::Ellipsoid ellipsoid(int i) const;
  EllipsoidState state(int i) const;
  // state(i) into s, rebuilding the shape matrices only when key (that of the last build of
  // s) differs from atom i's quaternion and semi-axes: atoms that do not rotate skip them
  void update_state(int i, EllipsoidState &s, ShapeKey &key) const;
  // update_state without the angular velocity (s.omega left stale), for a caller that needs it
  // only at contacts: add_omega(i, s) then gives it, bit for bit update_state's
  void update_shape(int i, EllipsoidState &s, ShapeKey &key) const;
  void add_omega(int i, EllipsoidState &s) const
  {
    // a valid sphere's state is in the identity frame (make_particle): omega() in that frame
    s.omega = s.shape.sphere && s.shape.finite ? principal_omega(i, angmom(i))
                                               : omega(i, s.shape.rotation);
  }
  // state(i) into s as a copy of atom k's state sk (key kk) moved to i's centre, when i and k
  // carry the same values bit for bit (bonus, velocity, angular momentum, mass, inertia), as a
  // periodic image does: identical to update_state(i, s, key) then (s.omega is sk's, stale
  // when sk's is). false (s untouched) if not
  bool copy_state(int i, int k, const EllipsoidState &sk, const ShapeKey &kk, EllipsoidState &s,
                  ShapeKey &key) const;
  // velocity, angular velocity and mass of state, whose shape must be atom i's
  void add_motion(int i, EllipsoidState &state) const;
  // add_motion without the angular velocity
  void add_translation(int i, EllipsoidState &state) const;

  Atom *atom;
  AtomVecEllipsoid *avec;
  bool super;    // atom_style ellipsoid superellipsoid (bonus_super)

 protected:
  double *stored_quat(int i) const;    // the bonus entry behind quat(i)
};

// the per-atom accessors are inline: the pair loop and the integrator call them per atom
inline const double *EllipsoidAtoms::shape(int i) const
{
  const int k = atom->ellipsoid[i];
  return super ? avec->bonus_super[k].shape : avec->bonus[k].shape;
}

inline double *EllipsoidAtoms::stored_quat(int i) const
{
  const int k = atom->ellipsoid[i];
  return super ? avec->bonus_super[k].quat : avec->bonus[k].quat;
}

inline const double *EllipsoidAtoms::quat(int i) const
{
  return stored_quat(i);
}

inline void EllipsoidAtoms::inertia(int i, double *moments) const
{
  if (super) {
    std::memcpy(moments, avec->bonus_super[atom->ellipsoid[i]].inertia, 3 * sizeof(double));
    return;
  }
  constexpr double INERTIA = 0.2;    // solid ellipsoid: I_x = m (b^2 + c^2) / 5
  const double *s = shape(i);
  const double m = atom->rmass[i];
  moments[0] = INERTIA * m * (s[1] * s[1] + s[2] * s[2]);
  moments[1] = INERTIA * m * (s[0] * s[0] + s[2] * s[2]);
  moments[2] = INERTIA * m * (s[0] * s[0] + s[1] * s[1]);
}

// write access for a fix that creates or rotates ellipsoid atoms
class EllipsoidAtomsWriter : public EllipsoidAtoms {
 public:
  using EllipsoidAtoms::EllipsoidAtoms;
  double *quat(int i) { return stored_quat(i); }    // (w, x, y, z), to be updated
  // gives atom i (whose rmass is set: the superellipsoid style derives its inertia from it)
  // semi-axes along its body axes and its orientation (w, x, y, z), body -> box
  void set_ellipsoid(int i, const double *semi_axes, const double *quat);
  // puts the owned atoms' bonus entries in the atoms' order (the ghosts' follow when borders
  // are next exchanged). LAMMPS's atom sort moves the atoms, not their bonus entries: after a
  // pour these stay in insertion order, and every read of a shape or quaternion by the pair,
  // the wall and the integrator goes to a random place once they outgrow the caches. No value
  // changes, only where it is stored.
  void order_bonus_as_atoms();
};

// Motion at the contact point x of atoms i and j. A frozen atom (fix freeze) is immovable:
// the effective mass is then the other atom's mass.
inline EllipsoidDep::ContactMotion contact_motion(const EllipsoidState &i, const EllipsoidState &j,
                                                  const EllipsoidDep::Vec3 &x, bool i_frozen,
                                                  bool j_frozen)
{
  EllipsoidDep::ContactMotion m;
  m.v_i = i.velocity;
  m.v_j = j.velocity;
  m.omega_i = i.omega;
  m.omega_j = j.omega;
  m.branch_i = x - i.shape.center;
  m.branch_j = x - j.shape.center;
  m.effective_mass = i.mass * j.mass / (i.mass + j.mass);
  if (i_frozen) m.effective_mass = j.mass;
  if (j_frozen) m.effective_mass = i.mass;
  return m;
}

// Motion at the contact point x of atom i with a wall (body j) translating at v_wall, without
// turning: effective mass m_i.
inline EllipsoidDep::ContactMotion wall_motion(const EllipsoidState &i, const EllipsoidDep::Vec3 &x,
                                               const EllipsoidDep::Vec3 &v_wall)
{
  EllipsoidDep::ContactMotion m;
  m.v_i = i.velocity;
  m.v_j = v_wall;
  m.omega_i = i.omega;
  m.branch_i = x - i.shape.center;
  m.effective_mass = i.mass;
  return m;
}

}    // namespace LAMMPS_NS

#endif
