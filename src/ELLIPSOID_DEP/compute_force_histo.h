/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: compute force/histo
   Distribution P(f/<f>) of the normal contact forces of the pair's real contacts, over the
   samples of contact/histo (granular_contact_samples.h: group, slab, select).
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_FORCE_HISTO_H
#define LMP_COMPUTE_FORCE_HISTO_H

#include "compute.h"
#include "granular_slab.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class ComputeForceHisto : public Compute {
 public:
  ComputeForceHisto(class LAMMPS *, int, char **);
  ~ComputeForceHisto() override;
  void init() override;
  void compute_vector() override;
  void compute_array() override;
  std::string get_thermo_colname(int) override;
  double memory_usage() override;

  // the global vector: mean |f_n|, number of samples, fraction at or beyond max, largest
  // f/<f>, fraction of attractive (f_n < 0) samples
  enum Value { MEAN, SAMPLES, BEYOND, LARGEST, ATTRACTIVE, NVALUES };

 private:
  int nbins;
  double xmax;    // bins cover f/<f> in [0, xmax]
  bool select_center;
  SlabOption slab;
  const class ContactList *contacts;
  std::vector<double> forces;    // this rank's |f_n| of the samples
  std::vector<double> counts, counts_all;

  void tally();
};

}    // namespace LAMMPS_NS

#endif
