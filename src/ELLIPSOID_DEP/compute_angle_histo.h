/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: common base of compute contact/histo and compute orient/histo.
   Histogram of the angle theta between sample directions and +z, normalised per unit solid
   angle, optionally restricted to a horizontal slab (zlo/zhi or the slab of a
   packing/ellipsoid compute), plus the second-moment tensor <u u^T> of the directions from
   which each subclass derives its global vector (fabric tensor, nematic order tensor).
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_ANGLE_HISTO_H
#define LMP_COMPUTE_ANGLE_HISTO_H

#include "compute.h"

#include <string>

namespace LAMMPS_NS {

class ComputeAngleHisto : public Compute {
 public:
  // the slab keyword reads these elements of compute packing/ellipsoid's vector, as a c_ID[5]
  // and c_ID[6] reference would: its documented zlo and zhi (its doc page; test_computes.py
  // checks the histograms against zlo/zhi given as numbers)
  static constexpr int SLAB_ZLO_ELEMENT = 5, SLAB_ZHI_ELEMENT = 6;

  ~ComputeAngleHisto() override;
  void init() override;
  void compute_vector() override;
  void compute_array() override;
  std::string get_thermo_colname(int) override;

 protected:
  // name: the style as it appears in messages ("contact/histo"); nvalues, colnames: the global
  // vector and its thermo column names; nextra: per-rank sums of the subclass's own, reduced
  // with the histogram and passed to finish_vector()
  ComputeAngleHisto(class LAMMPS *, int, char **, const char *name, int nvalues,
                    const char *const *colnames, int nextra);

  // Parse the keywords of arg[3..narg) (every keyword takes one value): bins, zlo, zhi, slab
  // here, the rest through parse_keyword(); then allocate the array. Called by the subclass
  // constructor (the subclass's parse_keyword() is then the one called).
  void parse_args(int narg, char **arg);
  // true when the subclass knows keyword key (value: its argument)
  virtual bool parse_keyword(const char * /*key*/, const char * /*value*/) { return false; }

  // start of every evaluation, before the slab is looked up (default: nothing)
  virtual void prepare() {}
  // add the local samples with add_direction() / bin() / add_moment(); zlo, zhi: the slab
  // (-/+ HUGE_VAL when none given), use_slab: any of zlo, zhi, slab given
  virtual void accumulate(double zlo, double zhi, bool use_slab) = 0;
  // fill vector from the reduced sums: moments = sum of u u^T (xx yy zz xy xz yz) over count
  // samples (add_moment calls), extra = the nextra reduced sums of the subclass
  virtual void finish_vector(const double *moments, double count, const double *extra) = 0;

  // histogram bin of the angle acos(cz)
  int bin_of(double cz) const;
  void bin(double cz) { hist[bin_of(cz)] += 1.0; }
  void add_moment(const double *u);
  // one sample direction u: its angle is binned and u u^T added to the moments
  void add_direction(const double *u)
  {
    bin(u[2]);
    add_moment(u);
  }
  double *extra_sums() { return hist + nbins + NMOMENT; }    // this rank's nextra sums

  const char *name;
  int nvalues;
  const char *const *colnames;
  int nextra;
  int nbins;
  double theta_max;    // bins cover theta in [0, theta_max] (pi, or pi/2 for folded axes)

 private:
  bool have_zlo, have_zhi;
  double zlo_user, zhi_user;
  char *slab_id;    // packing/ellipsoid compute giving zlo, zhi
  class Compute *slab_compute;
  // layout of the sums (local and reduced): nbins counts, then NMOMENT values (the 6 moment
  // sums xx yy zz xy xz yz and at SAMPLE_COUNT the number of samples), then the nextra sums
  static constexpr int SAMPLE_COUNT = 6, NMOMENT = 7;
  double *hist, *hist_all;

  void tally();
};

}    // namespace LAMMPS_NS

#endif
