/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: read access to ellipsoid atoms (see granular_ellipsoid_atoms.h)
------------------------------------------------------------------------- */

#include "granular_ellipsoid_atoms.h"

#include "error.h"

#include <algorithm>
#include <cmath>
#include <vector>

using namespace LAMMPS_NS;
using EllipsoidDep::Vec3;

EllipsoidAtoms::EllipsoidAtoms(Atom *atom_in) :
    atom(atom_in), avec(dynamic_cast<AtomVecEllipsoid *>(atom_in->style_match("ellipsoid"))),
    super(atom_in->superellipsoid_flag != 0)
{
}

void EllipsoidAtoms::require_granular_style(LAMMPS *lmp, const char *who)
{
  if (!lmp->atom->ellipsoid_flag) lmp->error->all(FLERR, "{} requires atom_style ellipsoid", who);
  if (!lmp->atom->rmass_flag || !lmp->atom->angmom_flag || !lmp->atom->torque_flag)
    lmp->error->all(FLERR, "{} requires per-atom mass, angmom and torque", who);
}

void EllipsoidAtoms::require_shapes(LAMMPS *lmp, const char *who, int n, int groupbit) const
{
  for (int i = 0; i < n; i++)
    if ((groupbit == 0 || (atom->mask[i] & groupbit)) && !has_shape(i))
      missing_shape(lmp, who, i, groupbit);
}

// error->one: only the rank holding the atom knows; it names the atom, which a reduction
// would lose
void EllipsoidAtoms::missing_shape(LAMMPS *lmp, const char *who, int i, int groupbit) const
{
  lmp->error->one(FLERR,
                  "{} requires every atom{} to be an ellipsoid: atom {} has no shape (set ... "
                  "shape; atoms inserted during a run need one too, as fix pour/ellipsoid "
                  "gives them)",
                  who, groupbit ? " of its group" : "", atom->tag[i]);
}

EllipsoidDep::Vec3 EllipsoidAtoms::omega(int i, const EllipsoidDep::Mat3 &rotation) const
{
  // as MathExtra::mq_to_omega, with the rotation the shape was built from
  return rotation * principal_omega(i, rotation.transpose() * angmom(i));
}

EllipsoidDep::Vec3 EllipsoidAtoms::principal_omega(int i, Vec3 body) const
{
  double moments[3];
  inertia(i, moments);
  for (int k = 0; k < 3; k++) body[k] = moments[k] == 0.0 ? 0.0 : body[k] / moments[k];
  return body;
}

EllipsoidDep::Ellipsoid EllipsoidAtoms::ellipsoid(int i) const
{
  const double *s = shape(i);
  return EllipsoidDep::make_particle(Vec3(atom->x[i][0], atom->x[i][1], atom->x[i][2]), quat(i),
                                     Vec3(s[0], s[1], s[2]));
}

EllipsoidState EllipsoidAtoms::state(int i) const
{
  EllipsoidState s{ellipsoid(i), {}, {}, 0.0};
  add_motion(i, s);
  return s;
}

namespace {
// Whether a state s built from key holds for the bonus values (quaternion, semi-axes): they are
// equal bit for bit, or s is a valid sphere (built in the identity frame) of the same semi-axes
// and the quaternion is usable.
bool built_from(const EllipsoidState &s, const ShapeKey &key, const double *values)
{
  if (!key.valid) return false;
  if (std::memcmp(values, key.values, 7 * sizeof(double)) == 0) return true;
  if (!s.shape.sphere || !s.shape.finite) return false;
  if (std::memcmp(values + 4, key.values + 4, 3 * sizeof(double)) != 0) return false;
  return EllipsoidDep::usable_quaternion(values);
}
}    // namespace

void EllipsoidAtoms::update_state(int i, EllipsoidState &s, ShapeKey &key) const
{
  update_shape(i, s, key);
  add_omega(i, s);
}

