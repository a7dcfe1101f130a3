/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: common base of compute contact/histo and compute orient/histo
   (see compute_angle_histo.h, doc/compute_contact_histo.rst, doc/compute_orient_histo.rst)

   Global array, one row per bin of theta in [0, theta_max]:
     1 bin centre theta_k
     2 P_k = c_k / (C dOmega_k),  dOmega_k = 2 pi (cos theta_k,lo - cos theta_k,hi),
       C = sum of the counts c_k
     3 c_k / C
------------------------------------------------------------------------- */

#include "compute_angle_histo.h"


#include "atom.h"
#include "error.h"
#include "math_const.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using MathConst::MY_PI;

/* ---------------------------------------------------------------------- */

ComputeAngleHisto::ComputeAngleHisto(LAMMPS *lmp, int narg, char **arg, const char *name_in,
                                     int nvalues_in, const char *const *colnames_in,
                                     int nextra_in) :
    Compute(lmp, narg, arg),
    name(name_in), nvalues(nvalues_in), colnames(colnames_in), nextra(nextra_in), nbins(18),
    theta_max(MY_PI), have_zlo(false), have_zhi(false), zlo_user(0.0), zhi_user(0.0),
    slab_id(nullptr), slab_compute(nullptr), hist(nullptr), hist_all(nullptr)
{
  if (!atom->ellipsoid_flag) error->all(FLERR, "Compute {} requires atom style ellipsoid", name);

  array_flag = 1;
  size_array_cols = 3;
  extarray = 0;
  vector_flag = 1;
  size_vector = nvalues;
  extvector = 0;
  thermo_modify_colname = 1;

  vector = new double[nvalues];
  for (int k = 0; k < nvalues; k++) vector[k] = 0.0;
}

/* ---------------------------------------------------------------------- */

void ComputeAngleHisto::parse_args(int narg, char **arg)
{
  int iarg = 3;
  while (iarg < narg) {
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, fmt::format("compute {}", name), error);
    if (strcmp(arg[iarg], "bins") == 0) {
      nbins = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (nbins < 1) error->all(FLERR, "Compute {} bins must be >= 1", name);
    } else if (strcmp(arg[iarg], "zlo") == 0) {
      have_zlo = true;
      zlo_user = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "zhi") == 0) {
      have_zhi = true;
      zhi_user = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "slab") == 0) {
      delete[] slab_id;
      slab_id = utils::strdup(arg[iarg + 1]);
    } else if (!parse_keyword(arg[iarg], arg[iarg + 1]))
      error->all(FLERR, "Unknown compute {} keyword: {}", name, arg[iarg]);
    iarg += 2;
  }
  if (slab_id && (have_zlo || have_zhi))
    error->all(FLERR, "Compute {}: use either 'slab' or 'zlo'/'zhi'", name);
  if (have_zlo && have_zhi && !(zhi_user > zlo_user))
    error->all(FLERR, "Compute {} needs zhi > zlo", name);

  size_array_rows = nbins;
  memory->create(array, nbins, 3, fmt::format("{}:array", name).c_str());
  hist = new double[nbins + NMOMENT + nextra];
  hist_all = new double[nbins + NMOMENT + nextra];
  const double dtheta = theta_max / nbins;
  for (int k = 0; k < nbins; k++) {
    array[k][0] = (k + 0.5) * dtheta;
    array[k][1] = array[k][2] = 0.0;
  }
}

/* ---------------------------------------------------------------------- */

ComputeAngleHisto::~ComputeAngleHisto()
{
  delete[] vector;
  memory->destroy(array);
  delete[] hist;
  delete[] hist_all;
  delete[] slab_id;
}

/* ---------------------------------------------------------------------- */

void ComputeAngleHisto::init()
{
  if (slab_id) {
    slab_compute = modify->get_compute_by_id(slab_id);
    if (!slab_compute) error->all(FLERR, "Compute {}: no compute with ID {}", name, slab_id);
    if (strcmp(slab_compute->style, "packing/ellipsoid") != 0 || !slab_compute->vector_flag ||
        slab_compute->size_vector < SLAB_ZHI_ELEMENT)
      error->all(FLERR, "Compute {}: slab compute {} is not packing/ellipsoid", name, slab_id);
  }
}

/* ---------------------------------------------------------------------- */

std::string ComputeAngleHisto::get_thermo_colname(int n)
{
  if (n >= 0 && n < nvalues) return fmt::format("c_{}:{}", id, colnames[n]);
  return {};
}

/* ---------------------------------------------------------------------- */

void ComputeAngleHisto::compute_vector()
{
  invoked_vector = update->ntimestep;
  tally();
}

void ComputeAngleHisto::compute_array()
{
  invoked_array = update->ntimestep;
  tally();
}

/* ---------------------------------------------------------------------- */

int ComputeAngleHisto::bin_of(double cz) const
{
  cz = cz > 1.0 ? 1.0 : (cz < -1.0 ? -1.0 : cz);
  const int k = static_cast<int>(std::acos(cz) / (theta_max / nbins));
  return k >= nbins ? nbins - 1 : (k < 0 ? 0 : k);
}

void ComputeAngleHisto::add_moment(const double *u)
{
  double *m = hist + nbins;
  m[0] += u[0] * u[0];
  m[1] += u[1] * u[1];
  m[2] += u[2] * u[2];
  m[3] += u[0] * u[1];
  m[4] += u[0] * u[2];
  m[5] += u[1] * u[2];
  m[SAMPLE_COUNT] += 1.0;
}

/* ---------------------------------------------------------------------- */

void ComputeAngleHisto::tally()
{
  prepare();

  double zlo = -HUGE_VAL, zhi = HUGE_VAL;
  if (have_zlo) zlo = zlo_user;
  if (have_zhi) zhi = zhi_user;
  if (slab_compute) {
    if (!(slab_compute->invoked_flag & Compute::INVOKED_VECTOR) ||
        slab_compute->invoked_vector != update->ntimestep) {
      slab_compute->compute_vector();
      slab_compute->invoked_flag |= Compute::INVOKED_VECTOR;
    }
    zlo = slab_compute->vector[SLAB_ZLO_ELEMENT - 1];
    zhi = slab_compute->vector[SLAB_ZHI_ELEMENT - 1];
  }
  const bool use_slab = have_zlo || have_zhi || slab_compute;

  const int nsums = nbins + NMOMENT + nextra;
  for (int k = 0; k < nsums; k++) hist[k] = 0.0;
  accumulate(zlo, zhi, use_slab);
  MPI_Allreduce(hist, hist_all, nsums, MPI_DOUBLE, MPI_SUM, world);

  finish_vector(hist_all + nbins, hist_all[nbins + SAMPLE_COUNT], hist_all + nbins + NMOMENT);

  double total = 0.0;
  for (int k = 0; k < nbins; k++) total += hist_all[k];
  const double dtheta = theta_max / nbins;
  for (int k = 0; k < nbins; k++) {
    const double domega = 2.0 * MY_PI * (std::cos(k * dtheta) - std::cos((k + 1) * dtheta));
    array[k][0] = (k + 0.5) * dtheta;
    array[k][1] = total > 0.0 ? hist_all[k] / (total * domega) : 0.0;
    array[k][2] = total > 0.0 ? hist_all[k] / total : 0.0;
  }
}
