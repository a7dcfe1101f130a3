/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/ellipsoid
   Flat walls (planes normal to x, y or z) for general ellipsoids: the kernel's exact
   ellipsoid-plane contact and the SAME force law as pair granular/ellipsoid (ForceLaw,
   parsed by parse_force_law from the pair_coeff words). See doc/fix_wall_gran_ellipsoid.rst.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_WALL_GRAN_ELLIPSOID_H
#define LMP_FIX_WALL_GRAN_ELLIPSOID_H

#include "fix.h"

#include "ellipsoid_force_law.h"
#include "granular_contact_time.h"

#include <vector>

namespace LAMMPS_NS {

class FixWallGranEllipsoid : public Fix {
 public:
  FixWallGranEllipsoid(class LAMMPS *, int, char **);
  ~FixWallGranEllipsoid() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;
  double compute_vector(int) override;
  double memory_usage() override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

  // the walls' law (fix pour/ellipsoid checks the time step of its particles against it)
  const EllipsoidDep::ForceLaw &force_law() const { return law; }

 private:
  struct Wall {
    int dim;                      // 0, 1, 2 = x, y, z
    int side;                     // -1: lower wall (solid below), +1: upper wall (solid above)
    double coord;                 // position of the plane
    EllipsoidDep::Vec3 normal;    // unit, into the particle region
    double offset;                // solid half-space {x : normal.x <= offset}
  };
  std::vector<Wall> walls;
  EllipsoidDep::ForceLaw law;
  int size_history;        // the law's history size times the number of walls
  double **history_one;    // per atom, per wall
  bool history_update;
  double impact_velocity;          // keyword; 0: the fastest atom of the group
  ContactTimes times_reported;    // last contact and damping times logged
  void update_contact_times();

  std::vector<double> wall_force;        // local sums, 3 per wall
  std::vector<double> wall_force_all;    // summed over ranks
  int force_flag;

  void wall_forces();
  // the law's history of atom i against wall k (null without history)
  double *wall_history(int i, int k) const
  {
    return size_history ? &history_one[i][law.history_size() * k] : nullptr;
  }
};

}    // namespace LAMMPS_NS

#endif
