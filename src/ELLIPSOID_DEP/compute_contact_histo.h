/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: compute contact/histo
   Distribution of the angle between contact normals and +z, per unit solid angle, from the
   pair's real contacts, plus the fabric tensor of the contact normals; with weight force
   both weighted by the contacts' normal forces.
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_CONTACT_HISTO_H
#define LMP_COMPUTE_CONTACT_HISTO_H

#include "compute_angle_histo.h"

namespace LAMMPS_NS {

class ComputeContactHisto : public ComputeAngleHisto {
 public:
  ComputeContactHisto(class LAMMPS *, int, char **);
  void init() override;

  // the global vector: fabric tensor F (xx yy zz xy xz yz), its anisotropy, deviator norm,
  // number of samples
  enum Value { FABRIC, ANISOTROPY = FABRIC + 6, DEVIATOR, SAMPLES, NVALUES };

 protected:
  bool parse_keyword(const char *, const char *) override;
  void prepare() override;
  void accumulate(const SlabOption::Bounds &slab) override;
  void finish_vector(const double *moments, double weight, double count,
                     const double *extra) override;

 private:
  const class ContactList *contacts;
  bool select_center;    // false: contact point in slab, true: the side's particle centre
  bool weight_force;     // samples weighted by |f_n| (weight force) or 1 (weight none)
};

}    // namespace LAMMPS_NS

#endif
