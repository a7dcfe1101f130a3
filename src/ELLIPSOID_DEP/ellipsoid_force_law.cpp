/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: contact force laws (see ellipsoid_force_law.h and
   doc/pair_granular_ellipsoid.rst for the equations).
------------------------------------------------------------------------- */

#include "ellipsoid_force_law.h"

#include <cmath>
#include <cstdlib>

namespace EllipsoidDep {

namespace {

  // sqrt(5/6): the factor of the Tsuji-type damping derived from the restitution coefficient
  const double SQRT_5_6 = std::sqrt(5.0 / 6.0);
  const double PI = 3.14159265358979323846;

  bool to_number(const std::string &word, double &value)
  {
    if (word.empty()) return false;
    char *end = nullptr;
    value = std::strtod(word.c_str(), &end);
    return end && *end == '\0' && std::isfinite(value);
  }

}    // namespace

std::string ForceLaw::validate() const
{
  if (normal == Normal::Hertz) {
    if (!(kn > 0.0)) return "hertz kn must be > 0";
    if (!(damping >= 0.0)) return "hertz damping K must be >= 0";
  } else {
    if (!(youngs > 0.0)) return "hertz/material E must be > 0";
    if (!(poisson > -1.0 && poisson < 0.5)) return "hertz/material nu must be in (-1, 0.5)";
    if (!(restitution > 0.0 && restitution <= 1.0)) return "hertz/material e must be in (0, 1]";
  }
  if (tangential == Tangential::Viscous && !(mu_viscous >= 0.0))
    return "tangential viscous mu must be >= 0";
  if (tangential == Tangential::History) {
    if (!(kt > 0.0)) return "tangential history kt must be > 0";
    if (!(mu >= 0.0)) return "tangential history mu must be >= 0";
  }
  if (rolling == Rolling::Constant && !(mu_roll >= 0.0))
    return "rolling constant mu_r must be >= 0";
  return {};
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

  double fn;
  if (normal == Normal::Hertz) {
    fn = kn * overlap * sqrt_overlap + damping * sqrt_overlap * overlap_rate;
  } else {
    // Hertz with E* = E / (2 (1 - nu^2)) for two bodies of one material, and the damping of
    // the restitution coefficient e: gamma = -2 sqrt(5/6) beta sqrt(S_n m*), S_n = 2 E* sqrt(R* xi)
    const double e_star = youngs / (2.0 * (1.0 - poisson * poisson));
    const double radius = geometry.effective_radius;
    const double log_e = std::log(restitution);
    const double beta = log_e / std::sqrt(log_e * log_e + PI * PI);
    const double stiffness_n = 2.0 * e_star * std::sqrt(radius) * sqrt_overlap;
    const double gamma = -2.0 * SQRT_5_6 * beta * std::sqrt(stiffness_n * motion.effective_mass);
    fn = 4.0 / 3.0 * e_star * std::sqrt(radius) * overlap * sqrt_overlap + gamma * overlap_rate;
  }
  out.normal_force = fn;
  Vec3 force = -fn * n;    // on i: pushed away from j
  const double fn_friction = fn > 0.0 ? fn : 0.0;

  if (tangential == Tangential::Viscous) {
    force -= mu_viscous * fn_friction * v_tangent;
  } else if (tangential == Tangential::History) {
    Eigen::Map<Vec3> shear(history);
    // keep the stored displacement on the current tangent plane, at its length, as the
    // contact normal turns
    const double length = shear.norm();
    shear -= shear.dot(n) * n;
    const double projected = shear.norm();
    if (projected > 0.0) shear *= length / projected;
    shear += v_tangent * dt;
    Vec3 ft = -kt * shear;
    const double limit = mu * fn_friction;
    const double ft_norm = ft.norm();
    if (ft_norm > limit) {
      ft *= limit / ft_norm;    // sliding: the spring follows the Coulomb force
      shear = -ft / kt;
    }
    force += ft;
  }

  out.force_i = force;
  out.torque_i = motion.branch_i.cross(force);
  out.torque_j = motion.branch_j.cross(-force);

  if (rolling == Rolling::Constant && fn_friction > 0.0) {
    const Vec3 omega_rel = motion.omega_i - motion.omega_j;
    const Vec3 omega_roll = omega_rel - omega_rel.dot(n) * n;
    const double w = omega_roll.norm();
    if (w > 0.0) {
      const Vec3 torque = -mu_roll * geometry.effective_radius * fn_friction / w * omega_roll;
      out.torque_i += torque;
      out.torque_j -= torque;
    }
  }
  return out;
}

int parse_force_law(const std::vector<std::string> &words, ForceLaw &law, std::string &error,
                    const MaterialLookup &lookup)
{
  std::size_t k = 0;
  auto need = [&](std::size_t count, const char *what) {
    if (k + count > words.size()) {
      error = std::string("missing argument(s) for ") + what;
      return false;
    }
    return true;
  };
  auto number = [&](const char *what, double &value) {
    if (!to_number(words[k], value)) {
      error = std::string("expected a number for ") + what + ", got '" + words[k] + "'";
      return false;
    }
    ++k;
    return true;
  };

  if (k >= words.size()) {
    error = "missing normal model (hertz or hertz/material)";
    return -1;
  }
  if (words[k] == "hertz") {
    ++k;
    law.normal = ForceLaw::Normal::Hertz;
    if (!need(2, "hertz kn K") || !number("hertz kn", law.kn) || !number("hertz K", law.damping))
      return -1;
  } else if (words[k] == "hertz/material") {
    ++k;
    law.normal = ForceLaw::Normal::HertzMaterial;
    if (!need(1, "hertz/material")) return -1;
    double value;
    if (!to_number(words[k], value)) {
      if (!lookup || !lookup(words[k], law.youngs, law.poisson, law.restitution)) {
        error = "unknown material '" + words[k] + "' for hertz/material";
        return -1;
      }
      ++k;
    } else if (!need(3, "hertz/material E nu e") || !number("hertz/material E", law.youngs) ||
               !number("hertz/material nu", law.poisson) ||
               !number("hertz/material e", law.restitution)) {
      return -1;
    }
  } else {
    error = "unknown normal model '" + words[k] + "' (expected hertz or hertz/material)";
    return -1;
  }

  while (k < words.size()) {
    if (words[k] == "tangential") {
      ++k;
      if (!need(1, "tangential")) return -1;
      const std::string model = words[k++];
      if (model == "none") {
        law.tangential = ForceLaw::Tangential::None;
      } else if (model == "viscous") {
        law.tangential = ForceLaw::Tangential::Viscous;
        if (!need(1, "tangential viscous mu") || !number("tangential viscous mu", law.mu_viscous))
          return -1;
      } else if (model == "history") {
        law.tangential = ForceLaw::Tangential::History;
        if (!need(2, "tangential history kt mu") || !number("tangential history kt", law.kt) ||
            !number("tangential history mu", law.mu))
          return -1;
      } else {
        error = "unknown tangential model '" + model + "' (expected none, viscous or history)";
        return -1;
      }
    } else if (words[k] == "rolling") {
      ++k;
      if (!need(1, "rolling")) return -1;
      const std::string model = words[k++];
      if (model == "none") {
        law.rolling = ForceLaw::Rolling::None;
      } else if (model == "constant") {
        law.rolling = ForceLaw::Rolling::Constant;
        if (!need(1, "rolling constant mu_r") || !number("rolling constant mu_r", law.mu_roll))
          return -1;
      } else {
        error = "unknown rolling model '" + model + "' (expected none or constant)";
        return -1;
      }
    } else {
      break;
    }
  }

  error = law.validate();
  return error.empty() ? static_cast<int>(k) : -1;
}

}    // namespace EllipsoidDep
