/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: pair_style granular/ellipsoid, the force evaluation (see
   doc/pair_granular_ellipsoid.rst and doc/architecture.md "One force evaluation"): the
   per-atom states, one pair through the kernel's pipeline and the force law, the neighbour
   loop, and single() for compute pair/local.
------------------------------------------------------------------------- */

#include "pair_granular_ellipsoid.h"

#include "atom.h"
#include "fix_neigh_history.h"
#include "force.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

void PairGranularEllipsoid::find_ghost_owners()
{
  const int nlocal = atom->nlocal, nghost = atom->nghost;
  const tagint *tag = atom->tag;
  ghost_owner.assign(nghost, -1);
  if (!atom->tag_enable) return;
  owned_index.clear();
  for (int i = 0; i < nlocal; i++) owned_index[tag[i]] = i;
  for (int g = 0; g < nghost; g++) {
    const auto owner = owned_index.find(tag[nlocal + g]);
    if (owner != owned_index.end()) ghost_owner[g] = owner->second;
  }
}

// the states of the atoms in candidate pairs (state_needed): only their pairs are evaluated;
// without the angular velocity, which complete_state adds at an atom's first contact
void PairGranularEllipsoid::update_states()
{
  const EllipsoidAtoms atoms(atom);
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  states.resize(nall);
  state_keys.resize(nall);
  omega_known.assign(nall, 0);
  // the candidates' atoms (every atom when the candidates do not cover them all)
  const std::vector<char> &state_needed = candidates.state_needed();
  const std::vector<char> every(static_cast<int>(state_needed.size()) != nall ? nall : 0, 1);
  const char *const needed = every.empty() ? state_needed.data() : every.data();
  for (int i = 0; i < nlocal; i++)
    if (needed[i]) atoms.update_shape(i, states[i], state_keys[i]);
  // a ghost that is an image of an owned atom copies its state (checked value by value)
  if (neighbor->ago == 0 || static_cast<int>(ghost_owner.size()) != atom->nghost)
    find_ghost_owners();
  for (int i = nlocal; i < nall; i++) {
    if (!needed[i]) continue;
    const int k = ghost_owner[i - nlocal];
    if (k < 0 || !needed[k] ||
        !atoms.copy_state(i, k, states[k], state_keys[k], states[i], state_keys[i]))
      atoms.update_shape(i, states[i], state_keys[i]);
  }
}

/* ---------------------------------------------------------------------- */

ContactForce PairGranularEllipsoid::pair_force(int i, int j, int law, double *history,
                                               const ContactGeometry &geometry) const
{
  const ForceLaw &force_law = laws[law];
  const ContactMotion motion =
      contact_motion(states[i], states[j], geometry.point, atom->mask[i] & freeze_group_bit,
                     atom->mask[j] & freeze_group_bit);
  // setup and single() look at the stored history without advancing it (dt = 0, on a copy),
  // as pair granular does, so a restart reproduces the forces it was written with
  const LawHistory law_history(PairHistory(history).law(), force_law.history_size(),
                               history_update);
  return force_law.compute(geometry, motion, history_update ? update->dt : 0.0, law_history.get());
}

/* ---------------------------------------------------------------------- */

double *PairGranularEllipsoid::pair_history(int i, int jj) const
{
  return &fix_history->firstvalue[i][size_history * jj];
}

void PairGranularEllipsoid::store_contact_rows()
{
  contact_rows.store(lmp, list, candidates, fix_history);
}

/* ---------------------------------------------------------------------- */

