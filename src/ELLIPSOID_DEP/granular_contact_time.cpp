/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: the contact time a run must resolve (see granular_contact_time.h)
------------------------------------------------------------------------- */

#include "granular_contact_time.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
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
  std::vector<double> local(3 * (ntypes + 1) + 1, 0.0), all(local.size(), 0.0);
  double *neg_mass = local.data(), *radius = local.data() + ntypes + 1,
         *compliance = local.data() + 2 * (ntypes + 1);
  double &speed = local.back();
  for (int t = 0; t <= ntypes; t++) neg_mass[t] = -HUGE_VAL;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit) || !atoms.has_shape(i)) continue;
    const int t = atom->type[i];
    const double *s = atoms.shape(i);
    neg_mass[t] = std::max(neg_mass[t], -atom->rmass[i]);
    radius[t] = std::max(radius[t], EllipsoidDep::flattest_radius(s[0], s[1], s[2]));
    compliance[t] =
        std::max(compliance[t], EllipsoidDep::rotational_compliance(s[0], s[1], s[2]));
    const double *v = atom->v[i];
    speed = std::max(speed, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  }
  MPI_Allreduce(local.data(), all.data(), static_cast<int>(local.size()), MPI_DOUBLE, MPI_MAX,
                lmp->world);
  ContactScales scales;
  scales.lightest_mass.assign(ntypes + 1, 0.0);
  scales.flattest_radius.assign(all.begin() + ntypes + 1, all.begin() + 2 * (ntypes + 1));
  scales.compliance.assign(all.begin() + 2 * (ntypes + 1), all.begin() + 3 * (ntypes + 1));
  for (int t = 1; t <= ntypes; t++)
    if (std::isfinite(all[t])) scales.lightest_mass[t] = -all[t];
  scales.fastest_speed = all.back();
  return scales;
}

double LAMMPS_NS::tangential_mass(double mass_i, double compliance_i, double mass_j,
                                  double compliance_j)
{
  const double inverse =
      (1.0 + compliance_i) / mass_i + (mass_j > 0.0 ? (1.0 + compliance_j) / mass_j : 0.0);
  return 1.0 / inverse;
}

void ContactTimes::add(double contact, double damping, const std::string &where,
                       const std::string &law, bool tangential)
{
  if (contact_time == 0.0 || contact < contact_time) {
    contact_time = contact;
    contact_where = where;
    contact_law = law;
  }
  if (damping_time == 0.0 || damping < damping_time) {
    damping_time = damping;
    damping_where = where;
    tangential_damping = tangential;
  }
}

void ContactTimes::add_contact(LAMMPS *lmp, const EllipsoidDep::ForceLaw &law,
                               double effective_radius, double effective_mass,
                               double tangential_mass, double impact_speed,
                               const std::string &where)
{
  const double ftm2v = lmp->force->ftm2v;
  const double normal = law.damping_time(effective_radius, effective_mass, impact_speed, ftm2v);
  const double tangential = law.tangential_damping_time(effective_radius, effective_mass,
                                                        tangential_mass, impact_speed, ftm2v);
  add(law.contact_time(effective_radius, effective_mass, impact_speed, ftm2v),
      std::min(normal, tangential), where, law.elastic_law(), tangential < normal);
}

namespace {
bool changed(double time, double last) { return !(last > 0.0 && std::fabs(time / last - 1.0) < 0.1); }
}    // namespace

void LAMMPS_NS::report_contact_times(LAMMPS *lmp, const std::string &who,
                                     const ContactTimes &times, double speed,
                                     ContactTimes &last_reported)
{
  if (!(times.contact_time > 0.0) || lmp->comm->me != 0) return;
  const double dt = lmp->update->dt;
  // a new timestep changes the steps per contact and the damping number: log both again
  if (dt != last_reported.timestep) last_reported = ContactTimes();
  last_reported.timestep = dt;
  if (changed(times.contact_time, last_reported.contact_time)) {
    utils::logmesg(lmp,
                   "{}: {} contact time {:.6g} ({}, impact speed {:.6g}) = {:.1f} time steps\n",
                   who, times.contact_law, times.contact_time, times.contact_where, speed,
                   times.contact_time / dt);
    last_reported.contact_time = times.contact_time;
  }
  if (dt > CONTACT_TIME_FRACTION * times.contact_time)
    lmp->error->warning(FLERR,
                        "{}: timestep {:.6g} exceeds {} of the {} contact time {:.6g} ({}, "
                        "impact speed {:.6g}): contacts are resolved by fewer than {:.0f} steps",
                        who, dt, CONTACT_TIME_FRACTION, times.contact_law, times.contact_time,
                        times.contact_where, speed, 1.0 / CONTACT_TIME_FRACTION);
  // an undamped law has no damping time to report
  if (!std::isfinite(times.damping_time)) return;
  const double number = dt / times.damping_time;
  if (changed(times.damping_time, last_reported.damping_time)) {
    utils::logmesg(lmp,
                   "{}: damping number {:.3g} ({}, impact speed {:.6g}): the time step over "
                   "the damping time {} {:.6g} at the {}\n",
                   who, number, times.damping_where, speed,
                   times.tangential_damping ? "m_t/gamma_t" : "m*/gamma", times.damping_time,
                   times.tangential_damping ? "peak force (tangential)" : "deepest overlap");
    last_reported.damping_time = times.damping_time;
  }
  if (number > DAMPING_NUMBER_BOUND)
    lmp->error->warning(FLERR,
                        "{}: damping number {:.3g} ({}, impact speed {:.6g}) exceeds {}: timestep "
                        "{:.6g} over the damping time {:.6g}; velocity Verlet damps a head-on "
                        "contact stably only below 2, and an off-centre contact of an elongated "
                        "particle has a smaller effective mass",
                        who, number, times.damping_where, speed, DAMPING_NUMBER_BOUND, dt,
                        times.damping_time);
}
