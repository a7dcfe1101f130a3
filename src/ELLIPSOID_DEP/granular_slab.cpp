/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: the slab and bins keywords of the histogram computes (see granular_slab.h)
------------------------------------------------------------------------- */

#include "granular_slab.h"

#include "compute.h"
#include "error.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

SlabOption::~SlabOption()
{
  delete[] slab_id;
}

bool SlabOption::parse(const char *key, const char *value)
{
  if (strcmp(key, "zlo") == 0) {
    have_zlo = true;
    zlo_user = utils::numeric(FLERR, value, false, lmp);
  } else if (strcmp(key, "zhi") == 0) {
    have_zhi = true;
    zhi_user = utils::numeric(FLERR, value, false, lmp);
  } else if (strcmp(key, "slab") == 0) {
    delete[] slab_id;
    slab_id = utils::strdup(value);
  } else {
    return false;
  }
  return true;
}

void SlabOption::check() const
{
  if (slab_id && (have_zlo || have_zhi))
    lmp->error->all(FLERR, "Compute {}: use either 'slab' or 'zlo'/'zhi'", name);
  if (have_zlo && have_zhi && !(zhi_user > zlo_user))
    lmp->error->all(FLERR, "Compute {} needs zhi > zlo", name);
}

// by its ID at every use, never a pointer kept from init(): the compute may have been deleted
// or defined again since (uncompute, then a library call or a variable between runs)
Compute *SlabOption::find() const
{
  Compute *slab_compute = lmp->modify->get_compute_by_id(slab_id);
  if (!slab_compute) lmp->error->all(FLERR, "Compute {}: no compute with ID {}", name, slab_id);
  if (strcmp(slab_compute->style, "packing/ellipsoid") != 0 || !slab_compute->vector_flag ||
      slab_compute->size_vector < ZHI_ELEMENT)
    lmp->error->all(FLERR, "Compute {}: slab compute {} is not packing/ellipsoid", name, slab_id);
  return slab_compute;
}

void SlabOption::init()
{
  if (slab_id) find();
}

SlabOption::Bounds SlabOption::bounds() const
{
  Compute *slab_compute = slab_id ? find() : nullptr;
  Bounds b{have_zlo ? zlo_user : -HUGE_VAL, have_zhi ? zhi_user : HUGE_VAL,
           have_zlo || have_zhi || slab_compute};
  if (slab_compute) {
    const bigint now = lmp->update->ntimestep;
    if (!(slab_compute->invoked_flag & Compute::INVOKED_VECTOR) ||
        slab_compute->invoked_vector != now) {
      slab_compute->compute_vector();
      slab_compute->invoked_flag |= Compute::INVOKED_VECTOR;
    }
    b.zlo = slab_compute->vector[ZLO_ELEMENT - 1];
    b.zhi = slab_compute->vector[ZHI_ELEMENT - 1];
  }
  return b;
}

int LAMMPS_NS::parse_histogram_bins(LAMMPS *lmp, const char *name, int iarg, const char *value)
{
  const int nbins = utils::inumeric(FLERR, value, false, lmp);
  if (nbins < 1) lmp->error->all(FLERR, iarg, "Compute {} bins must be >= 1", name);
  if (nbins > HISTOGRAM_MAX_BINS)
    lmp->error->all(FLERR, iarg, "Compute {} bins is too large: {} > {}", name, nbins,
                    HISTOGRAM_MAX_BINS);
  return nbins;
}
