// GoogleTest suite of the force laws (src/kernel/force_laws): each model against its closed
// form, the Hertz impact against a numerical integration of m xi'' = -k xi^3/2, the mixing
// rules, the restart record (its layout and a round trip), and the refusals of the parameter
// rows. The expected values are computed here from the equations of
// doc/pair_granular_ellipsoid.rst, not with the laws' own helpers.
#include "ellipsoid_force_law.h"
#include "ellipsoid_pair_history.h"
#include "ellipsoid_shape.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using namespace EllipsoidDep;

namespace {

constexpr double kR = 0.3, kMass = 0.7, kOverlap = 1e-3;

std::vector<std::string> split(const std::string &line)
{
  std::vector<std::string> words;
  for (std::size_t a = 0, b; a < line.size(); a = b + 1) {
    b = line.find(' ', a);
    if (b == std::string::npos) b = line.size();
    words.push_back(line.substr(a, b - a));
  }
  return words;
}

ForceLaw parsed(const std::string &line)
{
  ForceLaw law;
  std::string error;
  EXPECT_EQ(parse_force_law(split(line), law, error), static_cast<int>(split(line).size()))
      << error;
  return law;
}

// the refusal of a pair_coeff line ("" when it parses)
std::string refusal(const std::string &line)
{
  ForceLaw law;
  std::string error;
  return parse_force_law(split(line), law, error) < 0 ? error : "";
}

// a contact along +z with overlap kOverlap; i moves with velocity v_i, nothing turns
ContactGeometry geometry()
{
  ContactGeometry g;
  g.status = Status::Overlapping;
  g.normal = Vec3(0, 0, 1);
  g.overlap = kOverlap;
  g.effective_radius = kR;
  return g;
}
ContactMotion motion(const Vec3 &v_i)
{
  ContactMotion m;
  m.v_i = v_i;
  m.branch_i = Vec3(0, 0, 0.5);
  m.branch_j = Vec3(0, 0, -0.5);
  m.effective_mass = kMass;
  return m;
}

// the overlap's history of an undamped head-on impact, m xi'' = -k xi^3/2 (RK4, the step a
// fraction of the time scale): the time back at xi = 0 and the deepest overlap
void integrate_impact(double k, double m, double v, double &duration, double &deepest)
{
  const double scale = std::pow(m * m / (k * k * v), 0.2), dt = scale * 1e-5;
  auto accel = [&](double x) {
    return -k / m * std::pow(std::max(x, 0.0), 1.5);
  };
  double x = 0.0, u = v, t = 0.0;
  deepest = 0.0;
  while (true) {
    const double k1x = u, k1u = accel(x);
    const double k2x = u + 0.5 * dt * k1u, k2u = accel(x + 0.5 * dt * k1x);
    const double k3x = u + 0.5 * dt * k2u, k3u = accel(x + 0.5 * dt * k2x);
    const double k4x = u + dt * k3u, k4u = accel(x + dt * k3x);
    const double x_next = x + dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    u += dt / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
    deepest = std::max(deepest, x_next);
    if (x_next < 0.0) {
      duration = t + dt * x / (x - x_next);    // the crossing, linearly
      return;
    }
    x = x_next;
    t += dt;
  }
}

}    // namespace

TEST(ForceLaws, HertzForceAndDamping)
{
  const ForceLaw law = parsed("hertz 1e5 20");
  const double rate = 0.4;    // approaching
  const ContactForce f = law.compute(geometry(), motion(Vec3(0, 0, rate)), 1e-4, nullptr);
  const double fn = 1e5 * std::pow(kOverlap, 1.5) + 20 * std::sqrt(kOverlap) * rate;
  EXPECT_NEAR(f.normal_force, fn, 1e-14 * fn);
  EXPECT_NEAR(f.force_i.z(), -fn, 1e-14 * fn);
  EXPECT_EQ(f.force_i.x(), 0.0);
  EXPECT_EQ(law.stiffness(kR), 1e5);
  EXPECT_EQ(law.history_size(), 0);
}

TEST(ForceLaws, HertzMaterialForceAndRestitutionDamping)
{
  const double E = 1e7, nu = 0.3, e = 0.6, rate = 0.4;
  const ForceLaw law = parsed("hertz/material 1e7 0.3 0.6");
  const double e_star = E / (2 * (1 - nu * nu));
  const double k = 4.0 / 3.0 * e_star * std::sqrt(kR);
  EXPECT_NEAR(law.stiffness(kR), k, 1e-14 * k);
  const double beta = std::log(e) / std::sqrt(std::log(e) * std::log(e) + PI * PI);
  const double gamma =
      -2 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(2 * e_star * std::sqrt(kR * kOverlap) * kMass);
  const ContactForce f = law.compute(geometry(), motion(Vec3(0, 0, rate)), 1e-4, nullptr);
  const double fn = k * std::pow(kOverlap, 1.5) + gamma * rate;
  EXPECT_NEAR(f.normal_force, fn, 1e-13 * fn);
  // e = 1: no damping
  const ContactForce elastic = parsed("hertz/material 1e7 0.3 1")
                                   .compute(geometry(), motion(Vec3(0, 0, rate)), 1e-4, nullptr);
  EXPECT_NEAR(elastic.normal_force, k * std::pow(kOverlap, 1.5), 1e-14 * fn);
}

