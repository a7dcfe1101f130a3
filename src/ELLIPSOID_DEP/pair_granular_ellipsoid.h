/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: pair_style granular/ellipsoid
   Contact of general ellipsoids (Baram & Lind): bounding spheres, cached separating planes,
   Wang et al. separation test, Perram-type contact with normal correction, Hertz forces.
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_GRANULAR_ELLIPSOID_H
#define LMP_PAIR_GRANULAR_ELLIPSOID_H

#include "pair.h"

#include "ellipsoid_force_law.h"
#include "ellipsoid_kernel.h"
#include "granular_candidates.h"
#include "granular_contact_rows.h"
#include "granular_contact_time.h"
#include "granular_ellipsoid_atoms.h"
#include "granular_ellipsoid_contacts.h"

#include <string>
#include <unordered_map>
#include <vector>

namespace LAMMPS_NS {

class PairGranularEllipsoid : public Pair {
 public:
  PairGranularEllipsoid(class LAMMPS *);
  ~PairGranularEllipsoid() override;

  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  double single(int, int, int, int, double, double, double, double &) override;
  void *extract(const char *, int &) override;
  void finish() override;
  double memory_usage() override;

  // Counters since the pair was created: this rank's, and summed over all ranks, in the
  // order of EllipsoidDep::PIPELINE_COUNTERS (also the order of compute pair's vector).
  void local_counters(double *out) const;
  void global_counters(double *out) const;
  void *extract_counters(const char *name, int &dim);    // null: not a counter name
  static constexpr int NUM_COUNTERS = EllipsoidDep::NUM_PIPELINE_COUNTERS;
  // The law of types i j, set or mixed (false with the reason when there is none); public for
  // fix pour/ellipsoid's time-step check of the particles it will insert.
  bool law_of_pair(int i, int j, EllipsoidDep::ForceLaw &law, std::string &refusal) const;
  // the candidates' rows copied back into the history fix's (FixNeighHistoryRows)
  void store_contact_rows();

 protected:
  EllipsoidDep::PipelineSettings pipeline;
  EllipsoidDep::PipelineCounters counters;
  double counters_extracted[NUM_COUNTERS];

  // per type pair (1..ntypes): index into laws
  int **law_index;
  std::vector<EllipsoidDep::ForceLaw> laws;
  double *max_bounding_dynamic;    // per type, largest bounding radius (incl. future pours)

  class FixDummy *fix_dummy;
  FixStoreContactRows *fix_store_rows;    // before fix_history in the fix list
  class FixNeighHistory *fix_history;
  std::string history_id;    // fix_history's ID, which names its size (history_fix_id())
  int size_history;       // EllipsoidDep::PairHistory::size(the largest history of the laws)
  bool history_update;    // false: look at the stored history without advancing it
  int freeze_group_bit;

  ContactList contacts;
  // the history doubles of neighbour jj of i (PairHistory layout)
  double *pair_history(int i, int jj) const;

  // per-atom state of owned + ghost atoms, rebuilt each force evaluation for the atoms of the
  // candidate pairs (Candidates::state_needed(); the others' states are stale)
  std::vector<EllipsoidState> states;
  std::vector<ShapeKey> state_keys;    // what states[i].shape was last built from
  // whether states[i].omega is this evaluation's: it is computed at the atom's first contact
  // (most candidates of a dilute scene never touch)
  std::vector<char> omega_known;
  // per ghost atom (index - nlocal): the owned atom of the same ID (a periodic image on this
  // rank) or -1, found when the ghosts change (neighbour list builds)
  std::vector<int> ghost_owner;
  std::unordered_map<tagint, int> owned_index;    // scratch of find_ghost_owners()
  void find_ghost_owners();
  void update_states();
  // states[i].omega, once per evaluation (inline: a bed at rest asks at every contact)
  void complete_state(const EllipsoidAtoms &atoms, int i)
  {
    if (omega_known[i]) return;
    atoms.add_omega(i, states[i]);
    omega_known[i] = 1;
  }

  // the neighbour pairs each force evaluation visits (granular_candidates.h)
  Candidates candidates;
  // their history rows, contiguous in the loop's order while live (granular_contact_rows.h)
  ContactRows contact_rows;
  // r-RESPA builds before its inner levels move the atoms, so the first evaluation after a
  // build does not see the build's positions (set by init_style for the run)
  bool respa_run;

  // the force law on the contact geometry of atoms i and j (in contact: see in_contact())
  EllipsoidDep::ContactForce pair_force(int i, int j, int law, double *history,
                                        const EllipsoidDep::ContactGeometry &geometry) const;

  void allocate();
  int add_law(const EllipsoidDep::ForceLaw &law);

  // per-pair history layout (PairHistory::LAYOUT_VERSION; 0 for layouts 1 and 2, whose files
  // hold the bare size) and size of the run that wrote the restart file this pair was read
  // from (size 0: none read, or no history written); one int in the file, history_record()
  static constexpr int HISTORY_RECORD_BASE = 100;
  static int history_record(int size)
  {
    return EllipsoidDep::PairHistory::LAYOUT_VERSION * HISTORY_RECORD_BASE + size;
  }
  int restart_history_layout, restart_history_size;
  double impact_velocity;    // pair_style impact_velocity; 0: twice the largest atom speed
  // shortest Hertz contact and damping times over the type pairs (granular_contact_time.h);
  // 0: undefined (no moving atoms; for the damping time also an undamped law)
  double contact_time, damping_time;
  ContactTimes times_reported;
  void update_contact_times();
};

}    // namespace LAMMPS_NS

#endif
