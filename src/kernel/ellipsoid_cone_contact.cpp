/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: ellipsoid inside a cone (see ellipsoid_cone_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_cone_contact.h"

#include <algorithm>
#include <vector>

namespace EllipsoidDep {

namespace {

  constexpr int SAMPLES = 64;
  constexpr int GOLDEN_STEPS = 30;
  constexpr int NEWTON_STEPS = 20;

  // f(phi) = h(w) + w.d over the circle of directions w(phi) = cos e1 + sin e2 - slope u
  struct ConeObjective {
    const Mat3 &m;
    Vec3 e1, e2, u, d;
    double slope;

    Vec3 w(double phi) const { return std::cos(phi) * e1 + std::sin(phi) * e2 - slope * u; }
    double value(double phi) const
    {
      const Vec3 v = w(phi);
      return support(m, v) + v.dot(d);
    }
    // f' and f''
    void derivatives(double phi, double &df, double &ddf) const
    {
      const Vec3 v = w(phi);
      const Vec3 dv = -std::sin(phi) * e1 + std::cos(phi) * e2;
      const Vec3 ddv = -(v + slope * u);
      const Vec3 mv = m * v;
      const double h = std::sqrt(v.dot(mv));
      const double a = mv.dot(dv);
      df = a / h + dv.dot(d);
      ddf = (dv.dot(m * dv) + mv.dot(ddv)) / h - a * a / (h * h * h) + ddv.dot(d);
    }
  };

  struct Maximum {
    double phi, value;
    bool converged;
  };

  Maximum refine(const ConeObjective &f, double lo, double hi)
  {
    // golden section down to ~1e-7 of the sample spacing, then Newton on f' = 0
    const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
    double f1 = f.value(x1), f2 = f.value(x2);
    for (int it = 0; it < GOLDEN_STEPS; it++) {
      if (f1 > f2) {
        hi = x2, x2 = x1, f2 = f1;
        x1 = hi - ratio * (hi - lo), f1 = f.value(x1);
      } else {
        lo = x1, x1 = x2, f1 = f2;
        x2 = lo + ratio * (hi - lo), f2 = f.value(x2);
      }
    }
    double phi = 0.5 * (lo + hi);
    bool converged = false;
    for (int it = 0; it < NEWTON_STEPS && !converged; it++) {
      double df, ddf;
      f.derivatives(phi, df, ddf);
      if (!(ddf < 0.0)) break;    // not at a maximum: the iteration is not trusted
      const double step = -df / ddf;
      phi += step;
      converged = std::fabs(step) <= 1e-12;
    }
    return {phi, f.value(phi), converged};
  }

}    // namespace

ContactGeometry ellipsoid_cone_contact(const Ellipsoid &e, const Vec3 &center, const Vec3 &axis,
                                       double radius, double slope)
{
  ContactGeometry g;
  g.status = Status::Degenerate;
  if (!valid(e) || !finite3(center) || !finite3(axis) || !(axis.norm() > 0.0) ||
      !(radius > 0.0) || !std::isfinite(radius) || !std::isfinite(slope))
    return g;
  const Vec3 u = axis.normalized();
  const Vec3 e1 = u.unitOrthogonal();
  const ConeObjective f{e.inverse_form, e1, u.cross(e1), u, e.center - center, slope};

  // the discrete maxima of the samples, best first; the best two are refined
  std::vector<double> samples(SAMPLES);
  const double spacing = 2.0 * PI / SAMPLES;
  for (int j = 0; j < SAMPLES; j++) samples[j] = f.value(j * spacing);
  std::vector<int> peaks;
  for (int j = 0; j < SAMPLES; j++)
    if (samples[j] >= samples[(j + SAMPLES - 1) % SAMPLES] &&
        samples[j] >= samples[(j + 1) % SAMPLES])
      peaks.push_back(j);
  std::sort(peaks.begin(), peaks.end(), [&](int a, int b) { return samples[a] > samples[b]; });
  Maximum best{0.0, -HUGE_VAL, false};
  for (std::size_t p = 0; p < std::min<std::size_t>(2, peaks.size()); p++) {
    const double phi = peaks[p] * spacing;
    const Maximum candidate = refine(f, phi - spacing, phi + spacing);
    if (candidate.value > best.value) best = candidate;
  }

  const Vec3 w = f.w(best.phi);
  const double length = w.norm();
  const Vec3 normal = w / length;
  const Vec3 mn = e.inverse_form * normal;
  const Vec3 p = e.center + mn / std::sqrt(normal.dot(mn));    // support point along normal
  g.normal = normal;
  g.overlap = (best.value - radius) / length;
  g.point_a = p;
  g.point_b = p - g.overlap * normal;
  g.point = 0.5 * (g.point_a + g.point_b);
  const double local_radius = radius + slope * u.dot(g.point_b - center);
  g.effective_radius = wall_effective_radius(gaussian_radius(e, normal), -2.0 * local_radius);
  g.status = surface_status(best.converged, g.overlap);
  return g;
}

}    // namespace EllipsoidDep
