/* ----------------------------------------------------------------------
   ELLIPSOID_DEP force laws: the Hertz impact (see hertz_elastic.h).
------------------------------------------------------------------------- */

#include "hertz_elastic.h"

namespace EllipsoidDep {

double hertz_deepest_overlap(double stiffness, double inertia, double impact_speed)
{
  // m xi'' = -k xi^3/2 from xi' = v: the kinetic energy m v^2 / 2 stored as 2/5 k xi^5/2
  return std::pow(5.0 * inertia * impact_speed * impact_speed / (4.0 * stiffness), 0.4);
}

double hertz_contact_time(double stiffness, double inertia, double impact_speed)
{
  // the time in contact is 2 xi_max / v times the integral of (1 - u^5/2)^(-1/2) over [0, 1]
  const double integral = 0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  return 2.0 * integral * hertz_deepest_overlap(stiffness, inertia, impact_speed) / impact_speed;
}

}    // namespace EllipsoidDep
