// GoogleTest suite of the pour sampler (ellipsoid_pour_sampler.h): sizes, shapes and
// orientations of poured particles, tested as distributions.
//
// Every statistical test uses a fixed seed and the asymptotic Kolmogorov distribution:
// sqrt(n) D < 1.95 is the 0.1 % acceptance level (P(sqrt(n) D > 1.949) = 0.001). Each
// distribution test is paired with a check that the same statistic REJECTS a wrong
// distribution (sqrt(n) D > 5, a p-value below 1e-20), so the tests have power. The
// reference CDFs are analytic or integrated here by quadrature, independently of the
// sampler's own integrals.
#include "ellipsoid_pour_sampler.h"
#include "ellipsoid_shape.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <vector>

using namespace EllipsoidDep;

namespace {

constexpr double kPi = EllipsoidDep::PI;
constexpr double kAccept = 1.95;    // sqrt(n) D at the 0.1 % level
constexpr double kReject = 5.0;     // sqrt(n) D a wrong distribution must exceed
constexpr int kSamples = 20000;

// uniform deviates on (0, 1) from 53 random bits, never 0 or 1 (logarithms of them are taken)
UniformSource seeded_uniform(std::uint64_t seed)
{
  auto engine = std::make_shared<std::mt19937_64>(seed);
  return [engine] {
    return ((*engine)() >> 11) * 0x1.0p-53 + 0x1.0p-54;
  };
}

// sqrt(n) times the Kolmogorov-Smirnov distance of a sample from a continuous CDF
double ks_statistic(std::vector<double> x, const std::function<double(double)> &cdf)
{
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  double d = 0.0;
  for (std::size_t i = 0; i < x.size(); i++) {
    const double f = cdf(x[i]);
    d = std::max({d, (i + 1) / n - f, f - i / n});
  }
  return std::sqrt(n) * d;
}

// sqrt(n_eff) times the distance of the weight-w empirical CDF from cdf, with Kish's
// effective sample size n_eff = (sum w)^2 / sum w^2 (the Kolmogorov limit then holds
// approximately)
double weighted_ks_statistic(const std::vector<double> &x, const std::vector<double> &w,
                             const std::function<double(double)> &cdf)
{
  std::vector<std::size_t> order(x.size());
  for (std::size_t i = 0; i < order.size(); i++) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return x[i] < x[j];
  });
  double total = 0.0, total2 = 0.0;
  for (double wi : w) {
    total += wi;
    total2 += wi * wi;
  }
  double below = 0.0, d = 0.0;
  for (std::size_t k : order) {
    const double f = cdf(x[k]);
    d = std::max(d, f - below / total);
    below += w[k];
    d = std::max(d, below / total - f);
  }
  return std::sqrt(total * total / total2) * d;
}

// CDF of a density on [lo, hi] tabulated by Simpson's rule on 20000 sub-intervals
std::function<double(double)> tabulated_cdf(double lo, double hi,
                                            const std::function<double(double)> &density)
{
  const int n = 20000;
  const double h = (hi - lo) / n;
  std::vector<double> cum(n + 1, 0.0);
  for (int k = 0; k < n; k++) {
    const double x = lo + k * h;
    cum[k + 1] = cum[k] + h / 6.0 * (density(x) + 4.0 * density(x + 0.5 * h) + density(x + h));
  }
  for (double &c : cum) c /= cum[n];
  return [=](double x) {
    if (x <= lo) return 0.0;
    if (x >= hi) return 1.0;
    const double t = (x - lo) / h;
    const int k = std::min(n - 1, static_cast<int>(t));
    return cum[k] + (t - k) * (cum[k + 1] - cum[k]);
  };
}

double volume_density(const PourDistribution &d, double r)
{
  return std::pow(r - d.rmin, d.alpha - 1.0) * std::pow(d.rmax - r, d.beta - 1.0);
}