void EllipsoidAtoms::update_shape(int i, EllipsoidState &s, ShapeKey &key) const
{
  double values[7];
  std::memcpy(values, quat(i), 4 * sizeof(double));
  std::memcpy(values + 4, shape(i), 3 * sizeof(double));
  const Vec3 center(atom->x[i][0], atom->x[i][1], atom->x[i][2]);
  if (built_from(s, key, values)) {
    // a valid key was built (and since then moved) with a finite centre, so finite holds
    // the validity of the shape alone; a non-finite centre invalidates the state and the key
    s.shape.center = center;
    if (!EllipsoidDep::finite3(center)) s.shape.finite = key.valid = false;
  } else {
    s.shape = ellipsoid(i);
    std::memcpy(key.values, values, sizeof(values));
    key.valid = EllipsoidDep::finite3(center);
  }
  add_translation(i, s);
}

bool EllipsoidAtoms::copy_state(int i, int k, const EllipsoidState &sk, const ShapeKey &kk,
                                EllipsoidState &s, ShapeKey &key) const
{
  const Vec3 center(atom->x[i][0], atom->x[i][1], atom->x[i][2]);
  if (!EllipsoidDep::finite3(center)) return false;
  double mi[3], mk[3];
  inertia(i, mi);
  inertia(k, mk);
  double values[7];
  std::memcpy(values, quat(i), 4 * sizeof(double));
  std::memcpy(values + 4, shape(i), 3 * sizeof(double));
  const bool same = built_from(sk, kk, values) &&
      std::memcmp(atom->v[i], atom->v[k], 3 * sizeof(double)) == 0 &&
      std::memcmp(atom->angmom[i], atom->angmom[k], 3 * sizeof(double)) == 0 &&
      std::memcmp(&atom->rmass[i], &atom->rmass[k], sizeof(double)) == 0 &&
      std::memcmp(mi, mk, sizeof(mi)) == 0;
  if (!same) return false;
  s = sk;
  s.shape.center = center;
  key = kk;
  return true;
}

void EllipsoidAtoms::add_motion(int i, EllipsoidState &s) const
{
  add_translation(i, s);
  add_omega(i, s);
}

void EllipsoidAtoms::add_translation(int i, EllipsoidState &s) const
{
  s.velocity = Vec3(atom->v[i][0], atom->v[i][1], atom->v[i][2]);
  s.mass = atom->rmass[i];
}

void EllipsoidAtomsWriter::set_ellipsoid(int i, const double *semi_axes, const double *quat)
{
  avec->set_shape(i, semi_axes[0], semi_axes[1], semi_axes[2]);
  std::memcpy(stored_quat(i), quat, 4 * sizeof(double));
}

namespace {
// the owned bonus entries of one bonus type in their owners' order (order_bonus_as_atoms)
template <class Bonus> void order_bonus(Bonus *bonus, int *ellipsoid, int nlocal)
{
  int next = 0;
  bool ordered = true;
  for (int i = 0; i < nlocal && ordered; i++)
    if (ellipsoid[i] >= 0) ordered = ellipsoid[i] == next++;
  if (ordered) return;
  std::vector<Bonus> owned;    // the owned entries are bonus[0, nlocal_bonus)
  owned.reserve(nlocal);
  for (int i = 0; i < nlocal; i++) {
    if (ellipsoid[i] < 0) continue;
    owned.push_back(bonus[ellipsoid[i]]);
    owned.back().ilocal = i;
    ellipsoid[i] = static_cast<int>(owned.size()) - 1;
  }
  std::copy(owned.begin(), owned.end(), bonus);
}
}    // namespace

void EllipsoidAtomsWriter::order_bonus_as_atoms()
{
  if (super)
    order_bonus(avec->bonus_super, atom->ellipsoid, atom->nlocal);
  else
    order_bonus(avec->bonus, atom->ellipsoid, atom->nlocal);
}
