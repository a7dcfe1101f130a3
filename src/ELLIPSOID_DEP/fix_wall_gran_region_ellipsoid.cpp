/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/region/ellipsoid (see doc/fix_wall_gran_region_ellipsoid.rst)

   The region's faces are found in the region's own frame (region_faces(), the _faces file)
   at the fix's definition and again at every run (the region, looked up by its ID, may have
   been defined again), and placed at every step by the region's move and rotate transform; a
   face's velocity at a point is the region's, as LAMMPS's Region::velocity_contact() gives
   it. Its reach across periodic boundaries: the _periodic file.
------------------------------------------------------------------------- */

#include "fix_wall_gran_region_ellipsoid.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "region.h"

#include "granular_ellipsoid_atoms.h"

#include <algorithm>
#include <cstring>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

/* ---------------------------------------------------------------------- */

FixWallGranRegionEllipsoid::FixWallGranRegionEllipsoid(LAMMPS *lmp, int narg, char **arg) :
    FixWallGranEllipsoid(lmp, narg, arg, true), region(nullptr), motion_reset(false), reach(0.0)
{
  region = find_region();
  faces = faces_at_rest();
  walls = faces;
  // a moving region is checked where it is, at setup and at every step
  if (!region->dynamic_check()) check_periodic_crossing();
  restart_global = 1;    // the region's motion state, as LAMMPS's fix wall/gran/region
  wall_velocity = Vec3::Zero();
  allocate_walls();
}

Region *FixWallGranRegionEllipsoid::find_region()
{
  Region *found = domain->get_region_by_id(region_id);
  if (!found)
    error->all(FLERR, "Region {} for fix wall/gran/region/ellipsoid does not exist", region_id);
  return found;
}

// region_faces() probes the region through its transform: at rest (no displacement, no
// angle) the same region gives the same faces at every run
std::vector<WallSurface> FixWallGranRegionEllipsoid::faces_at_rest()
{
  const double placed[4] = {region->dx, region->dy, region->dz, region->theta};
  region->dx = region->dy = region->dz = region->theta = 0.0;
  const std::vector<WallSurface> found = region_faces();
  region->dx = placed[0];
  region->dy = placed[1];
  region->dz = placed[2];
  region->theta = placed[3];
  return found;
}

/* ----------------------------------------------------------------------
   the region by its ID at every run, as LAMMPS's fix wall/gran/region: it may have been
   deleted and defined again between runs, at its old address or at another one. Its faces
   are found again; other faces (or another region) rebuild the walls, restart the wall
   contacts' histories (they belonged to the old faces) and report the new walls at setup.
------------------------------------------------------------------------- */

void FixWallGranRegionEllipsoid::init()
{
  FixWallGranEllipsoid::init();
  Region *previous = region;
  region = find_region();
  const std::vector<WallSurface> rebuilt = faces_at_rest();
  if (rebuilt.size() != faces.size())
    error->all(FLERR,
               "Fix wall/gran/region/ellipsoid: region {} now has {} faces, not {}; define "
               "the fix again",
               region_id, rebuilt.size(), faces.size());
  const bool other_faces = rebuilt != faces;
  if (other_faces || region != previous) {
    faces = rebuilt;
    walls = faces;    // a moving region's are placed at setup
    if (other_faces && size_history)
      for (int i = 0; i < atom->nlocal; i++) std::fill_n(history_one[i], size_history, 0.0);
    setup_reported = false;
    if (comm->me == 0)
      error->warning(FLERR,
                     "Region {} for fix wall/gran/region/ellipsoid was defined again between "
                     "runs: its walls are rebuilt{}{}",
                     region_id, other_faces ? ", the wall contacts' histories restart" : "",
                     region != previous ? ", its motion is reset" : "");
    if (region != previous) region->reset_vel();
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
   the reach of the walls beyond a solid met from outside: the group's largest bounding
   radius (a particle centre that far from the solid can touch it)
------------------------------------------------------------------------- */

void FixWallGranRegionEllipsoid::setup(int vflag)
{
  const EllipsoidAtoms atoms(atom);
  double local = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if ((atom->mask[i] & groupbit) && atoms.has_shape(i))
      local = std::max(local, atoms.bounding_radius(i));
  MPI_Allreduce(&local, &reach, 1, MPI_DOUBLE, MPI_MAX, world);
  if (!region->dynamic_check()) check_periodic_crossing();
  FixWallGranEllipsoid::setup(vflag);    // places a moving region's walls and checks them
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
  check_periodic_crossing();    // wherever the region moves
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
   restart: the region's motion state, as LAMMPS's fix wall/gran/region writes it
------------------------------------------------------------------------- */

void FixWallGranRegionEllipsoid::write_restart(FILE *fp)
{
  // write_restart noinit skips init(): the region may have been deleted since
  Region *current = find_region();
  if (comm->me) return;
  int len = 0;
  current->length_restart_string(len);
  fwrite(&len, sizeof(int), 1, fp);
  current->write_restart(fp);
}

void FixWallGranRegionEllipsoid::restart(char *buf)
{
  int n = 0;
  if (!region->restart(buf, n)) motion_reset = true;
}
