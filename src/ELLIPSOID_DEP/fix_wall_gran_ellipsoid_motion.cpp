/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/ellipsoid, moving walls: wiggle and shear, the words and the
   motion of LAMMPS's fix wall/gran (see doc/fix_wall_gran_ellipsoid.rst)
------------------------------------------------------------------------- */

#include "fix_wall_gran_ellipsoid.h"

#include "error.h"
#include "math_const.h"
#include "update.h"

#include <cmath>
#include <string>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

/* ----------------------------------------------------------------------
   wiggle dim A period | shear dim v: the words fix wall/gran takes; the words used
------------------------------------------------------------------------- */

int FixWallGranEllipsoid::parse_motion(int iarg, int narg, char **arg)
{
  const std::string word = arg[iarg];
  const bool wiggle = word == "wiggle";
  const int nvalues = wiggle ? 3 : 2;
  if (iarg + nvalues >= narg)
    utils::missing_cmd_args(FLERR, "fix wall/gran/ellipsoid " + word, error);
  if (motion.kind != Motion::Kind::None)
    error->all(FLERR, iarg, "Fix wall/gran/ellipsoid: give one of wiggle and shear, once");
  const std::string dim = arg[iarg + 1];
  if (dim != "x" && dim != "y" && dim != "z")
    error->all(FLERR, iarg + 1,
               "Fix wall/gran/ellipsoid {}: dimension must be x, y or z, not '{}'", word, dim);
  motion.dim = dim[0] - 'x';
  if (wiggle) {
    motion.kind = Motion::Kind::Wiggle;
    motion.amplitude = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
    const double period = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
    if (!(period > 0.0))
      error->all(FLERR, iarg + 3, "Fix wall/gran/ellipsoid wiggle: period must be > 0");
    motion.omega = 2.0 * MathConst::MY_PI / period;
  } else {
    motion.kind = Motion::Kind::Shear;
    motion.vshear = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
  }
  return 1 + nvalues;
}

// the walls' offsets and velocity at this step (fix wall/gran's wiggle and shear)
void FixWallGranEllipsoid::move_walls()
{
  if (motion.kind == Motion::Kind::None) return;
  wall_velocity = Vec3::Zero();
  if (motion.kind == Motion::Kind::Shear) {
    wall_velocity[motion.dim] = motion.vshear;
    return;
  }
  const double phase = motion.omega * (update->ntimestep - motion.time_origin) * update->dt;
  const double shift = motion.amplitude - motion.amplitude * std::cos(phase);
  for (std::size_t k = 0; k < walls.size(); k++)
    walls[k].offset = rest_offset[k] + walls[k].normal[motion.dim] * shift;
  wall_velocity[motion.dim] = motion.amplitude * motion.omega * std::sin(phase);
}
