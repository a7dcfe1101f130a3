/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: farthest and nearest surface points (see ellipsoid_point_extremum.h)
------------------------------------------------------------------------- */

#include "ellipsoid_point_extremum.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace EllipsoidDep {

namespace {

  constexpr int MAX_ITERATIONS = 200;

  // the root of F(t) = 1 in [lo, hi], F monotone there (increasing when rising); Newton's
  // steps on 1/sqrt(F) - 1, nearly linear in t where one term dominates (close to a pole).
  // With an origin, t is counted from it (A_k + t = (A_k + origin) + t): near a pole taken as
  // the origin A_k + t keeps its digits
  template <int N>
  double secular_root(const Eigen::Matrix<double, N, 1> &a2, const Eigen::Matrix<double, N, 1> &x,
                      double lo, double hi, bool rising, bool &converged, double origin = 0.0)
  {
    double t = 0.5 * (lo + hi);
    converged = false;
    for (int it = 0; it < MAX_ITERATIONS; it++) {
      double big_f = 0.0, dbig_f = 0.0;
      for (int k = 0; k < N; k++) {
        const double q = 1.0 / ((a2[k] + origin) + t);
        const double term = a2[k] * x[k] * x[k] * q * q;
        big_f += term;
        dbig_f -= 2.0 * term * q;
      }
      const double f = big_f - 1.0;
      // shrink the bracket on the side the sign of F - 1 rules out
      if ((f < 0.0) == rising)
        lo = t;
      else
        hi = t;
      if (f == 0.0 || hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * std::fabs(t)) {
        converged = true;
        return t;
      }
      const double g = 1.0 / std::sqrt(big_f) - 1.0;
      const double dg = -0.5 * dbig_f / (big_f * std::sqrt(big_f));
      double next = dg != 0.0 && std::isfinite(dg) ? t - g / dg : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (next == t) {
        converged = true;
        return t;
      }
      t = next;
    }
    return t;
  }

  template <int N>
  SurfaceExtremum<N> point_at(const Eigen::Matrix<double, N, 1> &a2,
                              const Eigen::Matrix<double, N, 1> &x, double t, bool converged,
                              double origin = 0.0)
  {
    SurfaceExtremum<N> r;
    for (int k = 0; k < N; k++) r.point[k] = a2[k] * x[k] / ((a2[k] + origin) + t);
    r.distance = (r.point - x).norm();
    r.converged = converged;
    return r;
  }

}    // namespace

template <int N>
SurfaceExtremum<N> farthest_surface_point(const Eigen::Matrix<double, N, 1> &a2,
                                          const Eigen::Matrix<double, N, 1> &x)
{
  int largest = 0;
  for (int k = 1; k < N; k++)
    if (a2[k] > a2[largest]) largest = k;
  const double amax2 = a2[largest];
  // hard case: no component along any largest axis, and F stays below 1 up to -A_max
  bool hard = true;
  double f_hard = 0.0;
  for (int k = 0; k < N; k++) {
    if (a2[k] == amax2) {
      if (x[k] != 0.0) hard = false;
    } else {
      const double q = a2[k] - amax2;
      f_hard += a2[k] * x[k] * x[k] / (q * q);
    }
  }
  if (hard && f_hard <= 1.0) {
    SurfaceExtremum<N> r;
    for (int k = 0; k < N; k++)
      r.point[k] = a2[k] == amax2 ? 0.0 : a2[k] * x[k] / (a2[k] - amax2);
    r.point[largest] = std::sqrt(amax2 * (1.0 - f_hard));
    r.distance = (r.point - x).norm();
    return r;
  }
  // t counted from the pole -A_max it lies next to (x nearly without a component along the
  // largest axis: A_max + t small)
  bool converged = false;
  const double t = secular_root<N>(a2, x, -std::sqrt(amax2) * x.norm(), 0.0, true, converged,
                                   -amax2);
  return point_at<N>(a2, x, t, converged, -amax2);
}