TEST(ForceLaws, LimitDampingClipsAttraction)
{
  const Vec3 leaving(0, 0, -10.0);
  const double fn = 1e5 * std::pow(kOverlap, 1.5) - 20 * std::sqrt(kOverlap) * 10.0;
  ASSERT_LT(fn, 0.0);
  const ContactForce pulled = parsed("hertz 1e5 20 tangential viscous 1")
                                  .compute(geometry(), motion(leaving), 0.0, nullptr);
  EXPECT_NEAR(pulled.normal_force, fn, 1e-12 * std::fabs(fn));
  const ContactForce clipped =
      parsed("hertz 1e5 20 tangential viscous 1 limit_damping")
          .compute(geometry(), motion(leaving + Vec3(1, 0, 0)), 0.0, nullptr);
  EXPECT_EQ(clipped.normal_force, 0.0);
  EXPECT_EQ(clipped.force_i, Vec3::Zero());    // no friction without a load
}

TEST(ForceLaws, HertzImpactAgainstIntegration)
{
  for (const char *line : {"hertz 1e5 20", "hertz/material 1e6 0.25 0.8"}) {
    const ForceLaw law = parsed(line);
    const double v = 1.7, k = law.stiffness(kR);
    double duration, deepest;
    integrate_impact(k, kMass, v, duration, deepest);
    EXPECT_NEAR(law.contact_time(kR, kMass, v), duration, 1e-6 * duration) << line;
    EXPECT_NEAR(law.deepest_overlap(kR, kMass, v), deepest, 1e-6 * deepest) << line;
    // the closed forms: (5 m v^2 / (4 k))^(2/5) and 2 (2/5) B(2/5, 1/2) xi_max / v
    const double xi = std::pow(5 * kMass * v * v / (4 * k), 0.4);
    const double b = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
    EXPECT_NEAR(law.contact_time(kR, kMass, v), 2 * 0.4 * b * xi / v, 1e-14 * duration);
    // ftm2v divides the inertia
    EXPECT_DOUBLE_EQ(law.contact_time(kR, kMass, v, 4.0), law.contact_time(kR, kMass / 4.0, v));
  }
}

TEST(ForceLaws, DampingTimeAtTheDeepestOverlap)
{
  const double v = 1.7, ftm2v = 2.5;
  const ForceLaw hertz = parsed("hertz 1e5 20");
  const double xi = hertz.deepest_overlap(kR, kMass, v, ftm2v);
  EXPECT_NEAR(hertz.damping_time(kR, kMass, v, ftm2v), kMass / ftm2v / (20 * std::sqrt(xi)), 1e-14);
  EXPECT_EQ(parsed("hertz 1e5 0").damping_time(kR, kMass, v), HUGE_VAL);
  EXPECT_EQ(parsed("hertz/material 1e6 0.25 1").damping_time(kR, kMass, v), HUGE_VAL);
  EXPECT_STREQ(hertz.elastic_law(), "Hertz");
  EXPECT_STREQ(parsed("hertz/material 1e6 0.25 1").elastic_law(), "Hertz");
}

TEST(ForceLaws, TangentialDampingTimeAtThePeakForce)
{
  const double v = 1.7, ftm2v = 2.5, sliding = 0.2;
  const ForceLaw viscous = parsed("hertz 1e5 20 tangential viscous 0.5");
  const double xi = std::pow(5 * (kMass / ftm2v) * v * v / (4 * 1e5), 0.4);
  const double peak = 1e5 * std::pow(xi, 1.5);
  EXPECT_NEAR(viscous.tangential_damping_time(kR, kMass, sliding, v, ftm2v),
              sliding / ftm2v / (0.5 * peak), 1e-12 * sliding / peak);
  // the dashpot grows with the impact: a faster impact damps faster
  EXPECT_LT(viscous.tangential_damping_time(kR, kMass, sliding, 2 * v),
            viscous.tangential_damping_time(kR, kMass, sliding, v));
  for (const char *line : {"hertz 1e5 20", "hertz 1e5 20 tangential history 2e3 0.5",
                           "hertz 1e5 20 rolling constant 0.1",
                           "hertz 1e5 0 tangential history 2e3 0.5 xt 1"})
    EXPECT_EQ(parsed(line).tangential_damping_time(kR, kMass, sliding, v), HUGE_VAL) << line;
  // the history dashpot: xt gamma_n at the deepest overlap
  const ForceLaw damped = parsed("hertz 1e5 20 tangential history 2e3 0.5 xt 0.5");
  EXPECT_NEAR(damped.tangential_damping_time(kR, kMass, sliding, v, ftm2v),
              sliding / ftm2v / (0.5 * 20 * std::sqrt(xi)), 1e-12 * sliding);
}

