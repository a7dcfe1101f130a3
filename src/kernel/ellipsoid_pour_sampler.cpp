/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: the random particles of a pour (see ellipsoid_pour_sampler.h)

   The size is sampled exactly by rejection: x ~ Beta(alpha, beta), r = rmin + x (rmax - rmin)
   has density V(r); accepting it with probability (rmin / r)^3 <= 1 leaves n(r) ~ V(r) / r^3.
   The expected acceptance is rmin^3 <r^-3>_V, and the mean particle volume under n(r) is
   4/3 pi / <r^-3>_V: both are integrals over the Beta density, done once here.
------------------------------------------------------------------------- */

#include "ellipsoid_pour_sampler.h"

#include "ellipsoid_shape.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace EllipsoidDep {

namespace {

  constexpr double TWO_PI = 2.0 * PI;
  constexpr double FOUR_PI_3 = 4.18879020478639098462;
  constexpr double MONO_SIZED = 1.0e-12;    // relative width of a size range taken as one size

  // log(1 + e^x) without overflow
  double softplus(double x)
  {
    return x > 0.0 ? x + std::log1p(std::exp(-x)) : std::log1p(std::exp(x));
  }

  // integral over [0, 1] of x^(a-1) (1-x)^(b-1) w(x), a, b > 0, by the tanh-sinh rule
  // x = (1 + tanh(pi/2 sinh t)) / 2: the end-point singularities of any power decay double
  // exponentially in t. x^a (1-x)^b and dx/dt = pi cosh t x (1-x) are combined in logarithms
  // (log x = -softplus(-2s)), so no end point under- or overflows.
  template <class F> double beta_weighted_integral(double a, double b, F w)
  {
    const double h = 1.0 / 64.0;
    auto term = [&](double t) {
      const double s = 0.5 * PI * std::sinh(t);
      const double log_x = -softplus(-2.0 * s), log_1mx = -softplus(2.0 * s);
      const double x = std::exp(log_x);
      return w(x) * std::exp(a * log_x + b * log_1mx + std::log(PI * std::cosh(t)));
    };
    double sum = term(0.0);
    for (int k = 1; k < 64 * 64; k++) {
      const double tail = term(k * h) + term(-k * h);
      sum += tail;
      if (std::fabs(tail) <= 1.0e-17 * std::fabs(sum) && k * h > 1.0) break;
    }
    return sum * h;
  }

  // standard normal deviate (Box-Muller, one of the pair)
  double normal_deviate(const UniformSource &uniform)
  {
    const double u1 = uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(TWO_PI * u2);
  }

  // Gamma(a, 1): Marsaglia & Tsang (2000); shape a < 1 through Gamma(a + 1) U^(1/a)
  double gamma_deviate(double a, const UniformSource &uniform)
  {
    if (a < 1.0) {
      const double g = gamma_deviate(a + 1.0, uniform);
      return g * std::pow(uniform(), 1.0 / a);
    }
    const double d = a - 1.0 / 3.0, c = 1.0 / std::sqrt(9.0 * d);
    while (true) {
      double x, v;
      do {
        x = normal_deviate(uniform);
        v = 1.0 + c * x;
      } while (v <= 0.0);
      v = v * v * v;
      const double u = uniform();
      if (u < 1.0 - 0.0331 * x * x * x * x) return d * v;
      if (std::log(u) < 0.5 * x * x + d * (1.0 - v + std::log(v))) return d * v;
    }
  }

}    // namespace

double beta_deviate(double a, double b, const UniformSource &uniform)
{
  const double x = gamma_deviate(a, uniform), y = gamma_deviate(b, uniform);
  const double s = x + y;
  return s > 0.0 ? x / s : 0.5;
}

