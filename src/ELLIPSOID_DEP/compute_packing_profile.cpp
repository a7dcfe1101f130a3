/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: compute packing/profile (doc/compute_packing_profile.rst)

   Global array, one row per bin k = [zlo + k w, zlo + (k+1) w] (1-based columns in scripts):
     1 z of the bin centre
     2 solid fraction phi = solid volume in the bin / (Lx Ly w)
     3 solid volume in the bin (exact ellipsoid-slab volumes)
     4 number of group particles whose centre lies in the bin
------------------------------------------------------------------------- */

#include "compute_packing_profile.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "memory.h"
#include "update.h"

#include "ellipsoid_kernel.h"
#include "granular_ellipsoid_atoms.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace {
constexpr int MAXBINS = 1000000;
}

/* ---------------------------------------------------------------------- */

ComputePackingProfile::ComputePackingProfile(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), width(0.0), zlo(0.0), nbins(0), local(nullptr)
{
  if (narg < 4) utils::missing_cmd_args(FLERR, "compute packing/profile", error);
  if (!atom->ellipsoid_flag)
    error->all(FLERR, "Compute packing/profile requires atom style ellipsoid");
  if (domain->dimension != 3) error->all(FLERR, "Compute packing/profile requires 3d");

  width = utils::numeric(FLERR, arg[3], false, lmp);
  if (!(width > 0.0)) error->all(FLERR, 3, "Compute packing/profile bin width must be > 0");

  zlo = domain->boxlo[2];
  double zhi = domain->boxhi[2];
  int iarg = 4;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "zlo") == 0 || strcmp(arg[iarg], "zhi") == 0) {
      if (iarg + 2 > narg)
        utils::missing_cmd_args(FLERR, std::string("compute packing/profile ") + arg[iarg], error);
      const double value = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (strcmp(arg[iarg], "zlo") == 0)
        zlo = value;
      else
        zhi = value;
      iarg += 2;
    } else
      error->all(FLERR, iarg, "Unknown compute packing/profile keyword: {}", arg[iarg]);
  }
  if (!(zhi > zlo)) error->all(FLERR, "Compute packing/profile needs zhi > zlo");

  // bins of exactly the given width; the last one ends at or just above zhi
  const double n = std::ceil((zhi - zlo) / width * (1.0 - 1e-12));
  if (n > MAXBINS)
    error->all(FLERR, 3, "Compute packing/profile: {} bins exceed the limit of {}", n, MAXBINS);
  nbins = std::max(1, static_cast<int>(n));

  array_flag = 1;
  size_array_rows = nbins;
  size_array_cols = NCOLUMNS;
  extarray = 0;
  memory->create(array, nbins, NCOLUMNS, "packing/profile:array");
  memory->create(local, 2 * nbins, "packing/profile:local");
  for (int k = 0; k < nbins; k++) {
    array[k][0] = zlo + (k + 0.5) * width;
    for (int c = 1; c < NCOLUMNS; c++) array[k][c] = 0.0;
  }
}

/* ---------------------------------------------------------------------- */

ComputePackingProfile::~ComputePackingProfile()
{
  memory->destroy(array);
  memory->destroy(local);
}

/* ---------------------------------------------------------------------- */

void ComputePackingProfile::init()
{
  if (domain->triclinic)
    error->all(FLERR, "Compute packing/profile requires an orthogonal simulation box");
}

/* ----------------------------------------------------------------------
   each ellipsoid adds its exact volume to the bins its z extent [cz - h, cz + h] touches,
   h = sqrt(M_zz); with a periodic z boundary its images at -Lz and +Lz add theirs too
------------------------------------------------------------------------- */

void ComputePackingProfile::compute_array()
{
  invoked_array = update->ntimestep;

  const int nlocal = atom->nlocal;
  int *mask = atom->mask;
  const EllipsoidAtoms atoms(atom);

  int missing = 0;
  for (int i = 0; i < nlocal; i++)
    if ((mask[i] & groupbit) && !atoms.has_shape(i)) missing = 1;
  int missing_all;
  MPI_Allreduce(&missing, &missing_all, 1, MPI_INT, MPI_MAX, world);
  if (missing_all)
    error->all(FLERR, "Compute packing/profile: every atom of the group must have a shape");

  double *volume = local;
  double *centres = local + nbins;
  std::fill(local, local + 2 * nbins, 0.0);

  int invalid = 0;
  const int nimages = domain->zperiodic ? 1 : 0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    EllipsoidDep::Ellipsoid e = atoms.ellipsoid(i);
    const double cz = e.center[2];
    if (!e.finite || !std::isfinite(cz)) {
      invalid = 1;
      continue;
    }
    const double h = std::sqrt(e.inverse_form(2, 2));

    const double kc = std::floor((cz - zlo) / width);
    if (kc >= 0.0 && kc < nbins) centres[static_cast<int>(kc)] += 1.0;

    for (int image = -nimages; image <= nimages; image++) {
      e.center[2] = cz + image * domain->zprd;
      const double first = std::floor((e.center[2] - h - zlo) / width);
      const double last = std::floor((e.center[2] + h - zlo) / width);
      if (last < 0.0 || first >= nbins) continue;
      const int k0 = std::max(0, static_cast<int>(first));
      const int k1 = std::min(nbins - 1, static_cast<int>(last));
      for (int k = k0; k <= k1; k++)
        volume[k] += EllipsoidDep::ellipsoid_slab_volume(e, zlo + k * width, zlo + (k + 1) * width);
    }
  }

  int invalid_all;
  MPI_Allreduce(&invalid, &invalid_all, 1, MPI_INT, MPI_MAX, world);
  if (invalid_all)
    error->all(FLERR, "Compute packing/profile: an atom has a non-finite position or shape");
  MPI_Allreduce(MPI_IN_PLACE, local, 2 * nbins, MPI_DOUBLE, MPI_SUM, world);

  const double bin_volume = domain->xprd * domain->yprd * width;
  for (int k = 0; k < nbins; k++) {
    array[k][1] = volume[k] / bin_volume;
    array[k][2] = volume[k];
    array[k][3] = centres[k];
  }
}

/* ---------------------------------------------------------------------- */

double ComputePackingProfile::memory_usage()
{
  return (NCOLUMNS + 2.0) * nbins * sizeof(double);
}
