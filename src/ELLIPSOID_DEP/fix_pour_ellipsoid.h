/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: fix pour/ellipsoid
   Pours polydisperse general (triaxial) ellipsoids into a block or z-cylinder region:
   sizes from the volume distribution V(r) ~ (r-rmin)^(alpha-1) (rmax-r)^(beta-1),
   shapes eta = a/b, zeta = b/c, orientations uniform on SO(3), insertion overlaps
   rejected with the kernel's exact ellipsoid test. See doc/fix_pour_ellipsoid.rst.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_POUR_ELLIPSOID_H
#define LMP_FIX_POUR_ELLIPSOID_H

#include "fix.h"

#include "ellipsoid_contact.h"

#include <vector>

namespace LAMMPS_NS {

class FixPourEllipsoid : public Fix {
 public:
  FixPourEllipsoid(class LAMMPS *, int, char **);
  ~FixPourEllipsoid() override;
  int setmask() override;
  void init() override;
  void setup_pre_exchange() override;
  void pre_exchange() override;
  void post_run() override;
  void reset_dt() override;
  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  void *extract(const char *, int &) override;

  // --- sampling, public for the unit tests through the fix's own parameters ---
  double sample_size();                              // r from n(r) ~ V(r) / r^3
  void sample_shape(double r, double *semi_axes);    // (a, b, c) with a >= b >= c
  void sample_quat(double *quat);                    // uniform on SO(3)

 private:
  int ninsert, ntype, seed;
  char *idregion;
  class Region *region;
  int region_style;    // 1 block, 2 z-cylinder
  double xlo, xhi, ylo, yhi, zlo, zhi;
  double xc, yc, rc;

  // size and shape
  double rmin, rmax, alpha, beta;
  double eta, zeta, delta_eta, delta_zeta;
  double density;
  double acceptance;      // expected acceptance of the size rejection sampler
  double mean_volume;     // mean particle volume under n(r)
  double bounding_max;    // largest semi-axis that can be inserted

  // insertion schedule
  double volfrac;
  int maxattempt;
  double rate, vxlo, vxhi, vylo, vyhi, vz;
  int every;    // 0: from gravity like fix pour
  double grav;
  int nper, nfreq;
  bigint nfirst, next_insert;
  int initialized;
  double lo_current, hi_current;

  // counters
  bigint ninserted, nfailed, nrejected;
  tagint maxtag_all;

  class RanPark *random;
  EllipsoidDep::ContactSettings contact_settings;
  double radius_one;    // for extract()

  int me, nprocs;

  void options(int, char **);
  void find_maxid();
  bool near_region(const double *x, double bound) const;
  bool outside(int dim, double value, double lo, double hi) const;
  void xyz_random(double h, double *coord);
  double beta_variate(double a, double b);
  double gamma_variate(double a);
  double normal_variate();
  double shape_value(double mean, double delta);
  void setup_size_statistics();
};

}    // namespace LAMMPS_NS

#endif