PourSampler::PourSampler(const PourDistribution &distribution, UniformSource source) :
    dist(distribution), uniform(std::move(source))
{
  if (dist.rmax - dist.rmin <= MONO_SIZED * dist.rmax) {
    dist.rmax = dist.rmin;
    accepted = 1.0;
    volume_mean = FOUR_PI_3 * dist.rmin * dist.rmin * dist.rmin;
    return;
  }
  const double rmin = dist.rmin, span = dist.rmax - dist.rmin;
  const double norm = beta_weighted_integral(dist.alpha, dist.beta, [](double) {
    return 1.0;
  });
  const double inverse_cube = beta_weighted_integral(dist.alpha, dist.beta,
                                                     [&](double x) {
                                                       const double r = rmin + span * x;
                                                       return 1.0 / (r * r * r);
                                                     }) /
      norm;
  accepted = rmin * rmin * rmin * inverse_cube;
  volume_mean = FOUR_PI_3 / inverse_cube;
}

double PourSampler::size()
{
  if (dist.rmax == dist.rmin) return dist.rmin;
  const double span = dist.rmax - dist.rmin;
  while (true) {
    const double r = dist.rmin + span * beta_deviate(dist.alpha, dist.beta, uniform);
    const double w = dist.rmin / r;
    if (uniform() < w * w * w) return r;
  }
}

double PourSampler::shape_factor(double mean, double delta)
{
  if (delta <= 0.0) return mean;
  return mean * (1.0 - delta + 2.0 * delta * uniform());
}

Eigen::Vector3d PourSampler::semi_axes(double r)
{
  const double e = shape_factor(dist.eta, dist.delta_eta);
  const double z = shape_factor(dist.zeta, dist.delta_zeta);
  // r^3 = abc = (e z c)(z c) c = e z^2 c^3
  const double c = r / std::cbrt(e * z * z);
  const double b = z * c;
  return {e * b, b, c};
}

// Shoemake (1992): uniform unit quaternion (w, x, y, z)
void PourSampler::orientation(double quat[4])
{
  const double u1 = uniform(), u2 = uniform(), u3 = uniform();
  const double s1 = std::sqrt(1.0 - u1), s2 = std::sqrt(u1);
  quat[0] = s2 * std::cos(TWO_PI * u3);
  quat[1] = s1 * std::sin(TWO_PI * u2);
  quat[2] = s1 * std::cos(TWO_PI * u2);
  quat[3] = s2 * std::sin(TWO_PI * u3);
  const double norm =
      std::sqrt(quat[0] * quat[0] + quat[1] * quat[1] + quat[2] * quat[2] + quat[3] * quat[3]);
  for (int k = 0; k < 4; k++) quat[k] /= norm;
}

// a = r eta^(2/3) zeta^(1/3) grows with r, eta and zeta
double PourSampler::largest_semi_axis() const
{
  const double eta_max = dist.eta * (1.0 + dist.delta_eta);
  const double zeta_max = dist.zeta * (1.0 + dist.delta_zeta);
  return dist.rmax * std::cbrt(eta_max * eta_max * zeta_max);
}

// c = r (eta zeta^2)^(-1/3) shrinks as eta and zeta grow
double PourSampler::smallest_semi_axis() const
{
  const double eta_max = dist.eta * (1.0 + dist.delta_eta);
  const double zeta_max = dist.zeta * (1.0 + dist.delta_zeta);
  return dist.rmin / std::cbrt(eta_max * zeta_max * zeta_max);
}

// ab/c = r (eta zeta^2)^(2/3) grows with r, eta and zeta
double PourSampler::largest_rotational_compliance() const
{
  double largest = 0.0;
  for (double eta : {dist.eta * (1.0 - dist.delta_eta), dist.eta * (1.0 + dist.delta_eta)})
    for (double zeta : {dist.zeta * (1.0 - dist.delta_zeta), dist.zeta * (1.0 + dist.delta_zeta)})
      largest = std::max(largest, rotational_compliance(eta * zeta, zeta, 1.0));
  return largest;
}

double PourSampler::flattest_radius() const
{
  const double eta_max = dist.eta * (1.0 + dist.delta_eta);
  const double zeta_max = dist.zeta * (1.0 + dist.delta_zeta);
  const double c = dist.rmax / std::cbrt(eta_max * zeta_max * zeta_max);
  return EllipsoidDep::flattest_radius(eta_max * zeta_max * c, zeta_max * c, c);
}

}    // namespace EllipsoidDep