// the paper's distribution: mean size 0.5, delta_r 0.6, alpha = beta = 3, eta 1.4, zeta 1.8
PourDistribution paper_distribution()
{
  PourDistribution d;
  d.rmin = 0.5 * (1.0 - 0.6);
  d.rmax = 0.5 * (1.0 + 0.6);
  d.alpha = d.beta = 3.0;
  d.eta = 1.4;
  d.zeta = 1.8;
  return d;
}

std::vector<double> draw_sizes(PourSampler &sampler, int n)
{
  std::vector<double> r(n);
  for (double &x : r) x = sampler.size();
  return r;
}

// unit quaternion (w, x, y, z) -> rotation matrix, columns = body axes in the box frame
std::array<std::array<double, 3>, 3> rotation(const double *q)
{
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

// rotation angle in [0, pi] of a unit quaternion
double rotation_angle(const double *q)
{
  return 2.0 * std::acos(std::min(1.0, std::fabs(q[0])));
}

// CDF of the rotation angle of a Haar-uniform rotation: density (1 - cos t) / pi
double haar_angle_cdf(double t)
{
  return (t - std::sin(t)) / kPi;
}

// a scripted source: returns the listed deviates in order and counts the calls
struct ScriptedUniform {
  std::vector<double> values;
  int calls = 0;
  UniformSource source()
  {
    return [this] {
      return values.at(calls++);
    };
  }
};

}    // namespace

// ---- Beta deviates: analytic CDFs, including the shape < 1 branch of the gamma deviate ----

TEST(BetaDeviate, MatchesAnalyticCdfs)
{
  struct Case {
    double a, b;
    std::function<double(double)> cdf;
  };
  const std::vector<Case> cases = {
      {3.0, 3.0,
       [](double x) {
         return x * x * x * (10.0 - 15.0 * x + 6.0 * x * x);
       }},
      {2.0, 5.0,
       [](double x) {
         return 1.0 - std::pow(1.0 - x, 6) - 6.0 * x * std::pow(1.0 - x, 5);
       }},
      {0.5, 0.5,
       [](double x) {
         return 2.0 / kPi * std::asin(std::sqrt(x));
       }},
  };
  UniformSource uniform = seeded_uniform(11);
  for (const Case &c : cases) {
    std::vector<double> x(kSamples);
    for (double &v : x) v = beta_deviate(c.a, c.b, uniform);
    EXPECT_LT(ks_statistic(x, c.cdf), kAccept) << "Beta(" << c.a << ", " << c.b << ")";
    // power: Beta(3, 3) is rejected against the uniform distribution's CDF
    if (c.a == 3.0) {
      EXPECT_GT(ks_statistic(x,
                             [](double v) {
                               return v;
                             }),
                kReject);
    }
  }
}

// ---- sizes: n(r) ~ V(r) / r^3, and V(r) for the volume-weighted sample ----

TEST(PourSampler, SizesFollowTheNumberDistribution)
{
  PourDistribution wide = paper_distribution();
  PourDistribution skewed = paper_distribution();
  skewed.rmin = 0.4;
  skewed.rmax = 0.6;
  skewed.alpha = 2.0;
  skewed.beta = 5.0;
  int seed = 21;
  for (const PourDistribution &d : {wide, skewed}) {
    PourSampler sampler(d, seeded_uniform(seed++));
    const std::vector<double> r = draw_sizes(sampler, kSamples);
    for (double x : r) ASSERT_TRUE(x >= d.rmin && x <= d.rmax) << x;

    const auto number_cdf = tabulated_cdf(d.rmin, d.rmax, [&](double x) {
      return volume_density(d, x) / (x * x * x);
    });
    const auto volume_cdf = tabulated_cdf(d.rmin, d.rmax, [&](double x) {
      return volume_density(d, x);
    });
    EXPECT_LT(ks_statistic(r, number_cdf), kAccept) << "rmin " << d.rmin;
    // power: the unweighted sample is not distributed as V(r)
    EXPECT_GT(ks_statistic(r, volume_cdf), kReject) << "rmin " << d.rmin;

    // the volume of the particles of size r: weights r^3 turn the sample into V(r)
    std::vector<double> w(r.size());
    for (std::size_t i = 0; i < r.size(); i++) w[i] = r[i] * r[i] * r[i];
    EXPECT_LT(weighted_ks_statistic(r, w, volume_cdf), kAccept) << "rmin " << d.rmin;
    EXPECT_GT(weighted_ks_statistic(r, w, number_cdf), kReject) << "rmin " << d.rmin;
  }
}

