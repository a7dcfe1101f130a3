/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: common base of compute contact/histo and compute orient/histo.
   Histogram of the angle theta between sample directions and +z, normalised per unit solid
   angle, optionally restricted to a horizontal slab (SlabOption: zlo/zhi or the slab of a
   packing/ellipsoid compute), plus the second-moment tensor <u u^T> of the directions from
   which each subclass derives its global vector (fabric tensor, nematic order tensor).
   Samples may carry a weight (contact/histo weight force); P and <u u^T> are then weighted.
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_ANGLE_HISTO_H
#define LMP_COMPUTE_ANGLE_HISTO_H

#include "compute.h"
#include "granular_slab.h"

#include <string>

namespace LAMMPS_NS {

class ComputeAngleHisto : public Compute {
 public:
  ~ComputeAngleHisto() override;
  void init() override;
  void compute_vector() override;
  void compute_array() override;
  std::string get_thermo_colname(int) override;

 protected:
  // name: the style as it appears in messages ("contact/histo"); nvalues, colnames: the global
  // vector and its thermo column names; nextra: per-rank sums of the subclass's own, reduced
  // with the histogram and passed to finish_vector(); value_column: the array has a 4th
  // column, the mean of the samples' values (bin() argument v) in each bin
  ComputeAngleHisto(class LAMMPS *, int, char **, const char *name, int nvalues,
                    const char *const *colnames, int nextra, bool value_column = false);

  // Parse the keywords of arg[3..narg) (every keyword takes one value): bins and the slab's
  // here, the rest through parse_keyword(); then allocate the array. Called by the subclass
  // constructor (the subclass's parse_keyword() is then the one called).
  void parse_args(int narg, char **arg);
  // true when the subclass knows keyword key (value: its argument)
  virtual bool parse_keyword(const char * /*key*/, const char * /*value*/) { return false; }

  // start of every evaluation, before the slab is looked up (default: nothing)
  virtual void prepare() {}
  // add the local samples with add_direction() / bin() / add_moment(); the slab's bounds
  // are -/+ HUGE_VAL when none was given
  virtual void accumulate(const SlabOption::Bounds &slab) = 0;
  // fill vector from the reduced sums: moments = sum of w u u^T (xx yy zz xy xz yz) over the
  // add_moment calls, weight = the sum of their w, count = their number, extra = the nextra
  // reduced sums of the subclass
  virtual void finish_vector(const double *moments, double weight, double count,
                             const double *extra) = 0;

  // histogram bin of the angle acos(cz)
  int bin_of(double cz) const;
  // one sample in the bin of acos(cz): count 1, weight w, value v
  void bin(double cz, double w = 1.0, double v = 0.0);
  void add_moment(const double *u, double w = 1.0);
  // one sample direction u: its angle is binned and w u u^T added to the moments
  void add_direction(const double *u, double w = 1.0, double v = 0.0)
  {
    bin(u[2], w, v);
    add_moment(u, w);
  }
  double *extra_sums() { return hist + 3 * nbins + NMOMENT; }    // this rank's nextra sums

  const char *name;
  int nvalues;
  const char *const *colnames;
  int nextra;
  bool value_column;
  int nbins;
  double theta_max;    // bins cover theta in [0, theta_max] (pi, or pi/2 for folded axes)

 private:
  SlabOption slab;
  // layout of the sums (local and reduced): per bin the weights, counts and values (3 nbins),
  // then NMOMENT values (the 6 moment sums xx yy zz xy xz yz, the sum of their weights at
  // WEIGHT_SUM, their number at SAMPLE_COUNT), then the nextra sums
  static constexpr int WEIGHT_SUM = 6, SAMPLE_COUNT = 7, NMOMENT = 8;
  double *hist, *hist_all;

  void tally();
};

}    // namespace LAMMPS_NS

#endif
