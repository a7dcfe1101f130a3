/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/region/ellipsoid
   LAMMPS's fix wall/gran/region for general ellipsoids: the walls are the faces of a region
   (block, cylinder, cone, sphere, plane), each the kernel's exact contact of its shape, moved with
   the region's move and rotate keywords. The force law, the history per wall, the contacts
   array and the force loop are fix wall/gran/ellipsoid's (the base). See
   doc/fix_wall_gran_region_ellipsoid.rst.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_WALL_GRAN_REGION_ELLIPSOID_H
#define LMP_FIX_WALL_GRAN_REGION_ELLIPSOID_H

#include "fix_wall_gran_ellipsoid.h"

namespace LAMMPS_NS {

class FixWallGranRegionEllipsoid : public FixWallGranEllipsoid {
 public:
  FixWallGranRegionEllipsoid(class LAMMPS *, int, char **);
  void init() override;
  void setup(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 protected:
  void update_walls() override;
  EllipsoidDep::Vec3 velocity_at(int wall, const EllipsoidDep::Vec3 &point) const override;
  bool reaches_walls(int i) const override;

 private:
  class Region *region;    // looked up by its ID at every init (it may have been redefined)
  // the region's faces in its own frame (before move and rotate), LAMMPS's iwall order
  std::vector<EllipsoidDep::WallSurface> faces;
  bool motion_reset;    // the restart file's region motion did not match
  double reach;         // the group's largest bounding radius at the last setup
  class Region *find_region();
  std::vector<EllipsoidDep::WallSurface> faces_at_rest();
  std::vector<EllipsoidDep::WallSurface> region_faces();
  bool cone_from_probes(const std::vector<EllipsoidDep::Vec3> &probes,
                        EllipsoidDep::WallSurface &w);
  void side_extent(EllipsoidDep::WallSurface &w);
  bool past_open_end(const EllipsoidDep::Vec3 &x) const;
  void check_periodic_crossing();    // the _periodic file
};

}    // namespace LAMMPS_NS

#endif
