/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: the neighbour pairs a force evaluation of pair granular/ellipsoid visits
   (the candidates), and the atoms whose states those pairs need.

   After a neighbour list build, the candidates are the neighbours whose bounding spheres
   (positions and largest semi-axes) are within the skin, as LAMMPS's size lists for spheres
   keep radsum + skin; the others are apart until the next build when no atom moves half the
   skin in between (builds_keep_skin()). Those set aside are forgotten (history cleared, touch
   0) and counted as bounding rejects at every evaluation. Otherwise, or when the list changed
   at a step without a build, every neighbour is a candidate.
------------------------------------------------------------------------- */

#ifndef LMP_GRANULAR_CANDIDATES_H
#define LMP_GRANULAR_CANDIDATES_H

#include "lmptype.h"

#include "ellipsoid_force_law.h"
#include "ellipsoid_kernel.h"

#include <cstddef>
#include <vector>

namespace LAMMPS_NS {

class LAMMPS;
class NeighList;
class FixNeighHistory;

class Candidates {
 public:
  // The candidates of the current list, found again when they are stale (true then; the
  // rejects of a new search are counted in counters); the history rows are `stride` doubles,
  // the last law_slots of them the force law's. respa: the run is an r-RESPA run.
  bool refresh(LAMMPS *lmp, NeighList *list, FixNeighHistory *history, int stride,
               int law_slots, bool respa, EllipsoidDep::PipelineCounters &counters);

  // i's candidates (the ii-th atom of the list): count(ii) neighbour indices jj from first(ii)
  const int *first(int ii) const { return jj.data() + start[ii]; }
  int count(int ii) const { return start[ii + 1] - start[ii]; }
  // the place of i's first candidate among all (offset(inum) candidates in all)
  int offset(int ii) const { return start[ii]; }
  // pairs set aside at the last search (0: every neighbour is a candidate)
  bigint set_aside() const { return aside; }
  // per owned and ghost atom: 1 when a candidate pair holds it
  const std::vector<char> &state_needed() const { return needed; }

  std::size_t memory_usage() const
  {
    return (jj.capacity() + start.capacity()) * sizeof(int) + needed.capacity();
  }

  // the builds keep every pair within the skin of its last build: a build whenever an atom
  // has moved half the skin (neigh_modify every 1 delay 0 check yes once no, LAMMPS's
  // default), not under r-RESPA (whose first evaluation after a build does not see the
  // build's positions)
  static bool builds_keep_skin(LAMMPS *lmp, bool respa);
  // refresh() would find them again
  bool stale(LAMMPS *lmp, NeighList *list, bool respa) const;

 private:
  std::vector<int> jj, start;
  std::vector<char> needed;
  bigint step = -1, build_count = -1;    // Neighbor::lastcall and ncalls of the search
  bigint aside = 0;

  void find(LAMMPS *lmp, NeighList *list, FixNeighHistory *history, int stride,
            int law_slots, EllipsoidDep::PipelineCounters &counters);
  void all(LAMMPS *lmp, NeighList *list);
};

// A pair whose bounding spheres are apart (true): its history row cleared (the law's
// law_slots too), not kept at the next list build (touch 0), counted as a bounding reject.
// law_slots is a local of the caller's: a member would be reloaded after every store through
// touch.
inline bool forget_if_apart(const EllipsoidDep::BoundingTest &t, double *history, int &touch,
                            int law_slots, EllipsoidDep::PipelineCounters &counters)
{
  if (!t.apart) return false;
  // a row not in use holds zeros, the law's slots included (PairHistory::forget())
  EllipsoidDep::PairHistory row(history);
  if (row.in_use()) row.clear_law<EllipsoidDep::ForceLaw::MAX_HISTORY_SIZE>(law_slots);
  EllipsoidDep::reject_apart(t, history, counters);
  touch = 0;
  return true;
}

/* ----------------------------------------------------------------------
   the loop over candidates reads each one's state at gaps, which the hardware prefetcher does
   not follow as it follows a sweep over every neighbour: then the state's cache lines are
   asked for PREFETCH_AHEAD candidates ahead; without gaps the first line of the next one.
   Their history rows are contiguous (ContactRows): a sweep the hardware follows
------------------------------------------------------------------------- */

namespace CandidatePrefetch {
  constexpr int PREFETCH_AHEAD = 4;

  inline void line(const void *p)
  {
#if defined(__GNUC__)
    __builtin_prefetch(p);
#endif
  }

  // every cache line of n > 0 bytes from p
  inline void bytes(const void *p, std::size_t n)
  {
    const char *c = static_cast<const char *>(p);
    for (std::size_t offset = 0; offset < n; offset += 64) line(c + offset);
    line(c + n - 1);
  }

  // before candidate k of n (neighbour indices candidates[], neighbours jlist[]): states of
  // type State
  template <class State>
  inline void ahead(int k, int n, bool gaps, const int *candidates, const int *jlist,
                    const State *state, int neighmask)
  {
    if (gaps) {
      if (k == 0)
        for (int a = 1; a < PREFETCH_AHEAD && a < n; a++)
          bytes(&state[jlist[candidates[a]] & neighmask], sizeof(State));
      if (k + PREFETCH_AHEAD < n)
        bytes(&state[jlist[candidates[k + PREFETCH_AHEAD]] & neighmask], sizeof(State));
    } else if (k + 1 < n) {
      line(&state[jlist[candidates[k + 1]] & neighmask]);
    }
  }
}    // namespace CandidatePrefetch

}    // namespace LAMMPS_NS

#endif
