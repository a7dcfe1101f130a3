/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: pair_style granular/ellipsoid, its contact times (see
   doc/pair_granular_ellipsoid.rst): the shortest Hertz contact and damping times of the type
   pairs with atoms (per type the lightest atom, flattest surface, largest rotational
   compliance; impact speed: keyword or 2 x fastest), reported at each run start and the last
   two values of compute pair.
------------------------------------------------------------------------- */

#include "pair_granular_ellipsoid.h"

#include "atom.h"
#include "comm.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

void PairGranularEllipsoid::update_contact_times()
{
  const ContactScales scales = contact_scales(lmp, 1);
  const double speed = impact_velocity > 0.0 ? impact_velocity : 2.0 * scales.fastest_speed;
  ContactTimes times;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      const double mi = scales.lightest_mass[i], mj = scales.lightest_mass[j];
      if (!(mi > 0.0 && mj > 0.0 && speed > 0.0)) continue;
      ForceLaw law;
      std::string refusal;
      if (!law_of_pair(i, j, law, refusal)) continue;    // init_one reports it
      const double radius = effective_radius(scales.flattest_radius[i], scales.flattest_radius[j]);
      const double mass = mi * mj / (mi + mj),
                   sliding = tangential_mass(mi, scales.compliance[i], mj, scales.compliance[j]);
      times.add_contact(lmp, law, radius, mass, sliding, speed, fmt::format("types {} {}", i, j));
    }
  contact_time = times.contact_time;
  damping_time = std::isfinite(times.damping_time) ? times.damping_time : 0.0;
  pvector[NUM_COUNTERS] = comm->me == 0 ? contact_time : 0.0;
  pvector[NUM_COUNTERS + 1] = comm->me == 0 ? damping_time : 0.0;
  report_contact_times(lmp, "Pair granular/ellipsoid", times, speed, times_reported);
}
