/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: compute packing/profile
   Solid fraction phi(z) of a deposit of ellipsoids in horizontal bins of a chosen width, from
   the exact volume of each ellipsoid inside each bin.
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_PACKING_PROFILE_H
#define LMP_COMPUTE_PACKING_PROFILE_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputePackingProfile : public Compute {
 public:
  ComputePackingProfile(class LAMMPS *, int, char **);
  ~ComputePackingProfile() override;
  void init() override;
  void compute_array() override;
  double memory_usage() override;

  static constexpr int NCOLUMNS = 4;

 private:
  double width;     // bin width
  double zlo;       // bottom of the first bin
  int nbins;        // bin k spans [zlo + k width, zlo + (k+1) width]
  double *local;    // per bin: solid volume, centres (this rank), then reduced into array
};

}    // namespace LAMMPS_NS

#endif
