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
------------------------------------------------------------------------- */

#include "compute_contact_histo.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "math_const.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

#include "pair_granular_ellipsoid.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using MathConst::MY_PI;

namespace {
const char *const COLNAMES[ComputeContactHisto::NVALUES] = {
    "Fxx", "Fyy", "Fzz", "Fxy", "Fxz", "Fyz", "Fanis", "Fdev", "Nnormals"};
}

/* ---------------------------------------------------------------------- */

ComputeContactHisto::ComputeContactHisto(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), pair(nullptr), nbins(18), have_zlo(false), have_zhi(false),
    zlo_user(0.0), zhi_user(0.0), slab_id(nullptr), slab_compute(nullptr), select_center(0),
    hist(nullptr), hist_all(nullptr)
{
  if (!atom->ellipsoid_flag) error->all(FLERR, "Compute contact/histo requires atom style ellipsoid");

  int iarg = 3;
  while (iarg < narg) {
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "compute contact/histo", error);
    if (strcmp(arg[iarg], "bins") == 0) {
      nbins = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (nbins < 1) error->all(FLERR, "Compute contact/histo bins must be >= 1");
    } else if (strcmp(arg[iarg], "zlo") == 0) {
      have_zlo = true;
      zlo_user = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "zhi") == 0) {
      have_zhi = true;
      zhi_user = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "slab") == 0) {
      delete[] slab_id;
      slab_id = utils::strdup(arg[iarg + 1]);
    } else if (strcmp(arg[iarg], "select") == 0) {
      if (strcmp(arg[iarg + 1], "point") == 0)
        select_center = 0;
      else if (strcmp(arg[iarg + 1], "center") == 0)
        select_center = 1;
      else
        error->all(FLERR, "Compute contact/histo select must be 'point' or 'center'");
    } else
      error->all(FLERR, "Unknown compute contact/histo keyword: {}", arg[iarg]);
    iarg += 2;
  }
  if (slab_id && (have_zlo || have_zhi))
    error->all(FLERR, "Compute contact/histo: use either 'slab' or 'zlo'/'zhi'");
  if (have_zlo && have_zhi && !(zhi_user > zlo_user))
    error->all(FLERR, "Compute contact/histo needs zhi > zlo");

  array_flag = 1;
  size_array_rows = nbins;
  size_array_cols = 3;
  extarray = 0;
  vector_flag = 1;
  size_vector = NVALUES;
  extvector = 0;
  thermo_modify_colname = 1;

  vector = new double[NVALUES];
  for (int k = 0; k < NVALUES; k++) vector[k] = 0.0;
  memory->create(array, nbins, 3, "contact/histo:array");
  hist = new double[nbins + 7];
  hist_all = new double[nbins + 7];
  const double dtheta = MY_PI / nbins;
  for (int k = 0; k < nbins; k++) {
    array[k][0] = (k + 0.5) * dtheta;
    array[k][1] = array[k][2] = 0.0;
  }
}

/* ---------------------------------------------------------------------- */

ComputeContactHisto::~ComputeContactHisto()
{
  delete[] vector;
  memory->destroy(array);
  delete[] hist;
  delete[] hist_all;
  delete[] slab_id;
}

/* ---------------------------------------------------------------------- */

void ComputeContactHisto::init()
{
  pair = dynamic_cast<PairGranularEllipsoid *>(force->pair_match("granular/ellipsoid", 1));
  if (!pair) error->all(FLERR, "Compute contact/histo requires pair style granular/ellipsoid");
  pair->request_contacts();
  if (slab_id) {
    slab_compute = modify->get_compute_by_id(slab_id);
    if (!slab_compute) error->all(FLERR, "Compute contact/histo: no compute with ID {}", slab_id);
    if (strcmp(slab_compute->style, "packing/ellipsoid") != 0)
      error->all(FLERR, "Compute contact/histo: slab compute {} is not packing/ellipsoid", slab_id);
  }
}

/* ---------------------------------------------------------------------- */

std::string ComputeContactHisto::get_thermo_colname(int n)
{
  if (n >= 0 && n < NVALUES) return fmt::format("c_{}:{}", id, COLNAMES[n]);
  return {};
}

/* ---------------------------------------------------------------------- */

void ComputeContactHisto::compute_vector()
{
  invoked_vector = update->ntimestep;
  tally();
}

void ComputeContactHisto::compute_array()
{
  invoked_array = update->ntimestep;
  tally();
}

