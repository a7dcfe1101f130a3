/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: the candidate pairs of pair granular/ellipsoid (see granular_candidates.h)
------------------------------------------------------------------------- */

#include "granular_candidates.h"

#include "atom.h"
#include "fix_neigh_history.h"
#include "granular_ellipsoid_atoms.h"
#include "lammps.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

bool Candidates::refresh(LAMMPS *lmp, NeighList *list, FixNeighHistory *history, int stride,
                         int law_slots, bool respa, PipelineCounters &counters)
{
  if (!stale(lmp, list, respa)) return false;
  if (lmp->neighbor->ago == 0 && builds_keep_skin(lmp, respa))
    find(lmp, list, history, stride, law_slots, counters);
  else
    all(lmp, list);
  return true;
}

bool Candidates::builds_keep_skin(LAMMPS *lmp, bool respa)
{
  const Neighbor *neighbor = lmp->neighbor;
  return neighbor->every == 1 && neighbor->delay == 0 && neighbor->dist_check == 1 &&
      neighbor->build_once == 0 && !respa;
}

// the candidates are not those of the current list: it was built at this step (ago 0;
// Neighbor::ncalls restarts after the build of every run's setup), at another step than
// theirs, again at their step after their evaluation (a fix or command building between two
// evaluations: the build count within a run), or holds other atoms; or they set pairs aside
// under settings that no longer allow it
bool Candidates::stale(LAMMPS *lmp, NeighList *list, bool respa) const
{
  const Neighbor *neighbor = lmp->neighbor;
  return neighbor->ago == 0 || neighbor->lastcall != step || neighbor->ncalls != build_count ||
      static_cast<int>(start.size()) != list->inum + 1 ||
      (aside > 0 && !builds_keep_skin(lmp, respa));
}

/* ----------------------------------------------------------------------
   at the first force evaluation after a neighbour list build (its positions): the neighbours
   within the skin of their bounding spheres are the candidates, the others are forgotten and
   set aside. The rejects this makes are counted here; at the other steps the pair counts the
   pairs set aside. Only the atoms of the candidates need their states until the next build.
   The bounding spheres come from the positions and semi-axes: the states are built after this,
   for those atoms.
------------------------------------------------------------------------- */

void Candidates::find(LAMMPS *lmp, NeighList *list, FixNeighHistory *history, int stride,
                      int law_slots, PipelineCounters &counters)
{
  Atom *atom = lmp->atom;
  const int inum = list->inum, nall = atom->nlocal + atom->nghost;
  // a margin over the rounding of the distances and of LAMMPS's displacement test
  const double skin = lmp->neighbor->skin * (1.0 + 1e-10);
  const EllipsoidAtoms atoms(atom);
  double **x = atom->x;
  jj.clear();
  start.assign(inum + 1, 0);
  needed.assign(nall, 0);
  aside = 0;
  for (int ii = 0; ii < inum; ii++) {
    const int i = list->ilist[ii];
    const int *jlist = list->firstneigh[i];
    int *touch = history->firstflag[i];
    double *rows = history->firstvalue[i];
    const Vec3 ci(x[i][0], x[i][1], x[i][2]);
    const double ri = atoms.bounding_radius(i);
    for (int k = 0; k < list->numneigh[i]; k++) {
      const int j = jlist[k] & NEIGHMASK;
      const BoundingTest t =
          bounding_test(ci, ri, Vec3(x[j][0], x[j][1], x[j][2]), atoms.bounding_radius(j));
      const bool beyond_skin = t.dist > t.reach + skin;
      if (beyond_skin &&
          forget_if_apart(t, rows + stride * k, touch[k], law_slots, counters)) {
        ++aside;
        continue;
      }
      jj.push_back(k);
      needed[i] = needed[j] = 1;
    }
    start[ii + 1] = static_cast<int>(jj.size());
  }
  step = lmp->neighbor->lastcall;
  build_count = lmp->neighbor->ncalls;
}

// every neighbour is a candidate: the builds do not keep the skin, or the list changed since
// the first evaluation after its build (positions have moved since)
void Candidates::all(LAMMPS *lmp, NeighList *list)
{
  const int inum = list->inum;
  jj.clear();
  start.assign(inum + 1, 0);
  for (int ii = 0; ii < inum; ii++) {
    for (int k = 0; k < list->numneigh[list->ilist[ii]]; k++) jj.push_back(k);
    start[ii + 1] = static_cast<int>(jj.size());
  }
  aside = 0;
  needed.assign(lmp->atom->nlocal + lmp->atom->nghost, 1);
  step = lmp->neighbor->lastcall;
  build_count = lmp->neighbor->ncalls;
}
