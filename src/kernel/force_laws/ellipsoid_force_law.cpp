/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: contact force laws (see ellipsoid_force_law.h and
   doc/pair_granular_ellipsoid.rst for the equations).
------------------------------------------------------------------------- */

#include "ellipsoid_force_law.h"

#include <cmath>

namespace EllipsoidDep {

namespace {

  // sqrt(5/6): the factor of the Tsuji-type damping derived from the restitution coefficient
  const double SQRT_5_6 = std::sqrt(5.0 / 6.0);

  // E* of the contact; for unlike materials E holds the mixed value that gives Hertz's
  // 1/E* = (1-nu_a^2)/E_a + (1-nu_b^2)/E_b (see mix_laws)
  double reduced_modulus(const NormalModel &normal)
  {
    return normal.youngs / (2.0 * (1.0 - normal.poisson * normal.poisson));
  }

}    // namespace

double ForceLaw::hertz_stiffness(double effective_radius) const
{
  if (normal.kind == NormalModel::Kind::Hertz) return normal.kn;
  return 4.0 / 3.0 * reduced_modulus(normal) * std::sqrt(effective_radius);
}

double hertz_max_overlap(double stiffness, double effective_mass, double impact_speed)
{
  // m* xi'' = -k xi^3/2 from xi' = v: the kinetic energy m* v^2 / 2 stored as 2/5 k xi^5/2
  return std::pow(5.0 * effective_mass * impact_speed * impact_speed / (4.0 * stiffness), 0.4);
}

double hertz_contact_time(double stiffness, double effective_mass, double impact_speed,
                          double ftm2v)
{
  // the time in contact is 2 xi_max / v times the integral of (1 - u^5/2)^(-1/2) over [0, 1]
  const double integral = 0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  return 2.0 * integral * hertz_max_overlap(stiffness, effective_mass / ftm2v, impact_speed) /
      impact_speed;
}

double ForceLaw::damping_coefficient(double effective_radius, double sqrt_overlap,
                                     double effective_mass) const
{
  if (normal.kind == NormalModel::Kind::Hertz) return normal.damping * sqrt_overlap;
  // damping of the restitution coefficient e: gamma = -2 sqrt(5/6) beta sqrt(S_n m*),
  // S_n = 2 E* sqrt(R* xi) (LAMMPS's damping coeff_restitution for Hertz)
  const double log_e = std::log(normal.restitution);
  const double beta = log_e / std::sqrt(log_e * log_e + PI * PI);
  const double stiffness_n = 2.0 * reduced_modulus(normal) * std::sqrt(effective_radius) * sqrt_overlap;
  return -2.0 * SQRT_5_6 * beta * std::sqrt(stiffness_n * effective_mass);
}

double hertz_damping_time(const ForceLaw &law, double effective_radius, double effective_mass,
                          double impact_speed, double ftm2v)
{
  const double inertia = effective_mass / ftm2v;
  const double max_overlap =
      hertz_max_overlap(law.hertz_stiffness(effective_radius), inertia, impact_speed);
  // the gamma of compute(), which sees the mass in mass units
  const double gamma =
      law.damping_coefficient(effective_radius, std::sqrt(max_overlap), effective_mass);
  return gamma > 0.0 ? inertia / gamma : HUGE_VAL;
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

  double fn = hertz_stiffness(geometry.effective_radius) * overlap * sqrt_overlap +
      damping_coefficient(geometry.effective_radius, sqrt_overlap, motion.effective_mass) *
          overlap_rate;
  // limit_damping: on fast separation the damping may exceed the elastic force; clip
  if (normal.limit_damping && fn < 0.0) fn = 0.0;
  out.normal_force = fn;
  Vec3 force = -fn * n;    // on i: pushed away from j
  const double fn_friction = fn > 0.0 ? fn : 0.0;

  if (tangential.kind == TangentialModel::Kind::Viscous) {
    force -= tangential.mu_viscous * fn_friction * v_tangent;
  } else if (tangential.kind == TangentialModel::Kind::History) {
    Eigen::Map<Vec3> shear(history);
    // keep the stored displacement on the current tangent plane, at its length, as the
    // contact normal turns
    const double length = shear.norm();
    shear -= shear.dot(n) * n;
    const double projected = shear.norm();
    if (projected > 0.0) shear *= length / projected;
    shear += v_tangent * dt;
    Vec3 ft = -tangential.kt * shear;
    const double limit = tangential.mu * fn_friction;
    const double ft_norm = ft.norm();
    if (ft_norm > limit) {
      ft *= limit / ft_norm;    // sliding: the spring follows the Coulomb force
      shear = -ft / tangential.kt;
    }
    force += ft;
  }

  out.force_i = force;
  out.torque_i = motion.branch_i.cross(force);
  out.torque_j = motion.branch_j.cross(-force);

  if (rolling.kind == RollingModel::Kind::Constant && fn_friction > 0.0) {
    const Vec3 omega_rel = motion.omega_i - motion.omega_j;
    const Vec3 omega_roll = omega_rel - omega_rel.dot(n) * n;
    const double w = omega_roll.norm();
    if (w > 0.0) {
      const Vec3 torque =
          -rolling.mu_roll * geometry.effective_radius * fn_friction / w * omega_roll;
      out.torque_i += torque;
      out.torque_j -= torque;
    }
  }
  return out;
}

}    // namespace EllipsoidDep