// The largest m (r x t) . I^-1 (r x t) of a solid ellipsoid with semi-axes s over sampled
// surface points r and unit tangents t there (body frame, I_k = m (s_j^2 + s_l^2) / 5): for
// each point the largest eigenvalue of the form on its tangent plane.
double sampled_compliance(const Vec3 &s)
{
  const Vec3 inverse_inertia(5 / (s[1] * s[1] + s[2] * s[2]), 5 / (s[0] * s[0] + s[2] * s[2]),
                             5 / (s[0] * s[0] + s[1] * s[1]));
  double largest = 0.0;
  const int n = 200;
  for (int i = 0; i <= n; i++)
    for (int k = 0; k < 2 * n; k++) {
      const double theta = M_PI * i / n, phi = M_PI * k / n;
      const Vec3 u(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta));
      const Vec3 r = u.cwiseProduct(s);
      const Vec3 normal = r.cwiseQuotient(s.cwiseProduct(s)).normalized();
      Vec3 e1 = normal.cross(std::fabs(normal[0]) < 0.9 ? Vec3::UnitX() : Vec3::UnitY());
      e1.normalize();
      const Vec3 e2 = normal.cross(e1);
      auto form = [&](const Vec3 &a, const Vec3 &b) {
        return r.cross(a).cwiseProduct(inverse_inertia).dot(r.cross(b));
      };
      const double p = form(e1, e1), q = form(e2, e2), c = form(e1, e2);
      largest = std::max(largest, 0.5 * (p + q) + std::sqrt(0.25 * (p - q) * (p - q) + c * c));
    }
  return largest;
}

TEST(ForceLaws, RotationalComplianceBoundsTheSampledMaximum)
{
  // a sphere's tangential force at its surface: 1/m + R^2/I = (1 + 5/2)/m
  EXPECT_NEAR(rotational_compliance(1, 1, 1), 2.5, 1e-15);
  EXPECT_NEAR(rotational_compliance(0.3, 0.3, 0.3), 2.5, 1e-14);    // scale-free
  // the default deposit's shape, a needle, a disc, a prolate body and triaxial ones (the
  // study's diagonal ends at eta = zeta = 3, semi-axes 9:3:1)
  for (const Vec3 &s : {Vec3(2.52, 1.8, 1), Vec3(10, 1, 1), Vec3(1, 1, 0.05), Vec3(1.4, 1, 1),
                        Vec3(3, 2, 1), Vec3(9, 3, 1)}) {
    const double bound = rotational_compliance(s[0], s[1], s[2]), sampled = sampled_compliance(s);
    EXPECT_GE(bound * (1 + 1e-12), sampled) << s.transpose();    // the disc's is exact
    // a bound, not the maximum: within 50 % of it up to 3:2:1, 83 % at 9:3:1
    EXPECT_LE(bound, (s[0] / s[2] > 5 && s[1] / s[2] > 2 ? 1.85 : 1.5) * sampled)
        << s.transpose();
    EXPECT_DOUBLE_EQ(rotational_compliance(s[2], s[0], s[1]), bound) << s.transpose();
  }
}

TEST(ForceLaws, ViscousTangential)
{
  const Vec3 v(0.3, -0.2, 0.1);
  const ForceLaw law = parsed("hertz 1e5 0 tangential viscous 0.5");
  const ContactForce f = law.compute(geometry(), motion(v), 1e-4, nullptr);
  const double fn = 1e5 * std::pow(kOverlap, 1.5);
  const Vec3 expected(-0.5 * fn * 0.3, -0.5 * fn * -0.2, -fn);
  EXPECT_LT((f.force_i - expected).norm(), 1e-14 * fn);
  // the torques of that force about the centres
  EXPECT_LT((f.torque_i - Vec3(0, 0, 0.5).cross(expected)).norm(), 1e-14 * fn);
  EXPECT_LT((f.torque_j - Vec3(0, 0, -0.5).cross(-expected)).norm(), 1e-14 * fn);
}

