/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: common base of compute contact/histo and compute orient/histo
   (see compute_angle_histo.h, doc/compute_contact_histo.rst, doc/compute_orient_histo.rst)

   Global array, one row per bin of theta in [0, theta_max]:
     1 bin centre theta_k
     2 P_k = w_k / (W dOmega_k),  dOmega_k = 2 pi (cos theta_k,lo - cos theta_k,hi),
       w_k = the sum of the weights of the samples in bin k (their number when unweighted),
       W = sum of the w_k
     3 w_k / W
     4 (value_column only) the mean value of the samples in bin k (0 when empty)
------------------------------------------------------------------------- */

#include "compute_angle_histo.h"

#include "atom.h"
#include "error.h"
#include "math_const.h"
#include "memory.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using MathConst::MY_PI;

/* ---------------------------------------------------------------------- */

ComputeAngleHisto::ComputeAngleHisto(LAMMPS *lmp, int narg, char **arg, const char *name_in,
                                     int nvalues_in, const char *const *colnames_in,
                                     int nextra_in, bool value_column_in) :
    Compute(lmp, narg, arg),
    name(name_in), nvalues(nvalues_in), colnames(colnames_in), nextra(nextra_in),
    value_column(value_column_in), nbins(18), theta_max(MY_PI), slab(lmp, name_in),
    hist(nullptr), hist_all(nullptr)
{
  if (!atom->ellipsoid_flag) error->all(FLERR, "Compute {} requires atom style ellipsoid", name);

  array_flag = 1;
  size_array_cols = value_column ? 4 : 3;
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
      nbins = parse_histogram_bins(lmp, name, iarg + 1, arg[iarg + 1]);
    } else if (!slab.parse(arg[iarg], arg[iarg + 1]) && !parse_keyword(arg[iarg], arg[iarg + 1]))
      error->all(FLERR, "Unknown compute {} keyword: {}", name, arg[iarg]);
    iarg += 2;
  }
  slab.check();

  size_array_rows = nbins;
  memory->create(array, nbins, size_array_cols, fmt::format("{}:array", name).c_str());
  const int nsums = 3 * nbins + NMOMENT + nextra;
  hist = new double[nsums];
  hist_all = new double[nsums];
  const double dtheta = theta_max / nbins;
  for (int k = 0; k < nbins; k++) {
    array[k][0] = (k + 0.5) * dtheta;
    for (int c = 1; c < size_array_cols; c++) array[k][c] = 0.0;
  }
}

/* ---------------------------------------------------------------------- */

ComputeAngleHisto::~ComputeAngleHisto()
{
  delete[] vector;
  memory->destroy(array);
  delete[] hist;
  delete[] hist_all;
}

/* ---------------------------------------------------------------------- */

void ComputeAngleHisto::init()
{
  slab.init();
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

void ComputeAngleHisto::bin(double cz, double w, double v)
{
  const int k = bin_of(cz);
  hist[k] += w;
  hist[nbins + k] += 1.0;
  hist[2 * nbins + k] += v;
}

void ComputeAngleHisto::add_moment(const double *u, double w)
{
  double *m = hist + 3 * nbins;
  m[0] += w * u[0] * u[0];
  m[1] += w * u[1] * u[1];
  m[2] += w * u[2] * u[2];
  m[3] += w * u[0] * u[1];
  m[4] += w * u[0] * u[2];
  m[5] += w * u[1] * u[2];
  m[WEIGHT_SUM] += w;
  m[SAMPLE_COUNT] += 1.0;
}

/* ---------------------------------------------------------------------- */

void ComputeAngleHisto::tally()
{
  prepare();
  const SlabOption::Bounds bounds = slab.bounds();

  const int nsums = 3 * nbins + NMOMENT + nextra;
  for (int k = 0; k < nsums; k++) hist[k] = 0.0;
  accumulate(bounds);
  MPI_Allreduce(hist, hist_all, nsums, MPI_DOUBLE, MPI_SUM, world);

  const double *moments = hist_all + 3 * nbins;
  finish_vector(moments, moments[WEIGHT_SUM], moments[SAMPLE_COUNT], moments + NMOMENT);

  const double *weights = hist_all, *counts = hist_all + nbins, *values = hist_all + 2 * nbins;
  double total = 0.0;
  for (int k = 0; k < nbins; k++) total += weights[k];
  const double dtheta = theta_max / nbins;
  for (int k = 0; k < nbins; k++) {
    const double domega = 2.0 * MY_PI * (std::cos(k * dtheta) - std::cos((k + 1) * dtheta));
    array[k][0] = (k + 0.5) * dtheta;
    array[k][1] = total > 0.0 ? weights[k] / (total * domega) : 0.0;
    array[k][2] = total > 0.0 ? weights[k] / total : 0.0;
    if (value_column) array[k][3] = counts[k] > 0.0 ? values[k] / counts[k] : 0.0;
  }
}
