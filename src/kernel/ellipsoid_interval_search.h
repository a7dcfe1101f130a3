/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: the global minimum of a smooth function of one parameter on an
   interval (periodic, or closed with its ends), the walls' one-parameter searches over a
   circle or an arc of directions (a cone's side, a block's edge, a cylinder's side).

   The function is sampled; the best discrete minima are refined by golden-section search
   within a sample spacing either side (to ~1e-7 of it) and finished by Newton's method on
   f' = 0 (the caller's analytic f', f''). On a closed interval a minimum at an end is one
   (f' pointing out of the interval there). A Newton iteration that does not settle is
   reported (converged = false), never dropped; where it went uphill (a kink of f) the
   golden section's point is kept.

   F has  double value(double x) const  and  void derivatives(double x, double &df,
   double &ddf) const.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_INTERVAL_SEARCH_H
#define ELLIPSOID_DEP_ELLIPSOID_INTERVAL_SEARCH_H

#include <algorithm>
#include <cmath>
#include <vector>

namespace EllipsoidDep {

struct IntervalMinimum {
  double x = 0.0, value = HUGE_VAL;
  bool converged = false;
};

// The best `refined` discrete minima of the samples, each refined, in the samples' order of
// value (best first before refinement)
template <class F>
std::vector<IntervalMinimum> local_minima_on_interval(const F &f, double lo, double hi,
                                                      bool periodic, int samples, int refined)
{
  constexpr int GOLDEN_STEPS = 30;
  constexpr int NEWTON_STEPS = 20;
  const double spacing = (hi - lo) / (periodic ? samples : samples - 1);
  std::vector<double> values(samples);
  for (int j = 0; j < samples; j++) values[j] = f.value(lo + j * spacing);
  // discrete minima, best first
  std::vector<int> dips;
  for (int j = 0; j < samples; j++) {
    const bool has_left = periodic || j > 0, has_right = periodic || j < samples - 1;
    if (has_left && values[j] > values[(j + samples - 1) % samples]) continue;
    if (has_right && values[j] > values[(j + 1) % samples]) continue;
    dips.push_back(j);
  }
  std::sort(dips.begin(), dips.end(), [&](int a, int b) {
    return values[a] < values[b];
  });

  auto clamp = [&](double x) {
    return periodic ? x : std::min(hi, std::max(lo, x));
  };
  std::vector<IntervalMinimum> found;
  for (std::size_t k = 0; k < std::min<std::size_t>(refined, dips.size()); k++) {
    const double centre = lo + dips[k] * spacing;
    double a = clamp(centre - spacing), b = clamp(centre + spacing);
    const bool from_lo = !periodic && a == lo, from_hi = !periodic && b == hi;
    const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = b - ratio * (b - a), x2 = a + ratio * (b - a);
    double f1 = f.value(x1), f2 = f.value(x2);
    for (int it = 0; it < GOLDEN_STEPS; it++) {
      if (f1 < f2) {
        b = x2, x2 = x1, f2 = f1;
        x1 = b - ratio * (b - a), f1 = f.value(x1);
      } else {
        a = x1, x1 = x2, f1 = f2;
        x2 = a + ratio * (b - a), f2 = f.value(x2);
      }
    }
    // a bracket that never left an end of the interval: the minimum may lie on it
    double x = from_lo && a == lo ? lo : from_hi && b == hi ? hi : 0.5 * (a + b);
    const double bracketed = x;
    bool converged = false;
    for (int it = 0; it < NEWTON_STEPS && !converged; it++) {
      double df, ddf;
      f.derivatives(x, df, ddf);
      if (!periodic && ((x == lo && df >= 0.0) || (x == hi && df <= 0.0))) {
        converged = true;    // a minimum at an end
        break;
      }
      if (!(ddf > 0.0)) break;    // not at a minimum: the iteration is not trusted
      const double next = clamp(x - df / ddf);
      converged = std::fabs(next - x) <= 1e-12;
      x = next;
    }
    double value = f.value(x);
    // an iteration that did not settle and went uphill (a kink): the bracket's point
    if (!converged && value > f.value(bracketed)) x = bracketed, value = f.value(x);
    found.push_back({x, value, converged});
  }
  return found;
}

template <class F>
IntervalMinimum minimise_on_interval(const F &f, double lo, double hi, bool periodic, int samples,
                                     int refined = 2)
{
  IntervalMinimum best;
  for (const IntervalMinimum &m : local_minima_on_interval(f, lo, hi, periodic, samples, refined))
    if (m.value < best.value) best = m;
  return best;
}

}    // namespace EllipsoidDep

#endif