TEST(ForceLaws, HistoryTangentialSpringAndCoulombCap)
{
  const ForceLaw law = parsed("hertz 1e5 0 tangential history 1e3 0.5");
  ASSERT_EQ(law.history_size(), 3);
  const double fn = 1e5 * std::pow(kOverlap, 1.5), dt = 1e-4;
  double s[HistoryTangential::HISTORY_SIZE] = {};
  // sticking: F_t = -kt v_t dt
  ContactForce f = law.compute(geometry(), motion(Vec3(1e-3, 0, 0)), dt, s);
  EXPECT_DOUBLE_EQ(s[0], 1e-3 * dt);
  EXPECT_DOUBLE_EQ(f.force_i.x(), -1e3 * 1e-3 * dt);
  // sliding: capped at mu F_n, the spring stretched to the cap
  f = law.compute(geometry(), motion(Vec3(0, 100.0, 0)), dt, s);
  const double cap = 0.5 * fn;
  EXPECT_NEAR(Vec3(f.force_i.x(), f.force_i.y(), 0).norm(), cap, 1e-14 * cap);
  EXPECT_NEAR(Vec3(s[0], s[1], s[2]).norm(), cap / 1e3, 1e-14 * cap);
  EXPECT_DOUBLE_EQ(f.force_i.y() / f.force_i.x(), s[1] / s[0]);
  // a turned normal: the displacement on the new tangent plane, at its length
  double turned[HistoryTangential::HISTORY_SIZE] = {2e-6};
  ContactGeometry g = geometry();
  g.normal = Vec3(1, 0, 1).normalized();
  law.compute(g, motion(Vec3::Zero()), dt, turned);
  const Vec3 t(turned[0], turned[1], turned[2]);
  EXPECT_NEAR(t.dot(g.normal), 0.0, 1e-20);
  EXPECT_NEAR(t.norm(), 2e-6, 1e-20);
}

// The dashpot of "tangential history kt mu xt X": -xt gamma_n v_t added to the spring, gamma_n
// the normal model's damping coefficient at the contact; sliding, the spring keeps the share
// of the Coulomb force the dashpot leaves (LAMMPS's tangential linear_history).
TEST(ForceLaws, HistoryTangentialDashpot)
{
  const double K = 40, xt = 0.7, dt = 1e-4;
  const ForceLaw law = parsed("hertz 1e5 40 tangential history 1e3 0.5 xt 0.7");
  const double gamma_n = K * std::sqrt(kOverlap), fn = 1e5 * std::pow(kOverlap, 1.5);
  double s[HistoryTangential::HISTORY_SIZE] = {};
  const Vec3 slow(1e-3, -2e-3, 0);
  ContactForce f = law.compute(geometry(), motion(slow), dt, s);
  EXPECT_LT((Vec3(s[0], s[1], s[2]) - slow * dt).norm(), 1e-20);
  const Vec3 expected_t = -1e3 * slow * dt - xt * gamma_n * slow;
  EXPECT_LT((Vec3(f.force_i.x(), f.force_i.y(), 0) - expected_t).norm(),
            1e-14 * expected_t.norm());
  // sliding: |F_t| = mu F_n, and -kt s is what remains after the dashpot
  const Vec3 fast(0, 5.0, 0);
  f = law.compute(geometry(), motion(fast), dt, s);
  const Vec3 ft(f.force_i.x(), f.force_i.y(), 0);
  EXPECT_NEAR(ft.norm(), 0.5 * fn, 1e-14 * fn);
  EXPECT_LT((-1e3 * Vec3(s[0], s[1], s[2]) - (ft + xt * gamma_n * fast)).norm(), 1e-13 * fn);
  // xt absent is xt 0: the spring alone, to the bit
  double a[3] = {1e-7, 2e-7, 0}, b[3] = {1e-7, 2e-7, 0};
  const ContactForce plain = parsed("hertz 1e5 40 tangential history 1e3 0.5")
                                 .compute(geometry(), motion(slow), dt, a);
  const ContactForce zero = parsed("hertz 1e5 40 tangential history 1e3 0.5 xt 0")
                                .compute(geometry(), motion(slow), dt, b);
  EXPECT_EQ(plain.force_i, zero.force_i);
  EXPECT_EQ(Vec3(a[0], a[1], a[2]), Vec3(b[0], b[1], b[2]));
  // the dashpot of hertz/material: xt times the restitution damping
  const ForceLaw material = parsed("hertz/material 1e7 0.3 0.5 tangential history 1e3 10 xt 2");
  const double log_e = std::log(0.5), beta = log_e / std::sqrt(log_e * log_e + M_PI * M_PI);
  const double e_star = 1e7 / (2 * (1 - 0.09));
  const double gamma_m =
      -2 * std::sqrt(5.0 / 6) * beta * std::sqrt(2 * e_star * std::sqrt(kR * kOverlap) * kMass);
  double m[3] = {};
  f = material.compute(geometry(), motion(slow), dt, m);
  const Vec3 expected_m = -1e3 * slow * dt - 2 * gamma_m * slow;
  EXPECT_LT((Vec3(f.force_i.x(), f.force_i.y(), 0) - expected_m).norm(),
            1e-12 * expected_m.norm());
}

