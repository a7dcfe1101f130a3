/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: compute force/histo (doc/compute_force_histo.rst)

   Samples: those of contact/histo (granular_contact_samples.h), each with f = |f_n|, the
   magnitude of its contact's normal force; <f> their mean.
   Global array, one row per bin of x = f/<f> in [0, max], width D = max/N:
     1 bin centre x_k = (k + 1/2) D
     2 P_k = c_k / (C D) (per unit x; sum P_k D = 1 - the fraction beyond max)
     3 c_k / C
   with c_k the samples in bin k and C all samples.
   Global vector: 1 <f>, 2 C, 3 fraction with x >= max, 4 largest x, 5 fraction with f_n < 0.
------------------------------------------------------------------------- */

#include "compute_force_histo.h"

#include "atom.h"
#include "error.h"
#include "memory.h"
#include "update.h"

#include "granular_contact_samples.h"
#include "granular_ellipsoid_contacts.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace {
const char WHO[] = "Compute force/histo";
const char *const COLNAMES[ComputeForceHisto::NVALUES] = {"fmean", "Nforces", "beyond",
                                                          "xlargest", "attractive"};
}    // namespace

/* ---------------------------------------------------------------------- */

ComputeForceHisto::ComputeForceHisto(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nbins(20), xmax(5.0), select_center(false),
    slab(lmp, "force/histo"), contacts(nullptr)
{
  if (!atom->ellipsoid_flag) error->all(FLERR, "Compute force/histo requires atom style ellipsoid");

  int iarg = 3;
  while (iarg < narg) {
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "compute force/histo", error);
    const char *key = arg[iarg], *value = arg[iarg + 1];
    if (strcmp(key, "bins") == 0) {
      nbins = parse_histogram_bins(lmp, "force/histo", iarg + 1, value);
    } else if (strcmp(key, "max") == 0) {
      xmax = utils::numeric(FLERR, value, false, lmp);
      if (!(xmax > 0.0)) error->all(FLERR, "Compute force/histo max must be > 0");
    } else if (strcmp(key, "select") == 0) {
      select_center = parse_contact_select(lmp, "force/histo", value);
    } else if (!slab.parse(key, value)) {
      error->all(FLERR, "Unknown compute force/histo keyword: {}", key);
    }
    iarg += 2;
  }
  slab.check();

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
  memory->create(array, nbins, 3, "force/histo:array");
  for (int k = 0; k < nbins; k++) {
    array[k][0] = (k + 0.5) * xmax / nbins;
    array[k][1] = array[k][2] = 0.0;
  }
  counts.assign(static_cast<size_t>(nbins) + 1, 0.0);
  counts_all.assign(static_cast<size_t>(nbins) + 1, 0.0);
}

ComputeForceHisto::~ComputeForceHisto()
{
  delete[] vector;
  memory->destroy(array);
}

/* ---------------------------------------------------------------------- */

void ComputeForceHisto::init()
{
  contacts = ContactList::request(lmp, WHO);
  slab.init();
}

std::string ComputeForceHisto::get_thermo_colname(int n)
{
  if (n >= 0 && n < NVALUES) return fmt::format("c_{}:{}", id, COLNAMES[n]);
  return {};
}

void ComputeForceHisto::compute_vector()
{
  invoked_vector = update->ntimestep;
  tally();
}

void ComputeForceHisto::compute_array()
{
  invoked_array = update->ntimestep;
  tally();
}

double ComputeForceHisto::memory_usage()
{
  return static_cast<double>((forces.capacity() + 2 * counts.capacity()) * sizeof(double));
}

/* ----------------------------------------------------------------------
   Two passes: <f> over all ranks first, then each rank bins its own samples by f/<f>.
------------------------------------------------------------------------- */

void ComputeForceHisto::tally()
{
  const ContactList &list = ContactList::current(contacts, lmp, WHO);
  const ContactSampleFilter filter{groupbit, slab.bounds(), select_center};

  forces.clear();
  double sums[3] = {0.0, 0.0, 0.0};    // sum of |f_n|, samples, attractive samples
  for_each_contact_sample(list, lmp, WHO, filter, [&](const double *, double fn) {
    forces.push_back(std::fabs(fn));
    sums[0] += std::fabs(fn);
    sums[1] += 1.0;
    if (fn < 0.0) sums[2] += 1.0;
  });
  double sums_all[3];
  MPI_Allreduce(sums, sums_all, 3, MPI_DOUBLE, MPI_SUM, world);
  const double total = sums_all[1];
  const double mean = total > 0.0 ? sums_all[0] / total : 0.0;

  // counts[nbins]: the samples at or beyond max
  double largest = 0.0;
  counts.assign(counts.size(), 0.0);
  const double width = xmax / nbins;
  for (const double f : forces) {
    const double x = mean > 0.0 ? f / mean : 0.0;
    largest = x > largest ? x : largest;
    int k = nbins;
    if (x < xmax) k = std::min(static_cast<int>(x / width), nbins - 1);    // x / width may round up
    counts[k] += 1.0;
  }
  MPI_Allreduce(counts.data(), counts_all.data(), static_cast<int>(counts.size()), MPI_DOUBLE,
                MPI_SUM, world);
  double largest_all = 0.0;
  MPI_Allreduce(&largest, &largest_all, 1, MPI_DOUBLE, MPI_MAX, world);

  vector[MEAN] = mean;
  vector[SAMPLES] = total;
  vector[BEYOND] = total > 0.0 ? counts_all[nbins] / total : 0.0;
  vector[LARGEST] = largest_all;
  vector[ATTRACTIVE] = total > 0.0 ? sums_all[2] / total : 0.0;
  for (int k = 0; k < nbins; k++) {
    array[k][0] = (k + 0.5) * width;
    array[k][1] = total > 0.0 ? counts_all[k] / (total * width) : 0.0;
    array[k][2] = total > 0.0 ? counts_all[k] / total : 0.0;
  }
}
