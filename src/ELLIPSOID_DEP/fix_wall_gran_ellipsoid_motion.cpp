/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/ellipsoid, moving walls: wiggle and shear, the words and the
   motion of LAMMPS's fix wall/gran (see doc/fix_wall_gran_ellipsoid.rst)
------------------------------------------------------------------------- */

#include "fix_wall_gran_ellipsoid.h"

#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "math_const.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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
    error->all(FLERR, iarg, "Fix wall/gran/ellipsoid: give one of wiggle, shear and servo, once");
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

/* ----------------------------------------------------------------------
   servo force|stress target gain G vmax V [filter T] [area A]: the words used
------------------------------------------------------------------------- */

int FixWallGranEllipsoid::parse_servo(int iarg, int narg, char **arg)
{
  if (iarg + 6 >= narg) utils::missing_cmd_args(FLERR, "fix wall/gran/ellipsoid servo", error);
  if (motion.kind != Motion::Kind::None)
    error->all(FLERR, iarg, "Fix wall/gran/ellipsoid: give one of wiggle, shear and servo, once");
  const std::string kind = arg[iarg + 1];
  if (kind != "force" && kind != "stress")
    error->all(FLERR, iarg + 1, "Fix wall/gran/ellipsoid servo: expected force or stress, not '{}'",
               kind);
  if (std::string(arg[iarg + 3]) != "gain" || std::string(arg[iarg + 5]) != "vmax")
    error->all(FLERR, iarg, "Fix wall/gran/ellipsoid servo: expected 'servo {} VALUE gain G vmax V'",
               kind);
  motion.kind = Motion::Kind::Servo;
  motion.stress = kind == "stress";
  motion.target = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
  motion.gain = utils::numeric(FLERR, arg[iarg + 4], false, lmp);
  motion.vmax = utils::numeric(FLERR, arg[iarg + 6], false, lmp);
  if (!(motion.target > 0.0))
    error->all(FLERR, iarg + 2,
               "Fix wall/gran/ellipsoid servo: the target {} must be > 0 (the particles push on "
               "the wall)",
               kind);
  if (!(motion.gain > 0.0))
    error->all(FLERR, iarg + 4, "Fix wall/gran/ellipsoid servo: gain must be > 0");
  if (!(motion.vmax > 0.0))
    error->all(FLERR, iarg + 6, "Fix wall/gran/ellipsoid servo: vmax must be > 0");
  int used = 7;    // then the optional words, in any order
  while (iarg + used < narg) {
    const std::string word = arg[iarg + used];
    if (word != "filter" && word != "area") break;
    if (iarg + used + 1 >= narg)
      utils::missing_cmd_args(FLERR, "fix wall/gran/ellipsoid servo " + word, error);
    const double value = utils::numeric(FLERR, arg[iarg + used + 1], false, lmp);
    if (word == "filter") {
      if (!(value >= 0.0))
        error->all(FLERR, iarg + used + 1, "Fix wall/gran/ellipsoid servo: filter time must be >= 0");
      motion.filter_time = value;
    } else {
      if (!motion.stress)
        error->all(FLERR, iarg + used,
                   "Fix wall/gran/ellipsoid servo: area needs a stress target (servo stress ...)");
      if (!(value > 0.0))
        error->all(FLERR, iarg + used + 1, "Fix wall/gran/ellipsoid servo: area must be > 0");
      motion.area = value;
    }
    used += 2;
  }
  return used;
}

// the servo's target force: a stress acts on the given area, or else on the box's
// cross-section normal to the wall; LAMMPS's pressure units are force / area times nktv2p
// (not 1 in real, metal, electron)
double FixWallGranEllipsoid::servo_target() const
{
  if (!motion.stress) return motion.target;
  double area = motion.area;
  if (area == 0.0) {
    area = 1.0;
    for (int d = 0; d < 3; d++)
      if (walls[0].normal[d] == 0.0) area *= domain->prd[d];
  }
  return motion.target * area / force->nktv2p;
}

double FixWallGranEllipsoid::simulation_time() const
{
  return update->atime + static_cast<double>(update->ntimestep - update->atimestep) * update->dt;
}

// the walls' offsets and velocity at this step: wiggle and shear as fix wall/gran's, the
// servo by one step of its controller
void FixWallGranEllipsoid::move_walls()
{
  if (motion.kind == Motion::Kind::None) return;
  if (motion.kind == Motion::Kind::Servo) {
    const double u = motion.gain * (servo_target() - motion.force);
    motion.speed = std::max(-motion.vmax, std::min(motion.vmax, u));
    walls[0].offset += motion.speed * update->dt;
    wall_velocity = motion.speed * walls[0].normal;
    return;
  }
  wall_velocity = Vec3::Zero();
  if (motion.kind == Motion::Kind::Shear) {
    wall_velocity[motion.dim] = motion.vshear;
    return;
  }
  const double phase = motion.omega * (simulation_time() - motion.time_origin);
  const double shift = motion.amplitude - motion.amplitude * std::cos(phase);
  for (std::size_t k = 0; k < walls.size(); k++)
    walls[k].offset = rest_offset[k] + walls[k].normal[motion.dim] * shift;
  wall_velocity[motion.dim] = motion.amplitude * motion.omega * std::sin(phase);
}

// the servo's measure for the next step: the particles' push on its wall, along -n. With a
// filter a time step moves the measure towards it by 1 - exp(-dt / filter_time); setup
// forces only start a measure (a new fix), as they leave the contacts' histories alone.
void FixWallGranEllipsoid::measure_servo_force()
{
  const double push =
      -Vec3(wall_force_all[0], wall_force_all[1], wall_force_all[2]).dot(walls[0].normal);
  if (motion.filter_time > 0.0 && motion.measured) {
    if (history_update) {
      const double keep = std::exp(-update->dt / motion.filter_time);
      motion.force = keep * motion.force + (1.0 - keep) * push;
    }
  } else {
    motion.force = push;
  }
  motion.measured = true;
}

/* ----------------------------------------------------------------------
   restart: a moving wall's state (the wiggle's time origin, the servo's position, speed and
   measured force, filtered or not), for the same fix given again after read_restart
------------------------------------------------------------------------- */

void FixWallGranEllipsoid::write_restart(FILE *fp)
{
  std::vector<double> list = {static_cast<double>(motion.kind), static_cast<double>(walls.size()),
                              motion.time_origin, motion.speed,
                              motion.force};
  for (const WallSurface &w : walls) list.push_back(w.offset);
  if (comm->me == 0) {
    const int size = static_cast<int>(list.size() * sizeof(double));
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list.data(), sizeof(double), list.size(), fp);
  }
}

void FixWallGranEllipsoid::restart(char *buf)
{
  const auto *list = reinterpret_cast<const double *>(buf);
  if (static_cast<int>(list[0]) != static_cast<int>(motion.kind) ||
      static_cast<std::size_t>(list[1]) != walls.size())
    error->all(FLERR,
               "Fix wall/gran/ellipsoid {}: the restart file's walls move otherwise (another "
               "motion keyword or number of walls); give the fix as it was written, or a new ID",
               id);
  motion.time_origin = list[2];
  motion.speed = list[3];
  motion.force = list[4];
  motion.measured = true;
  // the servo's position is its state; wiggled and sheared walls stay where the command
  // puts them (the wiggle is placed from them at every step)
  if (motion.kind != Motion::Kind::Servo) return;
  for (std::size_t k = 0; k < walls.size(); k++) walls[k].offset = list[5 + k];
  wall_velocity = motion.speed * walls[0].normal;
}