// mu 0: the Coulomb limit cancels the spring and the dashpot at any displacement, so the law is
// frictionless: the forces and torques of tangential none bit for bit, and its displacement is
// neither computed nor written (the pair skips that work; the slots stay as they were)
TEST(ForceLaws, HistoryTangentialWithoutFrictionIsTangentialNone)
{
  const ForceLaw none = parsed("hertz 1e5 20");
  for (const char *line :
       {"hertz 1e5 20 tangential history 1e4 0", "hertz 1e5 20 tangential history 1e4 0 xt 0.5"}) {
    SCOPED_TRACE(line);
    const ForceLaw frictionless = parsed(line);
    ASSERT_EQ(frictionless.history_size(), 3);
    for (int step = 0; step < 20; ++step) {
      ContactGeometry g = geometry();
      g.normal = Vec3(std::sin(0.3 * step), 0.2, std::cos(0.3 * step)).normalized();
      ContactMotion m = motion(Vec3(0.3 - 0.05 * step, 0.7, -0.2));
      m.omega_i = Vec3(0.1 * step, -0.4, 0.25);
      double slots[3] = {0.0, 0.0, 0.0};
      const ContactForce a = frictionless.compute(g, m, 1e-3, slots);
      const ContactForce b = none.compute(g, m, 1e-3, nullptr);
      for (int d = 0; d < 3; ++d) {
        EXPECT_EQ(std::memcmp(&a.force_i[d], &b.force_i[d], sizeof(double)), 0) << d;
        EXPECT_EQ(std::memcmp(&a.torque_i[d], &b.torque_i[d], sizeof(double)), 0) << d;
        EXPECT_EQ(std::memcmp(&a.torque_j[d], &b.torque_j[d], sizeof(double)), 0) << d;
        const double zero = 0.0;
        EXPECT_EQ(std::memcmp(&slots[d], &zero, sizeof(double)), 0) << "slot " << d;
      }
    }
  }
}

TEST(ForceLaws, ConstantRollingTorque)
{
  const ForceLaw law = parsed("hertz 1e5 0 rolling constant 0.2");
  ContactMotion m = motion(Vec3::Zero());
  m.omega_i = Vec3(3, 0, 5);    // rolling about x, twisting about the normal
  const ContactForce f = law.compute(geometry(), m, 1e-4, nullptr);
  const double fn = 1e5 * std::pow(kOverlap, 1.5);
  const Vec3 torque(-0.2 * kR * fn, 0, 0);
  EXPECT_LT((f.torque_i - torque).norm(), 1e-14 * fn);
  EXPECT_LT((f.torque_j + torque).norm(), 1e-14 * fn);
}