void PairGranularEllipsoid::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  history_update = update->setupflag == 0;
  // atoms inserted during a run (fix deposit, ...) arrive with a neighbour list build; one
  // without a shape would be read out of bounds by the candidates and the states below.
  // The build follows LAMMPS's atom sort: the bonus entries follow the atoms from here on
  if (neighbor->ago == 0) {
    EllipsoidAtomsWriter atoms(atom);
    atoms.require_shapes(lmp, "Pair granular/ellipsoid", atom->nlocal + atom->nghost);
    atoms.order_bonus_as_atoms();
  }
  const int law_slots = pipeline.law_slots;
  // new candidates without a build between (the fix's rows are still those of the list)
  if (contact_rows.live() && candidates.stale(lmp, list, respa_run)) store_contact_rows();
  const bool refresh = candidates.refresh(lmp, list, fix_history, size_history, law_slots,
                                          respa_run, counters);
  if (!contact_rows.live()) contact_rows.load(lmp, list, candidates, fix_history, size_history);
  update_states();
  const EllipsoidAtoms atoms(atom);
  const bool record = contacts.recording();
  if (record) contacts.start(update->ntimestep);

  double **x = atom->x;
  double **f = atom->f;
  double **torque = atom->torque;
  int *type = atom->type;
  const int nlocal = atom->nlocal;

  const int inum = list->inum;
  int *ilist = list->ilist;
  int **firstneigh = list->firstneigh;
  int **firsttouch = fix_history->firstflag;
  // loop invariants in locals: the calls in the loop would have them reloaded for every pair
  const EllipsoidState *const state = states.data();
  const int stride = size_history;
  const bool gaps = candidates.set_aside() > 0;

  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    int *jlist = firstneigh[i];
    int *touch = firsttouch[i];
    // the k-th candidate's row at stride * k (contiguous over all candidates)
    double *const first_history = contact_rows.first(candidates.offset(ii));

    const int *const first_candidate = candidates.first(ii);
    const int ncandidates = candidates.count(ii);
    for (int k = 0; k < ncandidates; k++) {
      const int jj = first_candidate[k];
      const int j = jlist[jj] & NEIGHMASK;
      double *history = first_history + stride * k;
      CandidatePrefetch::ahead(k, ncandidates, gaps, first_candidate, jlist, state, NEIGHMASK);
      // a candidate may still be beyond the bounding spheres: no evaluation to set up for it
      const BoundingTest bounds = bounding_test(state[i].shape, state[j].shape);
      if (forget_if_apart(bounds, history, touch[jj], law_slots, counters)) continue;

      PairHistory row(history);
      // the law's slots hold values only after a contact (zeros otherwise)
      const bool had_contact = row.state() == PairHistory::State::Contact;
      const ContactGeometry geometry =
          evaluate_near_pair(state[i].shape, state[j].shape, bounds, pipeline, history, counters);
      // keep the history of this pair while it caches a plane or a contact normal
      touch[jj] = row.in_use() ? 1 : 0;
      if (!in_contact(geometry)) {
        if (had_contact) row.clear_law<ForceLaw::MAX_HISTORY_SIZE>(law_slots);
        continue;
      }

      complete_state(atoms, i);
      complete_state(atoms, j);
      const ContactForce result = pair_force(i, j, law_index[type[i]][type[j]], history, geometry);
      const double *fi = result.force_i.data();
      f[i][0] += fi[0];
      f[i][1] += fi[1];
      f[i][2] += fi[2];
      torque[i][0] += result.torque_i[0];
      torque[i][1] += result.torque_i[1];
      torque[i][2] += result.torque_i[2];
      if (force->newton_pair || j < nlocal) {
        f[j][0] -= fi[0];
        f[j][1] -= fi[1];
        f[j][2] -= fi[2];
        torque[j][0] += result.torque_j[0];
        torque[j][1] += result.torque_j[1];
        torque[j][2] += result.torque_j[2];
      }
      if (evflag)
        ev_tally_xyz(i, j, nlocal, force->newton_pair, 0.0, 0.0, fi[0], fi[1], fi[2],
                     x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]);
      if (record) {
        ContactList::Contact c;
        c.i = i;
        c.j = j;
        c.overlap = geometry.overlap;
        for (int d = 0; d < 3; d++) {
          c.normal[d] = geometry.normal[d];
          c.point[d] = geometry.point[d];
          c.force[d] = fi[d];
        }
        contacts.add(c);
      }
    }
  }
  // find_candidates() counted its rejects; the pairs it set aside are rejects at every step
  if (!refresh) {
    counters.pairs += candidates.set_aside();
    counters.bounding_rejects += candidates.set_aside();
  }
  local_counters(pvector);
}

/* ----------------------------------------------------------------------
   one pair for compute pair/local: extra values
   overlap, nx, ny, nz (i to j), cx, cy, cz (contact point), fx, fy, fz (force on i)
------------------------------------------------------------------------- */

double PairGranularEllipsoid::single(int i, int j, int itype, int jtype, double /*rsq*/,
                                     double /*factor_coul*/, double /*factor_lj*/, double &fforce)
{
  for (int k = 0; k < single_extra; k++) svector[k] = 0.0;
  fforce = 0.0;
  // the states of i and j as they are now, not as the last force evaluation left them
  // (atoms may have moved, turned or been added since); two atoms per call
  const int nall = atom->nlocal + atom->nghost;
  if (static_cast<int>(states.size()) < nall) {
    states.resize(nall);
    state_keys.resize(nall);
  }
  const EllipsoidAtoms atoms(atom);
  atoms.update_state(i, states[i], state_keys[i]);
  atoms.update_state(j, states[j], state_keys[j]);

  // the stored history of this pair, if the neighbour list still holds it
  std::vector<double> history(size_history, 0.0);
  if (fix_history && fix_history->firstvalue) {
    int *jlist = list->firstneigh[i];
    const int jnum = list->numneigh[i];
    for (int jj = 0; jj < jnum; jj++)
      if ((jlist[jj] & NEIGHMASK) == j) {
        std::memcpy(history.data(), pair_history(i, jj), size_history * sizeof(double));
        break;
      }
  }
  store_contact_rows();    // single() reads the fix's rows
  const PipelineCounters before = counters;
  const ContactGeometry geometry =
      evaluate_pair(states[i].shape, states[j].shape, pipeline, history.data(), counters);
  counters = before;    // single() is a look, not an evaluation
  if (!in_contact(geometry)) return 0.0;
  const bool saved = history_update;
  history_update = false;
  const ContactForce result = pair_force(i, j, law_index[itype][jtype], history.data(), geometry);
  history_update = saved;

  svector[0] = geometry.overlap;
  for (int d = 0; d < 3; d++) {
    svector[1 + d] = geometry.normal[d];
    svector[4 + d] = geometry.point[d];
    svector[7 + d] = result.force_i[d];
  }
  // fforce * (x_i - x_j) is the force on i in LAMMPS's convention; use its normal part
  const Vec3 dx = states[i].shape.center - states[j].shape.center;
  const double r2 = dx.squaredNorm();
  fforce = r2 > 0.0 ? result.force_i.dot(dx) / r2 : 0.0;
  return 0.0;
}
