/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: compute contact/histo (doc/compute_contact_histo.rst)

   Samples (granular_contact_samples.h): every contact contributes its normal seen from each
   of its particles in the group (n seen from i, -n seen from j); the partner may be any
   particle. Each sample has the weight w = 1 (weight none, default) or w = |f_n| (weight
   force), f_n the contact's normal force.

   Global array, one row per bin of theta in [0, pi] (angle between a contact normal and +z):
     1 bin centre theta_k
     2 P_k = w_k / (W dOmega_k),  dOmega_k = 2 pi (cos theta_k,lo - cos theta_k,hi),
       w_k the sum of the weights in bin k, W = sum of the w_k
       (uniform distribution of directions: P = 1/(4 pi))
     3 w_k / W (fraction of the normals, or of the normal force, in the bin)
     4 mean |f_n| of the samples in the bin
   Global vector (fabric tensor F = sum w n n^T / sum w over the same samples):
     1-6 Fxx Fyy Fzz Fxy Fxz Fyz
     7   Fzz - (Fxx + Fyy)/2
     8   sqrt(3/2 F':F'),  F' = F - tr(F) I / 3
     9   number of samples C (twice the number of contacts without a slab)

   Arguments, array and slab handling: ComputeAngleHisto (compute_angle_histo.cpp).
------------------------------------------------------------------------- */

#include "compute_contact_histo.h"

#include "atom.h"
#include "error.h"

#include "granular_contact_samples.h"
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
    ComputeAngleHisto(lmp, narg, arg, "contact/histo", NVALUES, COLNAMES, 0, true),
    contacts(nullptr), select_center(false), weight_force(false)
{
  parse_args(narg, arg);
}

/* ---------------------------------------------------------------------- */

bool ComputeContactHisto::parse_keyword(const char *key, const char *value)
{
  if (strcmp(key, "select") == 0) {
    select_center = parse_contact_select(lmp, "contact/histo", value);
  } else if (strcmp(key, "weight") == 0) {
    if (strcmp(value, "none") == 0)
      weight_force = false;
    else if (strcmp(value, "force") == 0)
      weight_force = true;
    else
      error->all(FLERR, "Compute contact/histo weight must be 'none' or 'force'");
  } else {
    return false;
  }
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

/* ---------------------------------------------------------------------- */

void ComputeContactHisto::accumulate(const SlabOption::Bounds &slab)
{
  const ContactSampleFilter filter{groupbit, slab, select_center};
  for_each_contact_sample(*contacts, lmp, WHO, filter, [&](const double *n, double fn) {
    const double f = std::fabs(fn);
    add_direction(n, weight_force ? f : 1.0, f);
  });
}

/* ---------------------------------------------------------------------- */

void ComputeContactHisto::finish_vector(const double *moments, double weight, double count,
                                        const double *)
{
  double F[6];
  for (int m = 0; m < 6; m++) F[m] = weight > 0.0 ? moments[m] / weight : 0.0;
  for (int m = 0; m < 6; m++) vector[FABRIC + m] = F[m];
  vector[ANISOTROPY] = F[2] - 0.5 * (F[0] + F[1]);
  const double tr3 = (F[0] + F[1] + F[2]) / 3.0;
  const double d0 = F[0] - tr3, d1 = F[1] - tr3, d2 = F[2] - tr3;
  const double ddot = d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (F[3] * F[3] + F[4] * F[4] + F[5] * F[5]);
  vector[DEVIATOR] = std::sqrt(1.5 * ddot);
  vector[SAMPLES] = count;
}