template <int N>
SurfaceExtremum<N> nearest_surface_point(const Eigen::Matrix<double, N, 1> &a2,
                                         const Eigen::Matrix<double, N, 1> &x)
{
  bool converged = false;
  if (x.cwiseProduct(x).cwiseQuotient(a2).sum() > 1.0) {
    const double t = secular_root<N>(a2, x, 0.0, std::sqrt(a2.maxCoeff()) * x.norm(), false,
                                     converged);
    return point_at<N>(a2, x, t, converged);
  }
  // inside: the root in (-A_min, 0]; hard case: no component along any smallest axis, and F
  // stays below 1 down to -A_min (x on the medial plane: two nearest points, one is taken)
  int smallest = 0;
  for (int k = 1; k < N; k++)
    if (a2[k] < a2[smallest]) smallest = k;
  const double amin2 = a2[smallest];
  bool hard = true;
  double f_hard = 0.0;
  for (int k = 0; k < N; k++) {
    if (a2[k] == amin2) {
      if (x[k] != 0.0) hard = false;
    } else {
      const double q = a2[k] - amin2;
      f_hard += a2[k] * x[k] * x[k] / (q * q);
    }
  }
  if (hard && f_hard <= 1.0) {
    SurfaceExtremum<N> r;
    for (int k = 0; k < N; k++)
      r.point[k] = a2[k] == amin2 ? 0.0 : a2[k] * x[k] / (a2[k] - amin2);
    r.point[smallest] = std::sqrt(amin2 * (1.0 - f_hard));
    r.distance = (r.point - x).norm();
    return r;
  }
  const double t = secular_root<N>(a2, x, 0.0, amin2, false, converged, -amin2);
  return point_at<N>(a2, x, t, converged, -amin2);
}

namespace {

  // F(t) = sum A_k x_k^2 / (A_k + t)^2 and F'(t)
  template <int N>
  double secular(const Eigen::Matrix<double, N, 1> &a2, const Eigen::Matrix<double, N, 1> &x,
                 double t, double &slope, double &curvature)
  {
    double big_f = 0.0;
    slope = curvature = 0.0;
    for (int k = 0; k < N; k++) {
      if (x[k] == 0.0) continue;
      const double q = 1.0 / (a2[k] + t), term = a2[k] * x[k] * x[k] * q * q;
      big_f += term;
      slope -= 2.0 * term * q;
      curvature += 6.0 * term * q * q;
    }
    return big_f;
  }

  // whether the stationary point y (multiplier t, shifted: A_k + t) is a local maximum of
  // |y - x| on the surface: the Lagrangian's Hessian diag(1 + t / A_k) negative on the
  // tangent plane
  template <int N>
  bool local_maximum(const Eigen::Matrix<double, N, 1> &a2, const Eigen::Matrix<double, N, 1> &y,
                     const Eigen::Matrix<double, N, 1> &shifted)
  {
    const Eigen::Matrix<double, N, 1> g = y.cwiseQuotient(a2).normalized();
    const Eigen::Matrix<double, N, 1> h = shifted.cwiseQuotient(a2);
    const Eigen::Matrix<double, N, 1> u = g.unitOrthogonal();
    const double uu = u.dot(h.cwiseProduct(u));
    if constexpr (N == 2) {
      return uu < 0.0;
    } else {
      const Eigen::Matrix<double, N, 1> v = g.cross(u);
      const double vv = v.dot(h.cwiseProduct(v)), uv = u.dot(h.cwiseProduct(v));
      return uu + vv < 0.0 && uu * vv - uv * uv > 0.0;
    }
  }

}    // namespace

