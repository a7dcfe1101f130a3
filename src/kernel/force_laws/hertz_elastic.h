/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws: what the Hertz normal models (normal_hertz.h,
   normal_hertz_material.h) share. Each gives its stiffness k(R*) and its damping coefficient
   gamma(R*, xi, m*); then

     F_n = k xi^(3/2) + gamma dxi/dt

   and, for an undamped head-on impact at relative normal speed v, with the inertia
   m = m* / ftm2v (the energy m v^2 / 2 stored as 2/5 k xi^(5/2)):

     deepest overlap  xi_max = (5 m v^2 / (4 k))^(2/5)
     contact time     t_c = 2 xi_max / v  int_0^1 (1 - u^(5/2))^(-1/2) du
                          = 2 (2/5) B(2/5, 1/2) xi_max / v  ~ 3.218 (m^2 / (k^2 v))^(1/5)
     peak force       k xi_max^(3/2), the elastic force there
     damping time     m / gamma(R*, xi_max, m*) (peak_damping: that gamma), HUGE_VAL
                      without damping: velocity Verlet integrates a damper stably only for
                      dt below twice it. gamma takes m*
                      in mass units as given (LAMMPS pair granular's convention for the
                      restitution damping), the time divides the inertia by it.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_HERTZ_ELASTIC_H
#define ELLIPSOID_DEP_HERTZ_ELASTIC_H

#include "force_law_model.h"

#include <cmath>

namespace EllipsoidDep {

// xi_max and t_c above for the stiffness k and the inertia m
double hertz_deepest_overlap(double stiffness, double inertia, double impact_speed);
double hertz_contact_time(double stiffness, double inertia, double impact_speed);

// The base of a Hertz normal model (CRTP): Model has stiffness(R*) and
// damping_coefficient(R*, sqrt(xi), m*).
template <class Model> struct HertzElastic {
  static constexpr int HISTORY_SIZE = 0;
  static constexpr const char *ELASTIC_LAW = "Hertz";

  NormalForce normal_force(double effective_radius, double overlap, double sqrt_overlap,
                           double overlap_rate, double effective_mass) const
  {
    const double damping = model().damping_coefficient(effective_radius, sqrt_overlap,
                                                       effective_mass);
    return {model().stiffness(effective_radius) * overlap * sqrt_overlap + damping * overlap_rate,
            damping};
  }
  double deepest_overlap(double effective_radius, double effective_mass, double impact_speed,
                         double ftm2v) const
  {
    return hertz_deepest_overlap(model().stiffness(effective_radius), effective_mass / ftm2v,
                                 impact_speed);
  }
  double peak_force(double effective_radius, double effective_mass, double impact_speed,
                    double ftm2v) const
  {
    const double overlap =
        deepest_overlap(effective_radius, effective_mass, impact_speed, ftm2v);
    return model().stiffness(effective_radius) * overlap * std::sqrt(overlap);
  }
  double contact_time(double effective_radius, double effective_mass, double impact_speed,
                      double ftm2v) const
  {
    return hertz_contact_time(model().stiffness(effective_radius), effective_mass / ftm2v,
                              impact_speed);
  }
  // gamma at the deepest overlap
  double peak_damping(double effective_radius, double effective_mass, double impact_speed,
                      double ftm2v) const
  {
    return model().damping_coefficient(
        effective_radius,
        std::sqrt(deepest_overlap(effective_radius, effective_mass, impact_speed, ftm2v)),
        effective_mass);
  }
  double damping_time(double effective_radius, double effective_mass, double impact_speed,
                      double ftm2v) const
  {
    const double gamma = peak_damping(effective_radius, effective_mass, impact_speed, ftm2v);
    return gamma > 0.0 ? effective_mass / ftm2v / gamma : HUGE_VAL;
  }

 private:
  const Model &model() const { return static_cast<const Model &>(*this); }
};

}    // namespace EllipsoidDep

#endif