TEST(PourSampler, MonoSizedDrawsNoNumber)
{
  PourDistribution d = paper_distribution();
  d.rmin = d.rmax = 0.3;
  ScriptedUniform script;
  PourSampler sampler(d, script.source());
  EXPECT_EQ(sampler.size(), 0.3);
  EXPECT_EQ(script.calls, 0);
  EXPECT_EQ(sampler.acceptance(), 1.0);
  EXPECT_DOUBLE_EQ(sampler.mean_volume(), 4.0 / 3.0 * kPi * 0.027);
}

// ---- statistics: acceptance and mean volume by independent quadrature and by the sample ----

TEST(PourSampler, StatisticsMatchQuadratureAndSample)
{
  const PourDistribution d = paper_distribution();
  PourSampler sampler(d, seeded_uniform(31));
  // plain Simpson on [rmin, rmax] (the integrands are smooth for alpha = beta = 3)
  auto integral = [&](const std::function<double(double)> &f) {
    const int n = 20000;
    const double h = (d.rmax - d.rmin) / n;
    double sum = f(d.rmin) + f(d.rmax);
    for (int k = 1; k < n; k++) sum += (k % 2 ? 4.0 : 2.0) * f(d.rmin + k * h);
    return sum * h / 3.0;
  };
  const double v_norm = integral([&](double r) {
    return volume_density(d, r);
  });
  const double v_inverse_cube = integral([&](double r) {
    return volume_density(d, r) / (r * r * r);
  });
  const double acceptance = d.rmin * d.rmin * d.rmin * v_inverse_cube / v_norm;
  const double mean_volume = 4.0 / 3.0 * kPi * v_norm / v_inverse_cube;
  EXPECT_NEAR(sampler.acceptance(), acceptance, 1e-12 * acceptance);
  EXPECT_NEAR(sampler.mean_volume(), mean_volume, 1e-12 * mean_volume);

  // the sample mean of 4/3 pi r^3 agrees within 4 standard errors
  const std::vector<double> r = draw_sizes(sampler, kSamples);
  double sum = 0.0, sum2 = 0.0;
  for (double x : r) {
    const double v = 4.0 / 3.0 * kPi * x * x * x;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / kSamples;
  const double error = std::sqrt((sum2 / kSamples - mean * mean) / kSamples);
  EXPECT_NEAR(mean, sampler.mean_volume(), 4.0 * error);
  // the mean-size sphere overestimates the mean volume: the sample must show it
  EXPECT_LT(mean + 4.0 * error, 4.0 / 3.0 * kPi * 0.125);
}

TEST(PourSampler, StatisticsOfSingularVolumeDistributions)
{
  // alpha = beta = 1/2: V(r) is infinite at both ends. With x = sin^2(theta) the Beta(1/2,
  // 1/2) density becomes the uniform 2/pi on [0, pi/2], a smooth integral for Simpson.
  PourDistribution d = paper_distribution();
  d.alpha = d.beta = 0.5;
  const PourSampler sampler(d, seeded_uniform(32));
  const int n = 20000;
  const double h = 0.5 * kPi / n;
  double inverse_cube = 0.0;
  for (int k = 0; k <= n; k++) {
    const double s = std::sin(k * h);
    const double r = d.rmin + (d.rmax - d.rmin) * s * s;
    const double weight = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    inverse_cube += weight / (r * r * r);
  }
  inverse_cube *= h / 3.0 * 2.0 / kPi;
  EXPECT_NEAR(sampler.acceptance(), d.rmin * d.rmin * d.rmin * inverse_cube, 1e-12);
  EXPECT_NEAR(sampler.mean_volume(), 4.0 / 3.0 * kPi / inverse_cube, 1e-12);
}

// ---- shapes: exact ratios and volume; uniform shape polydispersity; the bounds ----

TEST(PourSampler, MonoShapedAxesHaveExactRatiosAndVolume)
{
  const PourDistribution d = paper_distribution();
  ScriptedUniform script;
  PourSampler sampler(d, script.source());
  for (double r : {0.2, 0.37, 0.8}) {
    const Eigen::Vector3d s = sampler.semi_axes(r);
    EXPECT_NEAR(s[0] / s[1], d.eta, 1e-14);
    EXPECT_NEAR(s[1] / s[2], d.zeta, 1e-14);
    EXPECT_NEAR(std::cbrt(s[0] * s[1] * s[2]), r, 1e-15);
  }
  EXPECT_EQ(script.calls, 0);    // mono-shaped: no deviate drawn
  EXPECT_NEAR(sampler.largest_semi_axis(), 0.8 * std::cbrt(1.4 * 1.4 * 1.8), 1e-15);
  EXPECT_NEAR(sampler.smallest_semi_axis(), 0.2 / std::cbrt(1.4 * 1.8 * 1.8), 1e-15);
}

TEST(PourSampler, ShapePolydispersityIsUniformAndBounded)
{
  PourDistribution d = paper_distribution();
  d.delta_eta = 0.2;
  d.delta_zeta = 0.1;
  PourSampler sampler(d, seeded_uniform(41));
  std::vector<double> eta(kSamples), zeta(kSamples);
  for (int k = 0; k < kSamples; k++) {
    const double r = sampler.size();
    const Eigen::Vector3d s = sampler.semi_axes(r);
    ASSERT_TRUE(s[0] >= s[1] && s[1] >= s[2]);
    ASSERT_LE(s[0], sampler.largest_semi_axis() * (1 + 1e-15));
    ASSERT_GE(s[2], sampler.smallest_semi_axis() * (1 - 1e-15));
    ASSERT_LE(s[0] * s[1] / s[2], sampler.flattest_radius() * (1 + 1e-15));
    EXPECT_NEAR(std::cbrt(s[0] * s[1] * s[2]), r, 1e-15);
    eta[k] = s[0] / s[1];
    zeta[k] = s[1] / s[2];
  }
  auto uniform_cdf = [](double lo, double hi) {
    return [=](double x) {
      return std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
    };
  };
  EXPECT_LT(ks_statistic(eta, uniform_cdf(1.4 * 0.8, 1.4 * 1.2)), kAccept);
  EXPECT_LT(ks_statistic(zeta, uniform_cdf(1.8 * 0.9, 1.8 * 1.1)), kAccept);
  // power: a range 10 % too narrow is rejected
  EXPECT_GT(ks_statistic(eta, uniform_cdf(1.4 * 0.82, 1.4 * 1.18)), kReject);

  // the bounds are attained at the extreme deviates
  ScriptedUniform top{{1.0, 1.0, 1.0, 1.0}};
  PourSampler extreme(d, top.source());
  EXPECT_NEAR(extreme.semi_axes(d.rmax)[0], extreme.largest_semi_axis(), 1e-15);
  EXPECT_NEAR(extreme.semi_axes(d.rmin)[2], extreme.smallest_semi_axis(), 1e-15);
  EXPECT_EQ(top.calls, 4);    // one deviate per polydisperse factor
  ScriptedUniform flattest{{1.0, 1.0}};
  const Eigen::Vector3d flat = PourSampler(d, flattest.source()).semi_axes(d.rmax);
  EXPECT_NEAR(flat[0] * flat[1] / flat[2], extreme.flattest_radius(), 1e-14);
}

// ---- orientations: Haar-uniform on SO(3) ----

TEST(PourSampler, OrientationsAreUniformOnSO3)
{
  PourSampler sampler(paper_distribution(), seeded_uniform(51));
  std::vector<std::array<double, 4>> quats(kSamples);
  for (auto &q : quats) {
    sampler.orientation(q.data());
    ASSERT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-15);
  }

  // rotation angle: density (1 - cos t) / pi on [0, pi]; also after a fixed left rotation
  // (Haar measure is invariant), which a merely conjugation-invariant law would fail
  const double q0[4] = {std::cos(0.6), std::sin(0.6) * 0.6, std::sin(0.6) * 0.0,
                        std::sin(0.6) * 0.8};
  std::vector<double> angle(kSamples), shifted(kSamples);
  for (int k = 0; k < kSamples; k++) {
    const double *q = quats[k].data();
    angle[k] = rotation_angle(q);
    const double p[4] = {q0[0] * q[0] - q0[1] * q[1] - q0[2] * q[2] - q0[3] * q[3],
                         q0[0] * q[1] + q0[1] * q[0] + q0[2] * q[3] - q0[3] * q[2],
                         q0[0] * q[2] - q0[1] * q[3] + q0[2] * q[0] + q0[3] * q[1],
                         q0[0] * q[3] + q0[1] * q[2] - q0[2] * q[1] + q0[3] * q[0]};
    shifted[k] = rotation_angle(p);
  }
  EXPECT_LT(ks_statistic(angle, haar_angle_cdf), kAccept);
  EXPECT_LT(ks_statistic(shifted, haar_angle_cdf), kAccept);

  // each body axis is uniform on the sphere: z component uniform on [-1, 1], azimuth on
  // [0, 2 pi)
  for (int axis = 0; axis < 3; axis++) {
    std::vector<double> cz(kSamples), phi(kSamples);
    for (int k = 0; k < kSamples; k++) {
      const auto r = rotation(quats[k].data());
      cz[k] = r[2][axis];
      phi[k] = std::atan2(r[1][axis], r[0][axis]) + kPi;
    }
    EXPECT_LT(ks_statistic(cz,
                           [](double x) {
                             return 0.5 * (x + 1.0);
                           }),
              kAccept)
        << axis;
    EXPECT_LT(ks_statistic(phi,
                           [](double x) {
                             return x / (2.0 * kPi);
                           }),
              kAccept)
        << axis;
  }
}

