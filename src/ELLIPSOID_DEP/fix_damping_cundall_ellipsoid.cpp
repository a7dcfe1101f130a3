/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix damping/cundall/ellipsoid (see the header)
------------------------------------------------------------------------- */

#include "fix_damping_cundall_ellipsoid.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "modify.h"

#include "granular_ellipsoid_atoms.h"

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
const char WHO[] = "Fix damping/cundall/ellipsoid";

// gamma of argument iarg, in [0, 1]: 1 removes a component that drives the motion
double read_gamma(LAMMPS *lmp, int iarg, char **arg, const char *name)
{
  const double gamma = utils::numeric(FLERR, arg[iarg], false, lmp);
  if (!(gamma >= 0.0 && gamma <= 1.0))
    lmp->error->all(FLERR, iarg, "{} {} must be in [0, 1], got {}", WHO, name, arg[iarg]);
  return gamma;
}

// LAMMPS's rule, per component: reduced where it drives the motion, enlarged where it brakes
void damp(double *value, const double *velocity, double gamma)
{
  for (int k = 0; k < 3; k++) value[k] *= 1.0 - gamma * (value[k] * velocity[k] >= 0.0 ? 1 : -1);
}
}    // namespace

FixDampingCundallEllipsoid::FixDampingCundallEllipsoid(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg)
{
  if (narg < 5) utils::missing_cmd_args(FLERR, "fix damping/cundall/ellipsoid", error);
  if (narg > 5) error->all(FLERR, 5, "Unknown {} argument: {}", WHO, arg[5]);
  EllipsoidAtoms::require_granular_style(lmp, WHO);
  gamma_linear = read_gamma(lmp, 3, arg, "gamma_l");
  gamma_angular = read_gamma(lmp, 4, arg, "gamma_a");
}

int FixDampingCundallEllipsoid::setmask()
{
  return POST_FORCE | MIN_POST_FORCE;
}

void FixDampingCundallEllipsoid::init()
{
  // a force added after this fix would escape the damping (LAMMPS's warning)
  bool after = false;
  for (const auto &fix : modify->get_fix_list()) {
    if (after && comm->me == 0 && (fix->setmask() & POST_FORCE))
      error->warning(FLERR, "Fix {} alters forces after {}", fix->id, WHO);
    if (fix == this) after = true;
  }
}

void FixDampingCundallEllipsoid::setup(int vflag)
{
  post_force(vflag);
}

void FixDampingCundallEllipsoid::min_setup(int vflag)
{
  post_force(vflag);
}

void FixDampingCundallEllipsoid::min_post_force(int vflag)
{
  post_force(vflag);
}

void FixDampingCundallEllipsoid::post_force(int /*vflag*/)
{
  const EllipsoidAtoms atoms(atom);
  double **v = atom->v, **f = atom->f, **torque = atom->torque;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    if (!atoms.has_shape(i)) atoms.missing_shape(lmp, WHO, i, groupbit);
    const EllipsoidDep::Vec3 omega =
        atoms.omega(i, EllipsoidDep::quaternion_rotation(atoms.quat(i)));
    damp(f[i], v[i], gamma_linear);
    damp(torque[i], omega.data(), gamma_angular);
  }
}
