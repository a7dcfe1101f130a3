/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: compute contact/histo
   Distribution of the angle between contact normals and +z, per unit solid angle, from the
   pair's real contacts, plus the fabric tensor of the contact normals.
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_CONTACT_HISTO_H
#define LMP_COMPUTE_CONTACT_HISTO_H

#include "compute.h"

#include <string>

namespace LAMMPS_NS {

class ComputeContactHisto : public Compute {
 public:
  ComputeContactHisto(class LAMMPS *, int, char **);
  ~ComputeContactHisto() override;
  void init() override;
  void compute_vector() override;
  void compute_array() override;
  std::string get_thermo_colname(int) override;

  static constexpr int NVALUES = 9;

 private:
  class PairGranularEllipsoid *pair;
  int nbins;
  bool have_zlo, have_zhi;
  double zlo_user, zhi_user;
  char *slab_id;                 // packing/ellipsoid compute giving zlo, zhi
  class Compute *slab_compute;
  int select_center;             // 0: contact point in slab, 1: the side's particle centre
  double *hist, *hist_all;

  void tally();
};

}    // namespace LAMMPS_NS

#endif
