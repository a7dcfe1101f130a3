/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: the Hertz contact time a run must resolve, for the pair style and the wall.
   Per type the lightest atom and the flattest surface (largest Gaussian curvature radius,
   ab/c for semi-axes a >= b >= c) give the shortest contact of that type; the styles combine
   them with their laws (EllipsoidDep::hertz_contact_time) and report the shortest.
------------------------------------------------------------------------- */

#ifndef LMP_GRANULAR_CONTACT_TIME_H
#define LMP_GRANULAR_CONTACT_TIME_H

#include <string>
#include <vector>

namespace LAMMPS_NS {
class LAMMPS;

// dt above this fraction of the shortest contact time is warned about
constexpr double CONTACT_TIME_FRACTION = 0.1;

struct ContactScales {
  std::vector<double> lightest_mass;      // per type (1..ntypes); 0: no atom of the type
  std::vector<double> flattest_radius;    // per type, largest Gaussian curvature radius
  double fastest_speed = 0.0;             // largest atom speed
};

// Over the atoms of the group, on all ranks (collective).
ContactScales contact_scales(LAMMPS *lmp, int groupbit);

// Logs "who: Hertz contact time ..." on rank 0 and warns when the timestep exceeds
// CONTACT_TIME_FRACTION of it; where: which contact ("types 1 2"), speed: the impact speed.
// The log line is left out while time stays within 10 % of last_reported (rank 0's last
// logged value, updated); the warning is repeated at every run start.
void report_contact_time(LAMMPS *lmp, const std::string &who, double time, const std::string &where,
                         double speed, double &last_reported);
}    // namespace LAMMPS_NS

#endif
