/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: compute packing/ellipsoid
   Volume fraction of a horizontal slab from the exact volume of each ellipsoid inside it, and
   the mean coordination number (with and without rattlers) from the pair's real contacts.
------------------------------------------------------------------------- */

#ifndef LMP_COMPUTE_PACKING_ELLIPSOID_H
#define LMP_COMPUTE_PACKING_ELLIPSOID_H

#include "compute.h"

#include <string>

namespace LAMMPS_NS {

class ComputePackingEllipsoid : public Compute {
 public:
  ComputePackingEllipsoid(class LAMMPS *, int, char **);
  ~ComputePackingEllipsoid() override;
  void init() override;
  void compute_vector() override;
  std::string get_thermo_colname(int) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

  // the global vector (1-based in input scripts: PHI is c_ID[1])
  enum Value { PHI, NSLAB, Z, Z_NORATTLER, ZLO, ZHI, NRATTLER, DMEAN, VSOLID, NVALUES };

 private:
  const class ContactList *contacts;
  bool automatic;    // auto mode: slab from the deposit's extent
  double zlo_user, zhi_user;
  int zlo_edge, zhi_edge;    // 1: EDGE (box bound)
  double nbottom, ntop;      // auto: excluded mean diameters at the bottom and below the surface
  bool floor_given;
  double floor_z;      // auto: z of the floor (default: lowest particle bottom)
  int surface_mode;    // auto: 0 = max particle top, 1 = mean of per-column maxima
  int rattler_min;     // rattlers: fewer than this many contacts (iterated)

  int nmax;
  double *ncontact;    // per atom (owned + ghost): contacts with active partners
  double *active;      // per atom: 1 while in the group and not (yet) a rattler

  void grow();
  void count_contacts(int nall);
  void slab_bounds(double &zlo, double &zhi, double &dmean);
};

}    // namespace LAMMPS_NS

#endif
