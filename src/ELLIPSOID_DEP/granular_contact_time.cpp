/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: the Hertz contact time a run must resolve (see granular_contact_time.h)
------------------------------------------------------------------------- */

#include "granular_contact_time.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "granular_ellipsoid_atoms.h"
#include "update.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

ContactScales LAMMPS_NS::contact_scales(LAMMPS *lmp, int groupbit)
{
  Atom *atom = lmp->atom;
  const int ntypes = atom->ntypes;
  const EllipsoidAtoms atoms(atom);
  // negated masses so that one MPI_MAX finds the lightest (-0: no atom)
  std::vector<double> local(2 * (ntypes + 1) + 1, 0.0), all(local.size(), 0.0);
  double *neg_mass = local.data(), *radius = local.data() + ntypes + 1;
  double &speed = local.back();
  for (int t = 0; t <= ntypes; t++) neg_mass[t] = -HUGE_VAL;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit) || !atoms.has_shape(i)) continue;
    const int t = atom->type[i];
    const double *s = atoms.shape(i);
    const double thinnest = std::min(s[0], std::min(s[1], s[2]));
    neg_mass[t] = std::max(neg_mass[t], -atom->rmass[i]);
    radius[t] = std::max(radius[t], s[0] * s[1] * s[2] / (thinnest * thinnest));
    const double *v = atom->v[i];
    speed = std::max(speed, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  }
  MPI_Allreduce(local.data(), all.data(), static_cast<int>(local.size()), MPI_DOUBLE, MPI_MAX,
                lmp->world);
  ContactScales scales;
  scales.lightest_mass.assign(ntypes + 1, 0.0);
  scales.flattest_radius.assign(all.begin() + ntypes + 1, all.begin() + 2 * (ntypes + 1));
  for (int t = 1; t <= ntypes; t++)
    if (std::isfinite(all[t])) scales.lightest_mass[t] = -all[t];
  scales.fastest_speed = all.back();
  return scales;
}

void LAMMPS_NS::report_contact_time(LAMMPS *lmp, const std::string &who, double time,
                                    const std::string &where, double speed, double &last_reported)
{
  if (!(time > 0.0) || lmp->comm->me != 0) return;
  const double dt = lmp->update->dt;
  if (!(last_reported > 0.0 && std::fabs(time / last_reported - 1.0) < 0.1)) {
    utils::logmesg(lmp,
                   "{}: Hertz contact time {:.6g} ({}, impact speed {:.6g}) = {:.1f} time steps\n",
                   who, time, where, speed, time / dt);
    last_reported = time;
  }
  if (dt > CONTACT_TIME_FRACTION * time)
    lmp->error->warning(FLERR,
                        "{}: timestep {:.6g} exceeds {} of the Hertz contact time {:.6g} ({}, "
                        "impact speed {:.6g}): contacts are resolved by fewer than {:.0f} steps",
                        who, dt, CONTACT_TIME_FRACTION, time, where, speed,
                        1.0 / CONTACT_TIME_FRACTION);
}