template <int N>
std::vector<StationaryPoint<N>> stationary_surface_points(const Eigen::Matrix<double, N, 1> &a2,
                                                          const Eigen::Matrix<double, N, 1> &x)
{
  using VecN = Eigen::Matrix<double, N, 1>;
  std::vector<StationaryPoint<N>> found;
  // t counted from origin
  auto add = [&](const VecN &y, double origin, double t, bool converged) {
    const VecN shifted = (a2 + VecN::Constant(origin)) + VecN::Constant(t);
    found.push_back({y, (y - x).norm(), local_maximum<N>(a2, y, shifted), converged});
  };
  // the poles -A_k of the terms present, ascending and distinct
  std::vector<double> poles;
  double sum = 0.0;
  for (int k = 0; k < N; k++)
    if (x[k] != 0.0) poles.push_back(-a2[k]), sum += a2[k] * x[k] * x[k];
  std::sort(poles.begin(), poles.end());
  poles.erase(std::unique(poles.begin(), poles.end()), poles.end());
  // a root between lo and hi, both counted from the nearer pole `origin`
  auto root = [&](double lo, double hi, bool rising, double origin) {
    if (!(hi > lo)) return;    // within round-off of the pole: unresolved
    bool converged = false;
    const double t = secular_root<N>(a2, x, lo, hi, rising, converged, origin);
    const SurfaceExtremum<N> r = point_at<N>(a2, x, t, converged, origin);
    add(r.point, origin, t, converged);
  };
  if (!poles.empty()) {
    const double reach = std::sqrt(sum);    // F <= 1 that far beyond the outer poles
    root(-reach, 0.0, true, poles.front());
    root(0.0, reach, false, poles.back());
    // between two poles F is convex: at its lowest point below 1, a root either side (the
    // lowest point by Newton's method on F' inside a shrinking bracket)
    for (std::size_t j = 0; j + 1 < poles.size(); j++) {
      double lo = poles[j], hi = poles[j + 1], slope = 0.0, curvature = 0.0;
      double t = 0.5 * (lo + hi);
      for (int it = 0; it < 200; it++) {
        secular<N>(a2, x, t, slope, curvature);
        (slope < 0.0 ? lo : hi) = t;
        double next = t - slope / curvature;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (next == t || hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * std::fabs(t))
          break;
        t = next;
      }
      const double lowest = t;
      if (!(secular<N>(a2, x, lowest, slope, curvature) < 1.0)) continue;
      root(0.0, lowest - poles[j], false, poles[j]);
      root(lowest - poles[j + 1], 0.0, true, poles[j + 1]);
    }
  }
  // the hard cases: t = -A for a squared semi-axis A along which x has no component (its
  // pole absent), the free components on the circle or pair of points that closes the surface
  for (int k = 0; k < N; k++) {
    bool first = true, absent = true;
    for (int j = 0; j < N; j++)
      if (a2[j] == a2[k]) {
        first = first && j >= k;
        absent = absent && x[j] == 0.0;
      }
    if (!first || !absent) continue;
    VecN y = VecN::Zero();
    double rest = 1.0;
    for (int j = 0; j < N; j++)
      if (a2[j] != a2[k]) {
        y[j] = a2[j] * x[j] / (a2[j] - a2[k]);
        rest -= y[j] * y[j] / a2[j];
      }
    if (!(rest > 0.0)) continue;
    // one point of each: both signs along the first such axis (a circle: its value is one)
    y[k] = std::sqrt(a2[k] * rest);
    add(y, -a2[k], 0.0, true);
    y[k] = -y[k];
    add(y, -a2[k], 0.0, true);
  }
  return found;
}

template std::vector<StationaryPoint<2>> stationary_surface_points<2>(const Eigen::Vector2d &,
                                                                      const Eigen::Vector2d &);
template std::vector<StationaryPoint<3>> stationary_surface_points<3>(const Eigen::Vector3d &,
                                                                      const Eigen::Vector3d &);

template SurfaceExtremum<2> farthest_surface_point<2>(const Eigen::Vector2d &,
                                                      const Eigen::Vector2d &);
template SurfaceExtremum<3> farthest_surface_point<3>(const Eigen::Vector3d &,
                                                      const Eigen::Vector3d &);
template SurfaceExtremum<2> nearest_surface_point<2>(const Eigen::Vector2d &,
                                                     const Eigen::Vector2d &);
template SurfaceExtremum<3> nearest_surface_point<3>(const Eigen::Vector3d &,
                                                     const Eigen::Vector3d &);

}    // namespace EllipsoidDep
