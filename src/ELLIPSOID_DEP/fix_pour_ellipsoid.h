/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: fix pour/ellipsoid
   Pours polydisperse general (triaxial) ellipsoids into a block or z-cylinder region on
   LAMMPS's fix pour schedule. Sizes, shapes and orientations come from the engine-free
   sampler (ellipsoid_pour_sampler.h); insertion overlaps are rejected with the kernel's
   exact ellipsoid test. See doc/fix_pour_ellipsoid.rst.
   Files: fix_pour_ellipsoid.cpp (life cycle, schedule, restart, output),
   fix_pour_ellipsoid_options.cpp (the command's arguments, the region and the walls a new
   particle must be clear of),
   fix_pour_ellipsoid_insert.cpp (inserting one batch).
------------------------------------------------------------------------- */

#ifndef LMP_FIX_POUR_ELLIPSOID_H
#define LMP_FIX_POUR_ELLIPSOID_H

#include "fix.h"

#include "ellipsoid_cell_grid.h"
#include "ellipsoid_contact.h"
#include "ellipsoid_pour_sampler.h"
#include "ellipsoid_wall_contact.h"
#include "granular_contact_time.h"

#include <memory>
#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixWallGranEllipsoid;

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

 private:
  int ninsert, ntype, seed;
  char *idregion;
  class Region *region;
  int region_style;    // 1 block, 2 z-cylinder
  double xlo, xhi, ylo, yhi, zlo, zhi;
  double xc, yc, rc;
  // the region's lateral sides a whole particle stays within: a cylinder's side, a block's
  // faces in x and y except where the block spans a periodic box (particles cross there)
  std::vector<EllipsoidDep::WallSurface> region_sides;
  // the walls acting on the poured particles (looked up at every run start): a particle is
  // inserted clear of them
  std::vector<const FixWallGranEllipsoid *> walls;

  // particles
  EllipsoidDep::PourDistribution distribution;
  std::unique_ptr<EllipsoidDep::PourSampler> sampler;
  double density;
  double bounding_max;    // largest semi-axis that can be inserted

  // insertion schedule
  double volfrac;
  int maxattempt;
  double rate, vxlo, vxhi, vylo, vyhi, vz;
  int every;     // 0: from gravity like fix pour
  bool cloud;    // release cloud: uniform heights, every particle starts with vz
  double grav;
  int nper, nfreq;
  bigint nfirst, next_insert;
  int initialized;
  double lo_current, hi_current;

  // counters
  bigint ninserted, nfailed, nrejected;
  bigint nside, nwall;    // trial positions whose particle crossed the region's side, a wall
  tagint maxtag_all;

  class RanPark *random;
  EllipsoidDep::ContactSettings contact_settings;
  double radius_one;    // for extract()

  int me, nprocs;

  // The Hertz contact and damping times of the particles this fix will insert, against each
  // other (the pair) and the walls, at the speed they can hit with: checked at every run
  // start and again at a batch when they got shorter by more than 10 % (a rising region) or
  // the time step changed. checked: the times and time step of the last check.
  ContactTimes checked, times_reported;
  double lightest_mass() const;
  double impact_speed() const;
  void check_contact_times(bool run_start);

  // the arguments of the command, in restart order: keyword and values (restart refuses a
  // re-specified pour whose arguments differ from those written)
  struct Argument {
    std::string keyword;
    std::vector<double> values;
  };
  std::vector<Argument> arguments() const;
  static std::string argument_words(const std::string &keyword, const std::vector<double> &values);

  // fix_pour_ellipsoid_options.cpp
  void options(int, char **);
  void check_region();
  void read_region();
  std::vector<double> region_values() const;
  void recheck_region();
  void check_representable() const;
  void find_walls();
  bool inside_region(const EllipsoidDep::Ellipsoid &) const;
  const FixWallGranEllipsoid *touched_wall(const EllipsoidDep::Ellipsoid &) const;

  // fix_pour_ellipsoid.cpp
  double region_volume() const;
  void report_schedule() const;

  // fix_pour_ellipsoid_insert.cpp
  void find_maxid();
  std::vector<EllipsoidDep::Ellipsoid> gather_near_region(int reserve);
  EllipsoidDep::CellGrid near_cells(const std::vector<EllipsoidDep::Ellipsoid> &, int nnew) const;
  bool overlaps(const EllipsoidDep::Ellipsoid &, const std::vector<EllipsoidDep::Ellipsoid> &,
                const EllipsoidDep::CellGrid &) const;
  bool near_region(const double *x, double bound) const;
  bool outside(int dim, double value, double lo, double hi) const;
  double batch_depth(double rn, double height) const;
  void xyz_random(double h, double *coord);
  bool owns(const double *coord) const;
  void create_particle(double *coord, const double *vnew, tagint tag, const Eigen::Vector3d &axes,
                       const double *quat);
};

}    // namespace LAMMPS_NS

#endif
