/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: the time scales of a contact a run must resolve, for the pair style and the
   wall: the contact time of the law's undamped impact and the damping time, the shorter of
   the normal m* / gamma at its deepest overlap and the tangential m_t / gamma_t at its peak
   force (a viscous tangential law). Per type the lightest atom, the flattest surface (largest
   Gaussian curvature radius, ab/c for semi-axes a >= b >= c) and the largest rotational
   compliance (ellipsoid_shape.h; it makes m_t) give the shortest of that type; the styles
   combine them with their laws (ContactTimes::add_contact: ForceLaw::contact_time,
   damping_time and tangential_damping_time in the unit style's time) and report the
   shortest.
------------------------------------------------------------------------- */

#ifndef LMP_GRANULAR_CONTACT_TIME_H
#define LMP_GRANULAR_CONTACT_TIME_H

#include "ellipsoid_force_law.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {
class LAMMPS;

// dt above this fraction of the shortest contact time is warned about
constexpr double CONTACT_TIME_FRACTION = 0.1;
// dt above this many damping times (of the head-on contact; of its sliding, for a tangential
// dashpot) is warned about. Velocity Verlet damps a head-on contact stably only below 2. Off-centre contacts of elongated particles have
// a smaller effective mass (rotation joins in), which no head-on number bounds: the margin is
// empirical (a deposit that blew up at 1.28 reached rest at 0.99; doc/robustness.md, bug 4).
constexpr double DAMPING_NUMBER_BOUND = 1.0;

struct ContactScales {
  std::vector<double> lightest_mass;      // per type (1..ntypes); 0: no atom of the type
  std::vector<double> flattest_radius;    // per type, largest Gaussian curvature radius
  std::vector<double> compliance;         // per type, largest rotational_compliance
  double fastest_speed = 0.0;             // largest atom speed
};

// Over the atoms of the group, on all ranks (collective).
ContactScales contact_scales(LAMMPS *lmp, int groupbit);

// m_t of two bodies (masses, rotational compliances), 1/m_t = (1 + q_i)/m_i + (1 + q_j)/m_j;
// of one body against a wall with mass_j = 0
double tangential_mass(double mass_i, double compliance_i, double mass_j = 0.0,
                       double compliance_j = 0.0);

// The shortest contact and damping times of a style and which contact has them
// ("types 1 2"); 0: undefined (no atoms, or at rest).
struct ContactTimes {
  double contact_time = 0.0, damping_time = 0.0;    // damping: HUGE_VAL for an undamped law
  std::string contact_where, damping_where;
  std::string contact_law;    // the shortest contact time's law (ForceLaw::elastic_law)
  bool tangential_damping = false;    // the shortest damping time is m_t / gamma_t
  double timestep = 0.0;      // of the last report (last_reported only)
  // keeps the shorter of each
  void add(double contact, double damping, const std::string &where, const std::string &law,
           bool tangential = false);
  // the contact and damping times of one contact (law, R*, m* and m_t in mass units, impact
  // speed) in the time unit of the run: the law's times with LAMMPS's force->ftm2v, without
  // which units real, metal and electron got them wrong (doc/robustness.md)
  void add_contact(LAMMPS *lmp, const EllipsoidDep::ForceLaw &law, double effective_radius,
                   double effective_mass, double tangential_mass, double impact_speed,
                   const std::string &where);
};

// Logs "who: Hertz contact time ..." (the law's name, ForceLaw::elastic_law) and "who: damping
// number ..." on rank 0 and warns when the timestep exceeds CONTACT_TIME_FRACTION of the
// contact time or DAMPING_NUMBER_BOUND damping times; speed: the impact speed. The log lines
// are left out while the timestep is that of last_reported (rank 0's last logged values,
// updated) and each time stays within 10 % of it; the warnings are repeated at every run
// start.
void report_contact_times(LAMMPS *lmp, const std::string &who, const ContactTimes &times,
                          double speed, ContactTimes &last_reported);
}    // namespace LAMMPS_NS

#endif