TEST(PourSampler, OrientationTestRejectsUniformAngleAboutUniformAxis)
{
  // a common wrong recipe: a uniform axis and a uniform rotation angle on [0, pi] (the
  // angle's law does not depend on the axis, so one axis stands for all)
  UniformSource uniform = seeded_uniform(61);
  std::vector<double> angle(kSamples);
  for (double &t : angle) {
    t = kPi * uniform();
    const double q[4] = {std::cos(0.5 * t), std::sin(0.5 * t), 0.0, 0.0};
    t = rotation_angle(q);
  }
  EXPECT_GT(ks_statistic(angle, haar_angle_cdf), kReject);
}

// ---- the order of the deviates, which the fix's restarts rely on ----

TEST(PourSampler, OrientationIsShoemakesMapOfThreeDeviates)
{
  ScriptedUniform script{{0.25, 0.125, 0.5}};
  PourSampler sampler(paper_distribution(), script.source());
  double q[4];
  sampler.orientation(q);
  EXPECT_EQ(script.calls, 3);
  const double s1 = std::sqrt(0.75), s2 = 0.5;
  EXPECT_NEAR(q[0], s2 * std::cos(kPi), 1e-15);
  EXPECT_NEAR(q[1], s1 * std::sin(0.25 * kPi), 1e-15);
  EXPECT_NEAR(q[2], s1 * std::cos(0.25 * kPi), 1e-15);
  EXPECT_NEAR(q[3], s2 * std::sin(kPi), 1e-15);
}