// rolling sds: spring and dashpot on the rolling angle, the slider at mu_r R* F_n; the stored
// angle follows the rolling, turns with the normal and is reset on the slider
TEST(ForceLaws, SdsRollingSpringDashpotSlider)
{
  const double k = 50, gamma = 0.4, dt = 1e-3;
  const double fn = 1e5 * std::pow(kOverlap, 1.5);
  ContactMotion m = motion(Vec3::Zero());
  m.omega_i = Vec3(3, 0, 5);    // rolling about x, twisting about the normal z
  m.omega_j = Vec3(1, 0, 0);
  const Vec3 roll(2, 0, 0);
  // elastic: theta = w_roll dt, M = -R*^2 (k theta + gamma w_roll), on j the opposite
  double history[SdsRolling::HISTORY_SIZE] = {0, 0, 0};
  const ForceLaw soft = parsed("hertz 1e5 0 rolling sds 50 0.4 10");
  ContactForce f = soft.compute(geometry(), m, dt, history);
  Vec3 torque = -kR * kR * (k * roll * dt + gamma * roll);
  EXPECT_LT((f.torque_i - torque).norm(), 1e-15);
  EXPECT_LT((f.torque_j + torque).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(history[0], 2 * dt);
  // the next step adds to the angle; the normal turned about y carries it along, at its length
  ContactGeometry turned = geometry();
  turned.normal = Vec3(std::sin(0.1), 0, std::cos(0.1));
  ContactMotion still = m;
  still.omega_i = still.omega_j;    // no more rolling
  f = soft.compute(turned, still, dt, history);
  const Vec3 carried = 2 * dt * Vec3(std::cos(0.1), 0, -std::sin(0.1));
  EXPECT_LT((Vec3(history[0], history[1], history[2]) - carried).norm(), 1e-15);
  const Vec3 rolling_torque = f.torque_i - still.branch_i.cross(f.force_i);
  EXPECT_LT((rolling_torque + kR * kR * k * carried).norm(), 1e-14);
  // the slider: a stiff spring saturates at mu_r R* F_n against the rolling, and keeps the
  // angle whose spring with the dashpot gives that torque
  double slid[SdsRolling::HISTORY_SIZE] = {0.5, 0, 0};
  const ForceLaw stiff = parsed("hertz 1e5 0 rolling sds 1e4 0.4 0.2");
  f = stiff.compute(geometry(), m, dt, slid);
  EXPECT_NEAR(f.torque_i.norm(), 0.2 * kR * fn, 1e-14 * fn);
  EXPECT_GT(f.torque_i.normalized().dot(Vec3(-1, 0, 0)), 1 - 1e-14);
  const Vec3 angle(slid[0], slid[1], slid[2]);
  EXPECT_LT((-kR * kR * (1e4 * angle + 0.4 * roll) - f.torque_i).norm(), 1e-12 * f.torque_i.norm());
  // at rest up to round-off, nothing stored: a round-off torque (constant's switches fully on)
  double rest[SdsRolling::HISTORY_SIZE] = {0, 0, 0};
  ContactMotion resting = motion(Vec3::Zero());
  resting.omega_i = Vec3(1e-12, 0, 0);
  EXPECT_LT(stiff.compute(geometry(), resting, dt, rest).torque_i.norm(),
            kR * kR * (1e4 * dt + 0.4) * 1e-12 * (1 + 1e-12));
  EXPECT_GT(parsed("hertz 1e5 0 rolling constant 0.2").compute(geometry(), resting, dt, nullptr)
                .torque_i.norm(),
            0.1 * kR * fn);
}

TEST(ForceLaws, MixingRules)
{
  ForceLaw mixed;
  ASSERT_EQ(mix_laws(parsed("hertz/material 1e7 0.2 0.9 tangential history 1e3 0.4"),
                     parsed("hertz/material 4e7 0.4 0.4 tangential history 4e3 0.1"), mixed),
            "");
  const double e_star = 1.0 / ((1 - 0.04) / 1e7 + (1 - 0.16) / 4e7);
  EXPECT_NEAR(mixed.stiffness(kR), 4.0 / 3.0 * e_star * std::sqrt(kR), 1e-14 * e_star);
  const auto &normal = std::get<HertzMaterialNormal>(mixed.normal);
  EXPECT_DOUBLE_EQ(normal.poisson, 0.3);
  EXPECT_DOUBLE_EQ(normal.restitution, 0.6);
  const auto &tangential = std::get<HistoryTangential>(mixed.tangential);
  EXPECT_DOUBLE_EQ(tangential.kt, 2e3);
  EXPECT_DOUBLE_EQ(tangential.mu, 0.2);
  // equal values stay bit for bit
  ASSERT_EQ(mix_laws(parsed("hertz 3e5 7"), parsed("hertz 3e5 7"), mixed), "");
  EXPECT_EQ(std::get<HertzNormal>(mixed.normal).kn, 3e5);
  EXPECT_EQ(mix_laws(parsed("hertz 1 1"), parsed("hertz 1 1 tangential viscous 1"), mixed),
            "cannot mix 'hertz, tangential none, rolling none' with 'hertz, tangential viscous, "
            "rolling none'");
  EXPECT_NE(mix_laws(parsed("hertz 1 1"), parsed("hertz 1 1 limit_damping"), mixed), "");
}

// The record of restart files: its layout is fixed (old files must read), and it round-trips.
TEST(ForceLaws, RestartRecordLayoutAndRoundTrip)
{
  // the first version's 13 values, then rolling sds's three, then tangential history's
  // optional xt (each appended: an old record is the start of a new one)
  ASSERT_EQ(packed_law_size(), 17);
  const std::vector<double> hertz = pack_law(parsed("hertz 1e5 20 tangential viscous 0.5"));
  EXPECT_EQ(hertz,
            (std::vector<double>{0, 0, 1e5, 20, 0, 0, 1, 1, 0.5, 0, 0, 0, 0, 0, 0, 0, 0}));
  const std::vector<double> material =
      pack_law(parsed("hertz/material 1e7 0.3 0.6 tangential history 1e3 0.4 rolling constant "
                      "0.1 limit_damping"));
  EXPECT_EQ(material,
            (std::vector<double>{1, 1, 0, 0, 1e7, 0.3, 0.6, 2, 0, 1e3, 0.4, 1, 0.1, 0, 0, 0, 0}));
  const std::vector<double> sds = pack_law(parsed("hertz 1 2 rolling sds 3 4 5"));
  EXPECT_EQ(sds, (std::vector<double>{0, 0, 1, 2, 0, 0, 1, 0, 0, 0, 0, 2, 0, 3, 4, 5, 0}));
  const std::vector<double> damped =
      pack_law(parsed("hertz 1 2 tangential history 3 0.4 xt 0.5 rolling sds 3 4 5"));
  EXPECT_EQ(damped,
            (std::vector<double>{0, 0, 1, 2, 0, 0, 1, 2, 0, 3, 0.4, 2, 0, 3, 4, 5, 0.5}));
  for (const auto &record : {hertz, material, sds, damped}) {
    ForceLaw law;
    ASSERT_TRUE(unpack_law(record.data(), law));
    EXPECT_EQ(pack_law(law), record);
  }
  ForceLaw law;
  for (double code : {3.0, -1.0, 1.5, std::nan("")}) {
    std::vector<double> bad = hertz;
    bad[7] = code;    // the tangential model's code
    EXPECT_FALSE(unpack_law(bad.data(), law)) << code;
  }
}

TEST(ForceLaws, ParameterRefusals)
{
  EXPECT_EQ(refusal("hertz -1 20"), "hertz kn must be > 0");
  EXPECT_EQ(refusal("hertz 1 -2"), "hertz K must be >= 0");
  EXPECT_EQ(refusal("hertz/material 1e7 0.5 0.5"), "hertz/material nu must be in (-1, 0.5)");
  EXPECT_EQ(refusal("hertz/material 1e7 0.3 0"), "hertz/material e must be in (0, 1]");
  EXPECT_EQ(refusal("hertz 1 1 tangential history 0 0.5"), "tangential history kt must be > 0");
  EXPECT_EQ(refusal("hertz 1 1 tangential history 1 0.5 xt -1"),
            "tangential history xt must be >= 0");
  EXPECT_EQ(refusal("hertz 1 1 tangential history 1 0.5 xt"),
            "missing value for tangential history xt");
  EXPECT_EQ(refusal("hertz 1 1 tangential history 1 0.5 xt x"),
            "expected a number for tangential history xt, got 'x'");
  EXPECT_EQ(refusal("hertz 1 1 tangential history 1"),
            "missing argument(s) for tangential history kt mu");
  {    // xt is history's word: after viscous the parse stops there, for the caller to refuse
    ForceLaw law;
    std::string error;
    EXPECT_EQ(parse_force_law(split("hertz 1 1 tangential viscous 1 xt 1"), law, error), 6);
  }
  EXPECT_EQ(refusal("hertz 1 1 rolling constant 1.5"), "rolling constant mu_r must be in [0, 1]");
  EXPECT_EQ(refusal("hertz 1 1 rolling sds 1 -1 0.1"), "rolling sds gamma_r must be >= 0");
  EXPECT_EQ(refusal("hertz 1 1 rolling sds 1 1"), "missing argument(s) for rolling sds k_r gamma_r mu_r");
  EXPECT_EQ(refusal("hertz 1"), "missing argument(s) for hertz kn K");
  EXPECT_EQ(refusal("hertz 1 x"), "expected a number for hertz K, got 'x'");
  EXPECT_EQ(refusal("hooke 1 1"),
            "unknown normal model 'hooke' (expected hertz or hertz/material)");
  EXPECT_EQ(refusal("hertz 1 1 tangential"), "missing tangential model (none, viscous or history)");
  EXPECT_EQ(refusal("hertz/material glass"), "unknown material 'glass' for hertz/material");
  EXPECT_NE(refusal("hertz 1 1 tangential mindlin").find("LAMMPS pair granular's syntax"),
            std::string::npos);
  EXPECT_NE(refusal("hertz 1 1 damping coeff_restitution").find("applies only to hertz/material"),
            std::string::npos);
  EXPECT_NE(refusal("hertz/material 1e7 0.5 0.3 damping viscoelastic").find("is not available"),
            std::string::npos);
  // LAMMPS's order E e nu with its damping word is this style's E nu e
  EXPECT_EQ(pack_law(parsed("hertz/material 1e7 0.5 0.3 damping coeff_restitution")),
            pack_law(parsed("hertz/material 1e7 0.3 0.5")));
  EXPECT_EQ(
      describe_models(parsed("hertz/material 1e7 0.3 0.5 tangential history 1 1 limit_damping")),
      "hertz/material, tangential history, rolling none, limit_damping");
}

TEST(ForceLaws, MaterialNames)
{
  const MaterialLookup lookup = [](const std::string &name, Material &m) -> std::string {
    if (name != "glass") return "no " + name;
    m = {6.3e10, 0.22, 0.9};
    return "";
  };
  ForceLaw law;
  std::string error;
  EXPECT_EQ(parse_force_law({"hertz/material", "glass", "rolling", "constant", "0.1"}, law, error,
                            lookup),
            5);
  EXPECT_EQ(pack_law(law), pack_law(parsed("hertz/material 6.3e10 0.22 0.9 rolling constant 0.1")));
  EXPECT_EQ(parse_force_law({"hertz/material", "steel"}, law, error, lookup), -1);
  EXPECT_EQ(error, "no steel");
  // the numbers of a name cannot be reordered by LAMMPS's damping word
  EXPECT_EQ(parse_force_law({"hertz/material", "glass", "damping", "coeff_restitution"}, law, error,
                            lookup),
            -1);
}

// The history a law keeps follows from its models, sits after the pipeline's slots in a pair's
// row (layout 3: 10 + 3 with a tangential history) and obeys the swap rule: the pair seen
// from j, with the negated history, gets the negated force and history.
TEST(ForceLaws, HistorySlotsOfTheModels)
{
  EXPECT_EQ(parsed("hertz 1 1 tangential viscous 1 rolling constant 0.1").history_size(), 0);
  const ForceLaw law = parsed("hertz 1e5 0 tangential history 1e3 0.5");
  ASSERT_EQ(law.history_size(), HistoryTangential::HISTORY_SIZE);
  EXPECT_EQ(ForceLaw::MAX_HISTORY_SIZE, HistoryTangential::HISTORY_SIZE + SdsRolling::HISTORY_SIZE);
  EXPECT_EQ(PairHistory::LAYOUT_VERSION, 3);
  constexpr int ROW = PairHistory::size(HistoryTangential::HISTORY_SIZE);
  EXPECT_EQ(ROW, 13);
  EXPECT_EQ(PairHistory::LAW, PairHistory::PIPELINE_SIZE);

  double row[ROW], swapped[ROW];
  for (int k = 0; k < ROW; ++k) row[k] = 0.01 * (k + 1);
  PairHistory::swapped(row, swapped, ROW);
  ContactMotion from_i = motion(Vec3(0.3, -0.2, 0.1)), from_j;
  from_i.omega_i = Vec3(0.5, 1, -2);
  from_j.v_j = from_i.v_i;
  from_j.omega_j = from_i.omega_i;
  from_j.branch_i = from_i.branch_j;
  from_j.branch_j = from_i.branch_i;
  from_j.effective_mass = kMass;
  ContactGeometry seen_from_j = geometry();
  seen_from_j.normal = -seen_from_j.normal;
  const ContactForce f = law.compute(geometry(), from_i, 1e-4, PairHistory(row).law());
  const ContactForce g = law.compute(seen_from_j, from_j, 1e-4, PairHistory(swapped).law());
  EXPECT_EQ(g.force_i, -f.force_i);
  for (int k = PairHistory::LAW; k < ROW; ++k) EXPECT_EQ(swapped[k], -row[k]) << k;

  // rolling sds's angle follows the displacement in the row and is negated on a swap too
  const ForceLaw rolling = parsed("hertz 1e5 0 tangential history 1e3 0.5 rolling sds 50 0.4 0.3");
  constexpr int ROLLING_ROW =
      PairHistory::size(HistoryTangential::HISTORY_SIZE + SdsRolling::HISTORY_SIZE);
  ASSERT_EQ(rolling.history_size(), ROLLING_ROW - PairHistory::LAW);
  double rolling_row[ROLLING_ROW], rolling_swapped[ROLLING_ROW];
  for (int k = 0; k < ROLLING_ROW; ++k) rolling_row[k] = 0.01 * (k + 1);
  PairHistory::swapped(rolling_row, rolling_swapped, ROLLING_ROW);
  const ContactForce fr = rolling.compute(geometry(), from_i, 1e-4, PairHistory(rolling_row).law());
  const ContactForce gr =
      rolling.compute(seen_from_j, from_j, 1e-4, PairHistory(rolling_swapped).law());
  EXPECT_EQ(gr.force_i, -fr.force_i);
  EXPECT_EQ(gr.torque_i, fr.torque_j);
  for (int k = PairHistory::LAW; k < ROLLING_ROW; ++k)
    EXPECT_EQ(rolling_swapped[k], -rolling_row[k]) << k;

  // a look (setup forces, single()) does not advance the stored history
  double stored[HistoryTangential::HISTORY_SIZE] = {1e-4},
         advanced[HistoryTangential::HISTORY_SIZE] = {1e-4};
  const LawHistory look(stored, law.history_size(), false);
  const ContactForce looked = law.compute(geometry(), from_i, 1e-4, look.get());
  EXPECT_EQ(looked.force_i, law.compute(geometry(), from_i, 1e-4, advanced).force_i);
  EXPECT_EQ(stored[0], 1e-4);
  EXPECT_NE(advanced[1], 0.0);
  const LawHistory step(stored, law.history_size(), true);
  EXPECT_EQ(step.get(), stored);
}
