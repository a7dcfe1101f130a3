/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: contact force laws, a law's models composed (see ellipsoid_force_law.h;
   each model's equation is in its own header, and in doc/pair_granular_ellipsoid.rst).
------------------------------------------------------------------------- */

#include "ellipsoid_force_law.h"

#include <cmath>
#include <utility>

namespace EllipsoidDep {

double ForceLaw::stiffness(double effective_radius) const
{
  return visit_model(normal, [&](const auto &model) {
    return model.stiffness(effective_radius);
  });
}

double ForceLaw::deepest_overlap(double effective_radius, double effective_mass,
                                 double impact_speed, double ftm2v) const
{
  return visit_model(normal, [&](const auto &model) {
    return model.deepest_overlap(effective_radius, effective_mass, impact_speed, ftm2v);
  });
}

double ForceLaw::contact_time(double effective_radius, double effective_mass, double impact_speed,
                              double ftm2v) const
{
  return visit_model(normal, [&](const auto &model) {
    return model.contact_time(effective_radius, effective_mass, impact_speed, ftm2v);
  });
}

double ForceLaw::damping_time(double effective_radius, double effective_mass, double impact_speed,
                              double ftm2v) const
{
  return visit_model(normal, [&](const auto &model) {
    return model.damping_time(effective_radius, effective_mass, impact_speed, ftm2v);
  });
}

double ForceLaw::tangential_damping_time(double effective_radius, double effective_mass,
                                         double tangential_mass, double impact_speed,
                                         double ftm2v) const
{
  const auto [peak, peak_damping] = visit_model(normal, [&](const auto &model) {
    return std::pair(model.peak_force(effective_radius, effective_mass, impact_speed, ftm2v),
                     model.peak_damping(effective_radius, effective_mass, impact_speed, ftm2v));
  });
  const double gamma = visit_model(tangential, [&](const auto &model) {
    return model.damping_coefficient(peak, peak_damping);
  });
  return gamma > 0.0 ? tangential_mass / ftm2v / gamma : HUGE_VAL;
}

const char *ForceLaw::elastic_law() const
{
  return visit_model(normal, [](const auto &model) {
    return model.ELASTIC_LAW;
  });
}

ContactForce ForceLaw::compute(const ContactGeometry &geometry, const ContactMotion &motion,
                               double dt, double *history) const
{
  ContactForce out;
  const Vec3 &n = geometry.normal;
  const double overlap = geometry.overlap;
  const double sqrt_overlap = std::sqrt(overlap);

  // velocity of i relative to j at the contact point
  const Vec3 v_rel = motion.v_i + motion.omega_i.cross(motion.branch_i) - motion.v_j -
      motion.omega_j.cross(motion.branch_j);
  const double overlap_rate = v_rel.dot(n);    // d(xi)/dt > 0 while approaching
  const Vec3 v_tangent = v_rel - overlap_rate * n;

  const NormalForce normal_force = visit_model(normal, [&](const auto &model) {
    return model.normal_force(geometry.effective_radius, overlap, sqrt_overlap, overlap_rate,
                              motion.effective_mass);
  });
  double fn = normal_force.force;
  // limit_damping: on fast separation the damping may exceed the elastic force; clip
  if (limit_damping && fn < 0.0) fn = 0.0;
  out.normal_force = fn;
  Vec3 force = -fn * n;    // on i: pushed away from j
  const double fn_friction = fn > 0.0 ? fn : 0.0;

  // the history: the tangential model's slots, then the rolling model's (history_size())
  double *const tangential_history = history;
  visit_model(tangential, [&](const auto &model) {
    model.add_force(n, v_tangent, fn_friction, normal_force.damping, dt, tangential_history,
                    force);
  });

  out.force_i = force;
  out.torque_i = motion.branch_i.cross(force);
  out.torque_j = motion.branch_j.cross(-force);

  double *const rolling_history = history ? tangential_history + history_size_of(tangential)
                                          : nullptr;
  visit_model(rolling, [&](const auto &model) {
    model.add_torque(n, motion, geometry.effective_radius, fn_friction, dt, rolling_history, out);
  });
  return out;
}

}    // namespace EllipsoidDep