/* ----------------------------------------------------------------------
   One sample per contact and owned side: side i (always owned) with normal n, side j with -n
   when j is owned or newton_pair is on (then the pair is on this rank only). With newton_pair
   off a contact with a ghost j is in the list of j's owner too, which adds that side.
------------------------------------------------------------------------- */

void ComputeContactHisto::tally()
{
  if (!pair) error->all(FLERR, "Compute contact/histo used before initialisation (do a run)");
  if (pair->contacts_timestep() != update->ntimestep)
    error->all(FLERR,
               "Compute contact/histo: the pair's contacts are not from the current step "
               "(invoke it on a step where forces were computed; 'run 0' after defining it)");

  double zlo = -HUGE_VAL, zhi = HUGE_VAL;
  if (have_zlo) zlo = zlo_user;
  if (have_zhi) zhi = zhi_user;
  if (slab_compute) {
    if (!(slab_compute->invoked_flag & Compute::INVOKED_VECTOR) ||
        slab_compute->invoked_vector != update->ntimestep) {
      slab_compute->compute_vector();
      slab_compute->invoked_flag |= Compute::INVOKED_VECTOR;
    }
    zlo = slab_compute->vector[4];
    zhi = slab_compute->vector[5];
  }
  const bool use_slab = have_zlo || have_zhi || slab_compute;

  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton = force->newton_pair;
  int *mask = atom->mask;
  double **x = atom->x;
  const double dtheta = MY_PI / nbins;

  // hist[0..nbins): counts; then 6 fabric sums and the sample count
  double *fab = hist + nbins;
  for (int k = 0; k < nbins + 7; k++) hist[k] = 0.0;

  auto add = [&](const double *n, double sign) {
    double cz = sign * n[2];
    cz = cz > 1.0 ? 1.0 : (cz < -1.0 ? -1.0 : cz);
    int k = static_cast<int>(std::acos(cz) / dtheta);
    if (k >= nbins) k = nbins - 1;
    if (k < 0) k = 0;
    hist[k] += 1.0;
    fab[0] += n[0] * n[0];
    fab[1] += n[1] * n[1];
    fab[2] += n[2] * n[2];
    fab[3] += n[0] * n[1];
    fab[4] += n[0] * n[2];
    fab[5] += n[1] * n[2];
    fab[6] += 1.0;
  };

  for (const auto &c : pair->contacts()) {
    const int i = c.i, j = c.j;
    if (i < 0 || i >= nlocal || j < 0 || j >= nall)
      error->one(FLERR, "Compute contact/histo: contact list does not match the atoms");
    const double len = std::sqrt(c.normal[0] * c.normal[0] + c.normal[1] * c.normal[1] +
                                 c.normal[2] * c.normal[2]);
    if (!(len > 0.0)) continue;
    const double n[3] = {c.normal[0] / len, c.normal[1] / len, c.normal[2] / len};
    bool take_i = (mask[i] & groupbit) != 0;
    bool take_j = ((j < nlocal) || newton) && (mask[j] & groupbit);
    if (!take_i && !take_j) continue;
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
    if (take_i) add(n, 1.0);
    if (take_j) add(n, -1.0);
  }

  MPI_Allreduce(hist, hist_all, nbins + 7, MPI_DOUBLE, MPI_SUM, world);

  const double total = hist_all[nbins + 6];
  for (int k = 0; k < nbins; k++) {
    const double domega = 2.0 * MY_PI * (std::cos(k * dtheta) - std::cos((k + 1) * dtheta));
    array[k][0] = (k + 0.5) * dtheta;
    array[k][1] = total > 0.0 ? hist_all[k] / (total * domega) : 0.0;
    array[k][2] = total > 0.0 ? hist_all[k] / total : 0.0;
  }
  double F[6];
  for (int m = 0; m < 6; m++) F[m] = total > 0.0 ? hist_all[nbins + m] / total : 0.0;
  for (int m = 0; m < 6; m++) vector[m] = F[m];
  vector[6] = F[2] - 0.5 * (F[0] + F[1]);
  const double tr3 = (F[0] + F[1] + F[2]) / 3.0;
  const double d0 = F[0] - tr3, d1 = F[1] - tr3, d2 = F[2] - tr3;
  const double ddot = d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (F[3] * F[3] + F[4] * F[4] + F[5] * F[5]);
  vector[7] = std::sqrt(1.5 * ddot);
  vector[8] = total;
}
