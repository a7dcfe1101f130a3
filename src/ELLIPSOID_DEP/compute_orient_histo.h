/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: compute orient/histo
   Distribution of the angle between a principal axis of each ellipsoid (longest, middle or
   shortest) and +z, per unit solid angle, plus the nematic order tensor of that axis.
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_ORIENT_HISTO_H
#define LMP_COMPUTE_ORIENT_HISTO_H

#include "compute.h"

#include <string>

namespace LAMMPS_NS {

class ComputeOrientHisto : public Compute {
 public:
  ComputeOrientHisto(class LAMMPS *, int, char **);
  ~ComputeOrientHisto() override;
  void init() override;
  void compute_vector() override;
  void compute_array() override;
  std::string get_thermo_colname(int) override;

  static constexpr int NVALUES = 7;

 private:
  int which_axis;                // 0 longest, 1 middle, 2 shortest semi-axis
  int nbins;
  bool fold;                     // theta folded into [0, pi/2] (each axis once)
  bool have_zlo, have_zhi;
  double zlo_user, zhi_user;
  char *slab_id;
  class Compute *slab_compute;
  double *hist, *hist_all;

  void tally();
};

}    // namespace LAMMPS_NS

#endif
