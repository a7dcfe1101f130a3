/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: the samples of the contact computes (contact/histo, force/histo), one
   definition for both. A contact gives one sample per side whose particle is in the group
   (its partner may be any particle), counted once over ranks (ContactList owned sides): side
   i with the normal n (from i to j), side j with -n, each with the contact's normal force.
   With a slab, both sides of a contact whose contact point is in it (select point), or each
   side whose particle's centre is in it (select center).
------------------------------------------------------------------------- */

#ifndef LMP_GRANULAR_CONTACT_SAMPLES_H
#define LMP_GRANULAR_CONTACT_SAMPLES_H

#include "atom.h"
#include "error.h"
#include "granular_ellipsoid_contacts.h"
#include "granular_slab.h"

#include <cmath>
#include <cstring>

namespace LAMMPS_NS {

// The normal force of a contact, f_n = -F_i . n (F_i the total force on i, n the unit normal
// from i to j): positive when repulsive. The tangential force is perpendicular to n, so this
// is the force law's normal force (negative only while damping pulls during a fast release).
inline double contact_normal_force(const ContactList::Contact &c)
{
  const double len = std::sqrt(c.normal[0] * c.normal[0] + c.normal[1] * c.normal[1] +
                               c.normal[2] * c.normal[2]);
  if (!(len > 0.0)) return 0.0;
  return -(c.force[0] * c.normal[0] + c.force[1] * c.normal[1] + c.force[2] * c.normal[2]) / len;
}

// the value of the select keyword: false for point, true for center (ERROR naming the compute
// style otherwise)
inline bool parse_contact_select(LAMMPS *lmp, const char *name, const char *value)
{
  if (strcmp(value, "point") == 0) return false;
  if (strcmp(value, "center") != 0)
    lmp->error->all(FLERR, "Compute {} select must be 'point' or 'center'", name);
  return true;
}

struct ContactSampleFilter {
  int groupbit;
  SlabOption::Bounds slab;
  bool select_center;    // false: the contact point in the slab, true: the side's centre
};

// f(u, fn) for every sample: u the unit normal seen from the side's particle, fn the
// contact's normal force (contact_normal_force)
template <class F>
void for_each_contact_sample(const ContactList &contacts, LAMMPS *lmp, const char *who,
                             const ContactSampleFilter &filter, F f)
{
  const int *mask = lmp->atom->mask;
  double **x = lmp->atom->x;
  const double zlo = filter.slab.zlo, zhi = filter.slab.zhi;
  contacts.for_each_owned_side(lmp, who, [&](const ContactList::Contact &c, bool count_j) {
    const int i = c.i, j = c.j;
    const double len = std::sqrt(c.normal[0] * c.normal[0] + c.normal[1] * c.normal[1] +
                                 c.normal[2] * c.normal[2]);
    if (!(len > 0.0)) return;
    bool take_i = (mask[i] & filter.groupbit) != 0;
    bool take_j = count_j && (mask[j] & filter.groupbit);
    if (!take_i && !take_j) return;
    if (filter.slab.used) {
      if (filter.select_center) {
        take_i = take_i && x[i][2] >= zlo && x[i][2] < zhi;
        take_j = take_j && x[j][2] >= zlo && x[j][2] < zhi;
      } else {
        const bool in = c.point[2] >= zlo && c.point[2] < zhi;
        take_i = take_i && in;
        take_j = take_j && in;
      }
    }
    const double fn = contact_normal_force(c);
    const double n[3] = {c.normal[0] / len, c.normal[1] / len, c.normal[2] / len};
    if (take_i) f(n, fn);
    if (take_j) {
      const double m[3] = {-n[0], -n[1], -n[2]};
      f(m, fn);
    }
  });
}

}    // namespace LAMMPS_NS

#endif
