/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: the history rows of the candidate pairs of pair granular/ellipsoid in one
   contiguous array, in the order the force loop visits them.

   fix NEIGH_HISTORY keeps a row per neighbour; the loop over candidates visits them with gaps
   (the pairs set aside). Here the candidates' rows are copied into the pair's own array when
   the candidates are found (load) and copied back into the fix's rows (store) before the fix
   reads them: before its pre_exchange (every neighbour list build in a run, write_restart, the
   end of a run, minimisation), through FixStoreContactRows, and before single() looks at them.
   Exchange, ghosts and restart files stay fix NEIGH_HISTORY's.
------------------------------------------------------------------------- */

#ifndef LMP_GRANULAR_CONTACT_ROWS_H
#define LMP_GRANULAR_CONTACT_ROWS_H

#include "fix.h"
#include "fix_neigh_history.h"
#include "lmptype.h"

#include <cstddef>
#include <vector>

namespace LAMMPS_NS {

class Candidates;
class NeighList;

class ContactRows {
 public:
  // the rows of every candidate, `stride` doubles each, copied from the fix's
  void load(LAMMPS *lmp, NeighList *list, const Candidates &candidates,
            FixNeighHistory *history, int stride);
  // the rows copied back into the fix's (no longer live afterwards); a no-op when not live
  void store(LAMMPS *lmp, NeighList *list, const Candidates &candidates,
             FixNeighHistory *history);
  bool live() const { return is_live; }
  // the rows of the ii-th atom's candidates, in the candidates' order
  double *first(int candidate_offset) { return rows.data() + stride * candidate_offset; }

  std::size_t memory_usage() const { return rows.capacity() * sizeof(double); }

 private:
  std::vector<double> rows;
  int stride = 0;
  bool is_live = false;
  bigint build_step = -1, build_count = -1;    // the list build the rows were loaded from
};

// The internal fix that stores a pair's ContactRows back before fix NEIGH_HISTORY reads its
// rows: it sits before that fix in the fix list (the pair puts it there), so its pre_exchange,
// min_pre_exchange, post_run and write_restart come first. LAMMPS's own NEIGH_HISTORY keeps
// the exchange, the ghosts and the restart files (restart files of earlier versions read as
// before).
class FixStoreContactRows : public Fix {
 public:
  FixStoreContactRows(LAMMPS *lmp, int narg, char **arg);
  int setmask() override;
  void pre_exchange() override { store(); }
  void min_pre_exchange() override { store(); }
  void post_run() override { store(); }
  // an empty record (write_restart calls the fixes with a global record in order)
  void write_restart(FILE *fp) override;

  class PairGranularEllipsoid *pair = nullptr;

 private:
  void store();
};

}    // namespace LAMMPS_NS

#endif
