/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix nve/ellipsoid (see the header)
------------------------------------------------------------------------- */

#include "fix_nve_ellipsoid.h"

#include "atom.h"
#include "error.h"
#include "math_extra.h"

#include "granular_ellipsoid_atoms.h"

using namespace LAMMPS_NS;

FixNVEEllipsoid::FixNVEEllipsoid(LAMMPS *lmp, int narg, char **arg) : FixNVE(lmp, narg, arg)
{
  if (narg > 3) error->all(FLERR, 3, "Unknown fix nve/ellipsoid argument: {}", arg[3]);
}

void FixNVEEllipsoid::init()
{
  if (!atom->style_match("ellipsoid"))
    error->all(FLERR, "Fix nve/ellipsoid requires atom style ellipsoid");
  EllipsoidAtoms::require_granular_style(lmp, "Fix nve/ellipsoid");
  EllipsoidAtoms(atom).require_shapes(lmp, "Fix nve/ellipsoid", atom->nlocal, groupbit);
  FixNVE::init();
}

void FixNVEEllipsoid::initial_integrate(int /*vflag*/)
{
  EllipsoidAtomsWriter atoms(atom);
  double **x = atom->x, **v = atom->v, **f = atom->f;
  double **angmom = atom->angmom, **torque = atom->torque;
  const double *rmass = atom->rmass;
  const int nlocal = (igroup == atom->firstgroup) ? atom->nfirst : atom->nlocal;
  const double dtq = 0.5 * dtv;    // dt may have changed since init

  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const double dtfm = dtf / rmass[i];
    for (int d = 0; d < 3; d++) {
      v[i][d] += dtfm * f[i][d];
      x[i][d] += dtv * v[i][d];
      angmom[i][d] += dtf * torque[i][d];
    }
    // atoms join the group mid-run (fix pour, dynamic groups): each needs a shape
    if (!atoms.has_shape(i)) atoms.missing_shape(lmp, "Fix nve/ellipsoid", i, groupbit);
    // a sphere's orientation is not read by this package's styles; a blocky superellipsoid's
    // is read by others
    if (atoms.sphere(i) && !atoms.blocky(i)) continue;
    // omega at the half step from the half-step angular momentum, then the quaternion a full
    // step by LAMMPS's Richardson iteration
    double inertia[3], omega[3];
    atoms.inertia(i, inertia);
    double *quat = atoms.quat(i);
    MathExtra::mq_to_omega(angmom[i], quat, inertia, omega);
    MathExtra::richardson(quat, angmom[i], omega, inertia, dtq);
  }
}

void FixNVEEllipsoid::final_integrate()
{
  double **v = atom->v, **f = atom->f;
  double **angmom = atom->angmom, **torque = atom->torque;
  const double *rmass = atom->rmass;
  const int nlocal = (igroup == atom->firstgroup) ? atom->nfirst : atom->nlocal;

  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const double dtfm = dtf / rmass[i];
    for (int d = 0; d < 3; d++) {
      v[i][d] += dtfm * f[i][d];
      angmom[i][d] += dtf * torque[i][d];
    }
  }
}
