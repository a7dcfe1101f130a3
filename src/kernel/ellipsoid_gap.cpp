/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: minimiser of the gap function and its cold start
   (see ellipsoid_gap.h for the conventions, doc/kernel.md for the maths).
------------------------------------------------------------------------- */

#include "ellipsoid_gap.h"

namespace EllipsoidDep {

namespace {

  constexpr double kEps = std::numeric_limits<double>::epsilon();

  // Orthonormal tangent basis of a unit vector (branch-free-ish, Duff et al. 2017).
  inline void tangent_basis(const Vec3 &n, Vec3 &t1, Vec3 &t2)
  {
    const double s = std::copysign(1.0, n[2]);
    const double a = -1.0 / (s + n[2]);
    const double b = n[0] * n[1] * a;
    t1 = Vec3(1.0 + s * n[0] * n[0] * a, s * b, -s * n[0]);
    t2 = Vec3(b, s + n[1] * n[1] * a, -n[1]);
  }

  inline double min_axis(const Ellipsoid &e)
  {
    return e.semi_axes.minCoeff();
  }

  // Direction of the smallest semi-axis (fallback start when the centre line is undefined).
  inline Vec3 thin_axis(const Ellipsoid &e)
  {
    int k = 0;
    e.semi_axes.minCoeff(&k);
    return e.rotation.col(k);
  }

  // Paper eqs. (4)-(5): X = (A + l B)^-1 (A X_A + l B X_B), l = |(X - X_B)^T A (X - X_A)|.
  // Returns the point of the surface of "second" that minimises the potential of "first".
  Vec3 lagrange_point(const Ellipsoid &first, const Ellipsoid &second, int iters)
  {
    const Mat3 &qa = first.form;
    const Mat3 &qb = second.form;
    const Vec3 qaxa = qa * first.center, qbxb = qb * second.center;
    double lambda = 1.0;
    Vec3 x = 0.5 * (first.center + second.center);
    for (int k = 0; k < iters; ++k) {
      const Mat3 m = qa + lambda * qb;
      const Vec3 xn = m.llt().solve(qaxa + lambda * qbxb);
      if (!finite3(xn)) break;
      x = xn;
      const double ln = std::fabs((x - second.center).dot(qa * (x - first.center)));
      if (!(ln > 0.0) || !std::isfinite(ln)) break;
      lambda = ln;
    }
    return x;
  }

  // Backtracking along the retraction n' = normalize(n + v1 t1 + v2 t2): halves the tangent
  // step (v1, v2) until accept(d(n')) or max_halvings halvings were made. Returns false when
  // the halvings ran out (trial then holds the last point tried).
  template <class Accept>
  bool backtrack(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc, const Vec3 &n,
                 const Vec3 &t1, const Vec3 &t2, double v1, double v2, int max_halvings,
                 Accept accept, Vec3 &trial_n, GapEval &trial)
  {
    trial_n = (n + v1 * t1 + v2 * t2).normalized();
    trial = evaluate_gap(a, b, dc, trial_n);
    int k = 0;
    while (!accept(trial.d) && k < max_halvings) {
      v1 *= 0.5;
      v2 *= 0.5;
      trial_n = (n + v1 * t1 + v2 * t2).normalized();
      trial = evaluate_gap(a, b, dc, trial_n);
      ++k;
    }
    return k < max_halvings;
  }

  // d on the tangent plane at n (basis t1, t2): gradient (g1, g2), Hessian (h11, h12, h22),
  // its smallest eigenvalue lmin and scale hscale. The Hessian is T^T (H_A + H_B) T - d I with
  // H = M/h - (Mn)(Mn)^T/h^3 (exact for the degree-1 extension).
  struct TangentModel {
    Vec3 t1, t2;
    double g1, g2, h11, h22, h12, lmin, hscale;
  };

