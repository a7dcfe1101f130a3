/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: compute contact/histo (doc/compute_contact_histo.rst)

   Global array, one row per bin of theta in [0, pi] (angle between a contact normal and +z):
     1 bin centre theta_k
     2 P_k = c_k / (C dOmega_k),  dOmega_k = 2 pi (cos theta_k,lo - cos theta_k,hi)
       (uniform distribution of directions: P = 1/(4 pi))
     3 c_k / C (fraction of the normals in the bin)
   Every contact contributes its normal seen from each of its particles in the group (n seen
   from i, -n seen from j); the partner may be any particle.

   Global vector (fabric tensor F = <n n^T> over the same samples):
     1-6 Fxx Fyy Fzz Fxy Fxz Fyz
     7   Fzz - (Fxx + Fyy)/2
     8   sqrt(3/2 F':F'),  F' = F - tr(F) I / 3
     9   number of samples C (twice the number of contacts without a slab)

   Arguments, array and slab handling: ComputeAngleHisto (compute_angle_histo.cpp).
------------------------------------------------------------------------- */

#include "compute_contact_histo.h"

#include "atom.h"
#include "error.h"

#include "granular_ellipsoid_contacts.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace {
const char WHO[] = "Compute contact/histo";
const char *const COLNAMES[ComputeContactHisto::NVALUES] = {
    "Fxx", "Fyy", "Fzz", "Fxy", "Fxz", "Fyz", "Fanis", "Fdev", "Nnormals"};
}    // namespace

/* ---------------------------------------------------------------------- */

ComputeContactHisto::ComputeContactHisto(LAMMPS *lmp, int narg, char **arg) :
    ComputeAngleHisto(lmp, narg, arg, "contact/histo", NVALUES, COLNAMES, 0), contacts(nullptr),
    select_center(0)
{
  parse_args(narg, arg);
}

/* ---------------------------------------------------------------------- */

bool ComputeContactHisto::parse_keyword(const char *key, const char *value)
{
  if (strcmp(key, "select") != 0) return false;
  if (strcmp(value, "point") == 0)
    select_center = 0;
  else if (strcmp(value, "center") == 0)
    select_center = 1;
  else
    error->all(FLERR, "Compute contact/histo select must be 'point' or 'center'");
  return true;
}

/* ---------------------------------------------------------------------- */

void ComputeContactHisto::init()
{
  contacts = ContactList::request(lmp, WHO);
  ComputeAngleHisto::init();
}

/* ---------------------------------------------------------------------- */

void ComputeContactHisto::prepare()
{
  ContactList::current(contacts, lmp, WHO);
}

/* ----------------------------------------------------------------------
   One sample per contact and owned side (ContactList): side i with normal n, side j with -n.
------------------------------------------------------------------------- */

void ComputeContactHisto::accumulate(double zlo, double zhi, bool use_slab)
{
  int *mask = atom->mask;
  double **x = atom->x;

  contacts->for_each_owned_side(lmp, WHO, [&](const ContactList::Contact &c, bool count_j) {
    const int i = c.i, j = c.j;
    const double len = std::sqrt(c.normal[0] * c.normal[0] + c.normal[1] * c.normal[1] +
                                 c.normal[2] * c.normal[2]);
    if (!(len > 0.0)) return;
    const double n[3] = {c.normal[0] / len, c.normal[1] / len, c.normal[2] / len};
    bool take_i = (mask[i] & groupbit) != 0;
    bool take_j = count_j && (mask[j] & groupbit);
    if (!take_i && !take_j) return;
    if (use_slab) {
      if (select_center) {
        take_i = take_i && x[i][2] >= zlo && x[i][2] < zhi;
        take_j = take_j && x[j][2] >= zlo && x[j][2] < zhi;
      } else {
        const bool in = c.point[2] >= zlo && c.point[2] < zhi;
        take_i = take_i && in;
        take_j = take_j && in;
      }
    }
    if (take_i) add_direction(n);
    if (take_j) {
      // -n: the same n n^T, the angle of -n
      bin(-n[2]);
      add_moment(n);
    }
  });
}

/* ---------------------------------------------------------------------- */

void ComputeContactHisto::finish_vector(const double *moments, double count, const double *)
{
  double F[6];
  for (int m = 0; m < 6; m++) F[m] = count > 0.0 ? moments[m] / count : 0.0;
  for (int m = 0; m < 6; m++) vector[FABRIC + m] = F[m];
  vector[ANISOTROPY] = F[2] - 0.5 * (F[0] + F[1]);
  const double tr3 = (F[0] + F[1] + F[2]) / 3.0;
  const double d0 = F[0] - tr3, d1 = F[1] - tr3, d2 = F[2] - tr3;
  const double ddot = d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (F[3] * F[3] + F[4] * F[4] + F[5] * F[5]);
  vector[DEVIATOR] = std::sqrt(1.5 * ddot);
  vector[SAMPLES] = count;
}
