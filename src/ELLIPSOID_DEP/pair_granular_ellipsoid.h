/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: pair_style granular/ellipsoid
   Contact of general ellipsoids (Baram & Lind): bounding spheres, cached separating planes,
   Wang et al. separation test, Perram-type contact with normal correction, Hertz forces.
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_GRANULAR_ELLIPSOID_H
#define LMP_PAIR_GRANULAR_ELLIPSOID_H

#include "pair.h"

#include "ellipsoid_contact.h"
#include "ellipsoid_force_law.h"

#include <vector>

namespace LAMMPS_NS {

class PairGranularEllipsoid : public Pair {
 public:
  // One contact of the last force evaluation, for the computes (never a radius-sum guess).
  struct Contact {
    int i, j;            // local indices (j may be a ghost)
    double normal[3];    // unit, from i to j
    double point[3];     // contact point, box coordinates
    double overlap;
    double force[3];    // total force on i
  };

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

  // The pair style granular/ellipsoid in use; an error naming who (e.g. "Compute
  // contact/histo") when there is none.
  static PairGranularEllipsoid *find(class LAMMPS *lmp, const char *who);
  // Ask the pair to keep the list of contacts of each force evaluation (computes call this in
  // their init; the list costs nothing when nobody asked).
  void request_contacts() { record_contacts = true; }
  const std::vector<Contact> &contacts() const { return contact_list; }
  // timestep of the force evaluation that filled contacts() (-1: never recorded)
  bigint contacts_timestep() const { return contact_step; }
  // Counters since the pair was created: this rank's, and summed over all ranks.
  void local_counters(double *out) const;
  void global_counters(double *out) const;
  // pairs, plane hits, Wang tests, contacts, iterations, corrections, not converged,
  // bounding rejects, degenerate, continued contacts (re-evaluated without the Wang test)
  static constexpr int NUM_COUNTERS = 10;

 protected:
  EllipsoidDep::PipelineSettings pipeline;
  EllipsoidDep::PipelineCounters counters;
  double counters_global[NUM_COUNTERS];

  // per type pair (1..ntypes): index into laws
  int **law_index;
  std::vector<EllipsoidDep::ForceLaw> laws;
  double *max_bounding_dynamic;    // per type, largest bounding radius (incl. future pours)

  class FixDummy *fix_dummy;
  class FixNeighHistory *fix_history;
  int size_history;    // PAIR_CACHE_SIZE + tangential history (3) when any law needs it
  int tangential_offset;
  bool history_update;
  int freeze_group_bit;

  bool record_contacts;
  std::vector<Contact> contact_list;
  bigint contact_step = -1;

  // per-atom geometry for owned + ghost atoms, rebuilt each force evaluation
  std::vector<EllipsoidDep::Ellipsoid> shapes;
  std::vector<EllipsoidDep::Vec3> omegas;
  void update_shapes();

  // one pair: geometry from the pipeline, then the force law; returns true on contact
  bool pair_force(int i, int j, int law, double *history, EllipsoidDep::ContactGeometry &geometry,
                  EllipsoidDep::ContactForce &result);

  void allocate();
  int add_law(const EllipsoidDep::ForceLaw &law);
  bool law_of_pair(int i, int j, EllipsoidDep::ForceLaw &law, std::string &refusal) const;

  // per-pair history size of the run that wrote the restart file this pair was read from
  // (0: none read, or no history written)
  int restart_history_size;
  // shortest Hertz contact time over the type pairs (granular_contact_time.h); 0: undefined
  double impact_velocity;    // pair_style impact_velocity; 0: twice the largest atom speed
  double contact_time;
  double contact_time_reported;
  void update_contact_time();
};

}    // namespace LAMMPS_NS

#endif
