/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: compute orient/histo
   Distribution of the angle between a principal axis of each ellipsoid (longest, middle or
   shortest) and +z, per unit solid angle, plus the nematic order tensor of that axis.
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_ORIENT_HISTO_H
#define LMP_COMPUTE_ORIENT_HISTO_H

#include "compute_angle_histo.h"

namespace LAMMPS_NS {

class EllipsoidAtoms;

class ComputeOrientHisto : public ComputeAngleHisto {
 public:
  ComputeOrientHisto(class LAMMPS *, int, char **);
  ~ComputeOrientHisto() override;
  void init() override;
  void compute_peratom() override;
  double memory_usage() override;

  // the global vector: order parameter S, director (x y z), Q_zz, <cos^2 theta>, particles
  enum Value { S, DIRECTOR, QZZ = DIRECTOR + 3, COS2, PARTICLES, NVALUES };

 protected:
  bool parse_keyword(const char *, const char *) override;
  void accumulate(const SlabOption::Bounds &slab) override;
  void finish_vector(const double *moments, double weight, double count,
                     const double *extra) override;

 private:
  int which_axis;    // 0 longest, 1 middle, 2 shortest semi-axis
  bool fold;         // theta folded into [0, pi/2] (each axis once)
  int nmax;
  double *axis_angle;    // per-atom acos|u_z|

  void chosen_axis(const EllipsoidAtoms &, int i, double *u) const;
};

}    // namespace LAMMPS_NS

#endif