  TangentModel tangent_model(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &n,
                             const GapEval &ev, const Vec3 &gt, double gn, double size)
  {
    TangentModel m;
    tangent_basis(n, m.t1, m.t2);
    // the two bodies' M/h summed first: two matrix-vector products instead of four
    const double ia = 1.0 / ev.ha, ib = 1.0 / ev.hb;
    const Mat3 s = a.inverse_form * ia + b.inverse_form * ib;
    const Vec3 st1 = s * m.t1, st2 = s * m.t2;
    const Vec3 &ua = ev.ua, &ub = ev.ub;
    const double ua1 = ua.dot(m.t1), ua2 = ua.dot(m.t2), ub1 = ub.dot(m.t1), ub2 = ub.dot(m.t2);
    m.h11 = m.t1.dot(st1) - (ua1 * ua1 * ia + ub1 * ub1 * ib) - gn;
    m.h22 = m.t2.dot(st2) - (ua2 * ua2 * ia + ub2 * ub2 * ib) - gn;
    m.h12 = m.t1.dot(st2) - (ua1 * ua2 * ia + ub1 * ub2 * ib);
    m.g1 = gt.dot(m.t1);
    m.g2 = gt.dot(m.t2);
    const double tr = 0.5 * (m.h11 + m.h22);
    const double disc = std::sqrt(0.25 * (m.h11 - m.h22) * (m.h11 - m.h22) + m.h12 * m.h12);
    m.lmin = tr - disc;
    m.hscale = std::max(std::fabs(tr) + disc, size);
    return m;
  }

  // keeps the model convex: an eigenvalue below 1e-3 of the scale is shifted up to it
  double convexity_shift(const TangentModel &m)
  {
    return m.lmin < 1e-3 * m.hscale ? 1e-3 * m.hscale - m.lmin : 0.0;
  }

  // the unit eigenvector of the smallest eigenvalue (h11, h22 shifted by `shift`), turned
  // downhill: the way out of a saddle
  void descent_eigenvector(const TangentModel &m, double shift, double &e1, double &e2)
  {
    const double h11u = m.h11 - shift, h22u = m.h22 - shift;
    e1 = m.h12;
    e2 = m.lmin - h11u;
    if (e1 * e1 + e2 * e2 < (m.lmin - h22u) * (m.lmin - h22u) + m.h12 * m.h12) {
      e1 = m.lmin - h22u;
      e2 = m.h12;
    }
    const double en = std::sqrt(e1 * e1 + e2 * e2);
    if (!(en > 0.0)) {
      e1 = 1.0;
      e2 = 0.0;
    } else {
      e1 /= en;
      e2 /= en;
    }
    if (e1 * m.g1 + e2 * m.g2 > 0.0) {
      e1 = -e1;
      e2 = -e2;
    }
  }

