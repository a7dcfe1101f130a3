/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/region/ellipsoid (see doc/fix_wall_gran_region_ellipsoid.rst)

   The region's faces are found once in the region's own frame (region_faces(), the _faces
   file) and placed at every step by the region's move and rotate transform; a face's velocity
   at a point is the region's, as LAMMPS's Region::velocity_contact() gives it.
------------------------------------------------------------------------- */

#include "fix_wall_gran_region_ellipsoid.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "region.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

/* ---------------------------------------------------------------------- */

FixWallGranRegionEllipsoid::FixWallGranRegionEllipsoid(LAMMPS *lmp, int narg, char **arg) :
    FixWallGranEllipsoid(lmp, narg, arg, true), region(nullptr), motion_reset(false)
{
  region = domain->get_region_by_id(region_id);
  if (!region)
    error->all(FLERR, "Region {} for fix wall/gran/region/ellipsoid does not exist", region_id);
  faces = region_faces();
  walls = faces;
  check_periodic_crossing();
  restart_global = 1;    // the region's motion state, as LAMMPS's fix wall/gran/region
  wall_velocity = Vec3::Zero();
  allocate_walls();
}

/* ----------------------------------------------------------------------
   the region again (it may have been deleted or replaced between runs)
------------------------------------------------------------------------- */

void FixWallGranRegionEllipsoid::init()
{
  FixWallGranEllipsoid::init();
  Region *current = domain->get_region_by_id(region_id);
  if (!current)
    error->all(FLERR, "Region {} for fix wall/gran/region/ellipsoid does not exist", region_id);
  if (current != region) {
    region = current;
    const std::vector<WallSurface> rebuilt = region_faces();
    if (rebuilt.size() != faces.size())
      error->all(FLERR,
                 "Fix wall/gran/region/ellipsoid: region {} now has {} faces, not {}; define "
                 "the fix again",
                 region_id, rebuilt.size(), faces.size());
    faces = rebuilt;
    check_periodic_crossing();
    if (comm->me == 0)
      error->warning(FLERR,
                     "Region properties for region {} changed between runs, resetting its motion",
                     region_id);
    region->reset_vel();
  }
  if (motion_reset) {
    if (comm->me == 0)
      error->warning(FLERR,
                     "Region properties for region {} are inconsistent with restart file, "
                     "resetting its motion",
                     region_id);
    region->reset_vel();
    motion_reset = false;
  }
}

/* ----------------------------------------------------------------------
   the faces at this step: the region's transform of its own frame (move, then rotate about
   its axis), and its velocity
------------------------------------------------------------------------- */

void FixWallGranRegionEllipsoid::update_walls()
{
  if (!region->dynamic_check()) return;
  region->prematch();
  region->set_velocity();
  auto place = [this](const Vec3 &p) {
    double x = p[0], y = p[1], z = p[2];
    region->forward_transform(x, y, z);
    return Vec3(x, y, z);
  };
  for (std::size_t k = 0; k < faces.size(); k++) {
    const WallSurface &rest = faces[k];
    WallSurface &w = walls[k];
    if (rest.shape == WallShape::Plane) {
      const Vec3 on_plane = place(rest.offset * rest.normal);
      w.normal = (place(rest.offset * rest.normal + rest.normal) - on_plane).normalized();
      w.offset = w.normal.dot(on_plane);
    } else {
      w.center = place(rest.center);
      w.axis = (place(rest.center + rest.axis) - w.center).normalized();
      for (int d = 0; d < 3; d++)
        w.frame.col(d) = (place(rest.center + rest.frame.col(d)) - w.center).normalized();
    }
  }
}

// LAMMPS's Region::velocity_contact: the translation's velocity plus omega x (x_c - rpoint)
Vec3 FixWallGranRegionEllipsoid::velocity_at(int /*wall*/, const Vec3 &point) const
{
  Vec3 v = Vec3::Zero();
  if (region->moveflag) v = Vec3(region->v[0], region->v[1], region->v[2]);
  if (region->rotateflag) {
    const Vec3 omega(region->omega[0], region->omega[1], region->omega[2]);
    const Vec3 r = point - Vec3(region->rpoint[0], region->rpoint[1], region->rpoint[2]);
    v += omega.cross(r);
  }
  return v;
}

// as LAMMPS's fix wall/gran/region: particles whose centres lie on the region's side, and
// for a cylinder or cone with side in those that left it through an open end (they meet the
// rim there). Region::match() takes every point of a region with an open face: LAMMPS also
// meets particles outside a side (the outer face of a funnel) or a closed cap from outside,
// which the faces here do not model (doc/fix_wall_gran_region_ellipsoid.rst)
bool FixWallGranRegionEllipsoid::reaches_walls(int i) const
{
  double x = atom->x[i][0], y = atom->x[i][1], z = atom->x[i][2];
  if (region->dynamic) region->inverse_transform(x, y, z);
  return (region->inside(x, y, z) != 0) == (region->interior != 0) ||
      past_open_end(Vec3(x, y, z));
}

/* ----------------------------------------------------------------------
   a curved face that crosses a periodic boundary would act on one periodic image of a
   particle and not on the other
------------------------------------------------------------------------- */

void FixWallGranRegionEllipsoid::check_periodic_crossing()
{
  for (const WallSurface &w : walls) {
    if (w.shape == WallShape::Plane || w.shape == WallShape::Box) continue;
    for (int d = 0; d < 3; d++) {
      if (!domain->periodicity[d]) continue;
      if (w.shape != WallShape::Sphere && std::fabs(w.axis[d]) == 1.0) continue;
      if (w.center[d] - w.radius < domain->boxlo[d] || w.center[d] + w.radius > domain->boxhi[d])
        error->all(FLERR,
                   "Fix wall/gran/region/ellipsoid: region {}'s {} (radius {}) crosses the "
                   "periodic boundary in {}; a wall across a periodic boundary would hold one "
                   "image of a particle and not the other",
                   region_id, region->style, w.radius, "xyz"[d]);
    }
  }
}

/* ----------------------------------------------------------------------
   restart: the region's motion state, as LAMMPS's fix wall/gran/region writes it
------------------------------------------------------------------------- */

void FixWallGranRegionEllipsoid::write_restart(FILE *fp)
{
  if (comm->me) return;
  int len = 0;
  region->length_restart_string(len);
  fwrite(&len, sizeof(int), 1, fp);
  region->write_restart(fp);
}

void FixWallGranRegionEllipsoid::restart(char *buf)
{
  int n = 0;
  if (!region->restart(buf, n)) motion_reset = true;
}
