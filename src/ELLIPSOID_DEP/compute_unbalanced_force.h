/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: compute unbalanced/force
   The unbalanced force ratio of a granular packing (YADE's unbalancedForce(), PFC's mean force
   ratio): the mean |net force| of the group's particles, gravity and walls included, over the
   mean |normal + tangential force| of the contacts, the pair's and the given walls'.
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_UNBALANCED_FORCE_H
#define LMP_COMPUTE_UNBALANCED_FORCE_H

#include "compute.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class ComputeUnbalancedForce : public Compute {
 public:
  ComputeUnbalancedForce(class LAMMPS *, int, char **);
  ~ComputeUnbalancedForce() override;
  void init() override;
  double compute_scalar() override;
  void compute_vector() override;
  std::string get_thermo_colname(int) override;

  // the global vector: the ratio, mean |net force|, mean |contact force|, contacts counted
  enum Value { RATIO, NET, CONTACT, CONTACTS, NVALUES };

 private:
  std::vector<std::string> wall_ids;
  std::vector<class Fix *> walls;
  const class ContactList *contacts;

  void find_walls();
  void tally();
};

}    // namespace LAMMPS_NS

#endif
