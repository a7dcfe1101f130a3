/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: contiguous history rows of the candidate pairs (see granular_contact_rows.h)
------------------------------------------------------------------------- */

#include "granular_contact_rows.h"

#include "comm.h"
#include "error.h"
#include "granular_candidates.h"
#include "lammps.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "pair_granular_ellipsoid.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

void ContactRows::load(LAMMPS *lmp, NeighList *list, const Candidates &candidates,
                       FixNeighHistory *history, int row_size)
{
  stride = row_size;
  const int inum = list->inum;
  rows.resize(static_cast<std::size_t>(stride) * candidates.offset(inum));
  const std::size_t bytes = stride * sizeof(double);
  for (int ii = 0; ii < inum; ii++) {
    const double *fix_rows = history->firstvalue[list->ilist[ii]];
    const int *jj = candidates.first(ii);
    double *out = first(candidates.offset(ii));
    for (int k = 0; k < candidates.count(ii); k++)
      std::memcpy(out + stride * k, fix_rows + stride * jj[k], bytes);
  }
  build_step = lmp->neighbor->lastcall;
  build_count = lmp->neighbor->ncalls;
  is_live = true;
}

void ContactRows::store(LAMMPS *lmp, NeighList *list, const Candidates &candidates,
                        FixNeighHistory *history)
{
  if (!is_live) return;
  // the fix's rows are those of the list the rows were loaded from until the next build
  if (lmp->neighbor->lastcall != build_step || lmp->neighbor->ncalls != build_count)
    lmp->error->one(FLERR, "Pair granular/ellipsoid: contact rows not stored before a neighbour "
                           "list build (was fix STORE_CONTACT_ROWS_GRANULAR_ELLIPSOID unfixed?)");
  const int inum = list->inum;
  const std::size_t bytes = stride * sizeof(double);
  for (int ii = 0; ii < inum; ii++) {
    double *fix_rows = history->firstvalue[list->ilist[ii]];
    const int *jj = candidates.first(ii);
    const double *in = first(candidates.offset(ii));
    for (int k = 0; k < candidates.count(ii); k++)
      std::memcpy(fix_rows + stride * jj[k], in + stride * k, bytes);
  }
  is_live = false;
}

FixStoreContactRows::FixStoreContactRows(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg)
{
  restart_global = 1;
}

int FixStoreContactRows::setmask()
{
  return PRE_EXCHANGE | MIN_PRE_EXCHANGE | POST_RUN;
}

void FixStoreContactRows::write_restart(FILE *fp)
{
  store();
  if (comm->me == 0) {
    const int size = 0;
    fwrite(&size, sizeof(int), 1, fp);
  }
}

void FixStoreContactRows::store()
{
  if (pair) pair->store_contact_rows();
}