  // the Newton step (v1, v2) of the shifted model, within the trust radius; its length
  double newton_step(const TangentModel &m, double &v1, double &v2)
  {
    const double det = m.h11 * m.h22 - m.h12 * m.h12;
    v1 = -(m.h22 * m.g1 - m.h12 * m.g2) / det;
    v2 = -(m.h11 * m.g2 - m.h12 * m.g1) / det;
    double step = std::sqrt(v1 * v1 + v2 * v2);
    if (!std::isfinite(step)) {    // should not happen; steepest descent fallback
      v1 = -m.g1 / m.hscale;
      v2 = -m.g2 / m.hscale;
      step = std::sqrt(v1 * v1 + v2 * v2);
    }
    const double max_step = 0.5;    // trust radius in radians
    if (step > max_step) {
      v1 *= max_step / step;
      v2 *= max_step / step;
      step = max_step;
    }
    return step;
  }

}    // namespace

// Riemannian Newton on the unit sphere: indefinite Hessians are shifted and long steps are
// line-searched; a stationary start is checked for a saddle and left downhill.
GapMinimum minimise_gap(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc, Vec3 n, double tol,
                        int max_iter)
{
  GapMinimum r;
  r.n = n;
  r.ev = evaluate_gap(a, b, dc, n);
  r.iterations = 0;
  r.converged = false;
  const double size = std::min(min_axis(a), min_axis(b));
  const double dc_norm = dc.norm();
  for (int it = 0; it < max_iter; ++it) {
    const GapEval &ev = r.ev;
    const double gn = ev.grad.dot(r.n);
    const Vec3 gt = ev.grad - gn * r.n;
    // round-off floor: d and grad carry ~eps*(|dc| + h) absolute error from cancellation
    const double floor = 32.0 * kEps * (dc_norm + ev.ha + ev.hb);
    const double gtn = gt.norm();
    // A start that is already stationary may be a saddle (symmetric configurations, e.g. the
    // centre line in the mid-plane of a disc): only then is the curvature checked below.
    const bool stationary = gtn <= std::max(tol * size, floor);
    if (stationary && it > 0) {
      r.converged = true;
      return r;
    }
    TangentModel m = tangent_model(a, b, r.n, ev, gt, gn, size);
    if (stationary && !(m.lmin < -1e-6 * m.hscale)) {
      r.converged = true;
      return r;
    }
    ++r.iterations;
    const double shift = convexity_shift(m);
    m.h11 += shift;
    m.h22 += shift;
    if (stationary) {    // saddle: leave along the negative-curvature eigenvector
      double e1, e2;
      descent_eigenvector(m, shift, e1, e2);
      // any decrease of d will do
      const double d0 = ev.d;
      Vec3 trial_n;
      GapEval trial;
      if (!backtrack(
              a, b, dc, r.n, m.t1, m.t2, 0.25 * e1, 0.25 * e2, 30,
              [d0](double d) {
                return d < d0;
              },
              trial_n, trial)) {
        r.converged = true;    // flat to round-off: accept the stationary point
        return r;
      }
      r.n = trial_n;
      r.ev = trial;
      continue;
    }
    double v1, v2;
    const double step = newton_step(m, v1, v2);
    // Near the minimiser the pure Newton step is safe and the line search would only
    // see round-off; far away, Armijo backtracking guarantees descent.
    const bool line_search = step > 1e-4;
    const double sufficient = ev.d + 1e-4 * (m.g1 * v1 + m.g2 * v2);    // slope < 0
    Vec3 nn;
    GapEval en;
    if (!backtrack(
            a, b, dc, r.n, m.t1, m.t2, v1, v2, 40,
            [line_search, sufficient](double d) {
              return !line_search || d <= sufficient;
            },
            nn, en))
      return r;    // no descent possible: round-off bound, not converged
    r.n = nn;
    r.ev = en;
    if (step < 1e-3 * tol) {    // step below resolution: converged to round-off
      r.converged = true;
      return r;
    }
  }
  // final convergence check after the last step
  const Vec3 gt = r.ev.grad - r.ev.grad.dot(r.n) * r.n;
  const double floor = 32.0 * kEps * (dc_norm + r.ev.ha + r.ev.hb);
  r.converged = gt.norm() <= std::max(tol * size, floor);
  return r;
}

ColdStart cold_start(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc)
{
  ColdStart s{Vec3::Zero(), 0, false, Vec3::Zero(), Vec3::Zero()};
  s.iterations = 0;
  s.perram = false;
  const double dn = dc.norm();
  const double size = std::min(min_axis(a), min_axis(b));
  const Vec3 line = dn > 1e-12 * size ? Vec3(dc / dn) : thin_axis(a);
  s.n = line;
  if ((a.sphere && b.sphere) || dn <= 1e-12 * size) return s;
  auto gapf = [&](const Vec3 &n) {
    return support(a.inverse_form, n) + support(b.inverse_form, n) - n.dot(dc);
  };
  // Several cheap candidates; keep the one with the smallest gap function. A start with
  // d < 0 lies in the (spherically convex) sublevel set {d < 0} of a disjoint pair, so the
  // descent iteration then cannot end in a spurious positive local minimum. Besides the
  // centre line: the surface normals where the centre line crosses each surface (good when
  // one body is much larger), and the Perram-type vector and the normals at its points.
  double best = gapf(line);
  auto consider = [&](Vec3 n) {
    const double nn = n.norm();
    if (!(nn > 0.0) || !std::isfinite(nn)) return;
    n /= nn;
    const double dv = gapf(n);
    if (dv < best) {
      best = dv;
      s.n = n;
    }
  };
  consider(a.form * dc);
  consider(b.form * dc);
  if (a.sphere || b.sphere) return s;
  const int iters = 4;
  s.xb = lagrange_point(b, a, iters);    // on A's surface, minimising f_B
  s.xa = lagrange_point(a, b, iters);    // on B's surface, minimising f_A
  s.iterations = 2 * iters;
  Vec3 xi = s.xb - s.xa;    // overlapping pairs: points from A's side to B's side
  const double xn = xi.norm();
  if (!(xn > 1e-12 * size) || !finite3(xi)) return s;
  consider(xi);
  consider(-xi);
  consider(a.form * (s.xb - a.center));       // A's outer normal at its Perram point
  consider(-(b.form * (s.xa - b.center)));    // B's inner normal at its Perram point
  s.perram = true;
  return s;
}

}    // namespace EllipsoidDep
