/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: engine-independent contact kernel (see ellipsoid_contact.h
   and doc/kernel.md for the maths). C++17 + Eigen only.
------------------------------------------------------------------------- */

#include "ellipsoid_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace EllipsoidDep {

namespace {

  constexpr double kEps = std::numeric_limits<double>::epsilon();
  constexpr double kPi = 3.14159265358979323846;

  inline bool finite3(const Vec3 &v)
  {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
  }

  // make_ellipsoid decides validity once per body; a centre moved afterwards (periodic
  // images) is checked again because it is cheap
  inline bool valid(const Ellipsoid &e)
  {
    return e.finite && finite3(e.center);
  }

  // Support half-width sqrt(n^T M n) (n need not be unit: degree-1 homogeneous).
  inline double support(const Mat3 &m, const Vec3 &n)
  {
    return std::sqrt(std::max(n.dot(m * n), 0.0));
  }

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

  // State of the gap function d(n) = h_A(n) + h_B(n) - n.(c_B - c_A) at a unit n.
  struct Eval {
    double ha, hb, d;
    Vec3 man, mbn;    // M_A n, M_B n
    Vec3 grad;        // gradient of the degree-1 extension = p_A - p_B
  };

  inline Eval evaluate(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc, const Vec3 &n)
  {
    Eval e;
    e.man = a.inverse_form * n;
    e.mbn = b.inverse_form * n;
    e.ha = std::sqrt(std::max(n.dot(e.man), std::numeric_limits<double>::min()));
    e.hb = std::sqrt(std::max(n.dot(e.mbn), std::numeric_limits<double>::min()));
    e.grad = e.man / e.ha + e.mbn / e.hb - dc;
    e.d = e.ha + e.hb - n.dot(dc);
    return e;
  }

  void fill_geometry(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &n, const Eval &ev,
                     ContactGeometry &g)
  {
    g.normal = n;
    g.overlap = ev.d;
    g.point_a = a.center + ev.man / ev.ha;
    g.point_b = b.center - ev.mbn / ev.hb;
    g.point = 0.5 * (g.point_a + g.point_b);
    const double ra = gaussian_radius(a, n), rb = gaussian_radius(b, -n);
    g.effective_radius = ra * rb / (ra + rb);
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

  // Result of the minimisation of d over the unit sphere.
  struct MinResult {
    Vec3 n;
    Eval ev;
    int iterations;
    bool converged;
  };

  // Safeguarded Riemannian Newton on d(n) over the unit sphere. The 2x2 Hessian is
  // T^T (H_A + H_B) T - d I with H = M/h - (Mn)(Mn)^T/h^3 (exact for the degree-1
  // extension); indefinite Hessians are shifted and long steps are line-searched.
  MinResult minimise_gap(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc, Vec3 n, double tol,
                         int max_iter)
  {
    MinResult r;
    r.n = n;
    r.ev = evaluate(a, b, dc, n);
    r.iterations = 0;
    r.converged = false;
    const double size = std::min(min_axis(a), min_axis(b));
    for (int it = 0; it < max_iter; ++it) {
      const Eval &ev = r.ev;
      const double gn = ev.grad.dot(r.n);
      const Vec3 gt = ev.grad - gn * r.n;
      // round-off floor: d and grad carry ~eps*(|dc| + h) absolute error from cancellation
      const double floor = 32.0 * kEps * (dc.norm() + ev.ha + ev.hb);
      const double gtn = gt.norm();
      // A start that is already stationary may be a saddle (symmetric configurations, e.g. the
      // centre line in the mid-plane of a disc): only then is the curvature checked below.
      const bool stationary = gtn <= std::max(tol * size, floor);
      if (stationary && it > 0) {
        r.converged = true;
        return r;
      }
      Vec3 t1, t2;
      tangent_basis(r.n, t1, t2);
      const Vec3 ua = ev.man / ev.ha, ub = ev.mbn / ev.hb;
      const Vec3 at1 = a.inverse_form * t1, at2 = a.inverse_form * t2;
      const Vec3 bt1 = b.inverse_form * t1, bt2 = b.inverse_form * t2;
      const double ua1 = ua.dot(t1), ua2 = ua.dot(t2), ub1 = ub.dot(t1), ub2 = ub.dot(t2);
      double h11 = (t1.dot(at1) - ua1 * ua1) / ev.ha + (t1.dot(bt1) - ub1 * ub1) / ev.hb - gn;
      double h22 = (t2.dot(at2) - ua2 * ua2) / ev.ha + (t2.dot(bt2) - ub2 * ub2) / ev.hb - gn;
      const double h12 = (t1.dot(at2) - ua1 * ua2) / ev.ha + (t1.dot(bt2) - ub1 * ub2) / ev.hb;
      const double g1 = gt.dot(t1), g2 = gt.dot(t2);
      // smallest eigenvalue of the 2x2; shift to keep the model convex
      const double tr = 0.5 * (h11 + h22);
      const double disc = std::sqrt(0.25 * (h11 - h22) * (h11 - h22) + h12 * h12);
      const double lmin = tr - disc;
      const double hscale = std::max(std::fabs(tr) + disc, size);
      if (stationary) {
        if (!(lmin < -1e-6 * hscale)) {
          r.converged = true;
          return r;
        }
      }
      ++r.iterations;
      if (lmin < 1e-3 * hscale) {
        const double shift = 1e-3 * hscale - lmin;
        h11 += shift;
        h22 += shift;
      }
      const double det = h11 * h22 - h12 * h12;
      double v1 = -(h22 * g1 - h12 * g2) / det;
      double v2 = -(h11 * g2 - h12 * g1) / det;
      double step = std::sqrt(v1 * v1 + v2 * v2);
      if (stationary) {    // saddle: leave along the negative-curvature eigenvector
        const double h11u = h11 - (lmin < 1e-3 * hscale ? 1e-3 * hscale - lmin : 0.0);
        const double h22u = h22 - (lmin < 1e-3 * hscale ? 1e-3 * hscale - lmin : 0.0);
        double e1 = h12, e2 = lmin - h11u;
        if (e1 * e1 + e2 * e2 < (lmin - h22u) * (lmin - h22u) + h12 * h12) {
          e1 = lmin - h22u;
          e2 = h12;
        }
        const double en = std::sqrt(e1 * e1 + e2 * e2);
        if (!(en > 0.0)) {
          e1 = 1.0;
          e2 = 0.0;
        } else {
          e1 /= en;
          e2 /= en;
        }
        if (e1 * g1 + e2 * g2 > 0.0) {
          e1 = -e1;
          e2 = -e2;
        }
        v1 = 0.25 * e1;
        v2 = 0.25 * e2;
        step = 0.25;
        Vec3 nn = (r.n + v1 * t1 + v2 * t2).normalized();
        Eval en2 = evaluate(a, b, dc, nn);
        int k = 0;
        while (!(en2.d < ev.d) && k < 30) {
          v1 *= 0.5;
          v2 *= 0.5;
          nn = (r.n + v1 * t1 + v2 * t2).normalized();
          en2 = evaluate(a, b, dc, nn);
          ++k;
        }
        if (k == 30) {    // flat to round-off: accept the stationary point
          r.converged = true;
          return r;
        }
        r.n = nn;
        r.ev = en2;
        continue;
      }
      if (!std::isfinite(step)) {    // should not happen; steepest descent fallback
        v1 = -g1 / hscale;
        v2 = -g2 / hscale;
        step = std::sqrt(v1 * v1 + v2 * v2);
      }
      const double max_step = 0.5;    // trust radius in radians
      if (step > max_step) {
        v1 *= max_step / step;
        v2 *= max_step / step;
        step = max_step;
      }
      // Near the minimiser the pure Newton step is safe and the line search would only
      // see round-off; far away, Armijo backtracking guarantees descent.
      Vec3 nn = (r.n + v1 * t1 + v2 * t2).normalized();
      Eval en = evaluate(a, b, dc, nn);
      if (step > 1e-4) {
        const double slope = g1 * v1 + g2 * v2;    // < 0
        int k = 0;
        while (!(en.d <= ev.d + 1e-4 * slope) && k < 40) {
          v1 *= 0.5;
          v2 *= 0.5;
          nn = (r.n + v1 * t1 + v2 * t2).normalized();
          en = evaluate(a, b, dc, nn);
          ++k;
        }
        if (k == 40) return r;    // no descent possible: round-off bound, not converged
      }
      r.n = nn;
      r.ev = en;
      if (step < 1e-3 * tol) {    // step below resolution: converged to round-off
        r.converged = true;
        return r;
      }
    }
    // final convergence check after the last step
    const Vec3 gt = r.ev.grad - r.ev.grad.dot(r.n) * r.n;
    const double floor = 32.0 * kEps * (dc.norm() + r.ev.ha + r.ev.hb);
    r.converged = gt.norm() <= std::max(tol * size, floor);
    return r;
  }

  // Start direction (A to B) of the iteration and the Perram-type estimate.
  struct Start {
    Vec3 n;
    int iterations;
    bool perram;    // the Perram points are valid
    Vec3 xa, xb;    // X_m^(B) (on A, deepest in B) and X_m^(A) (on B, deepest in A)
  };

  Start cold_start(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc)
  {
    Start s{Vec3::Zero(), 0, false, Vec3::Zero(), Vec3::Zero()};
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

  // --- Wang et al. quartic ----------------------------------------------------

  // Polynomial c[0] + c[1] x + ... + c[deg] x^deg, normalised to max |c| = 1.
  struct Poly {
    double c[5];
    int deg;
  };

  void normalise(Poly &p)
  {
    double m = 0.0;
    for (int i = 0; i <= p.deg; ++i) m = std::max(m, std::fabs(p.c[i]));
    if (m > 0.0) {
      const double im = 1.0 / m;
      for (int i = 0; i <= p.deg; ++i) p.c[i] *= im;
    }
  }

  // -rem(u, v) normalised; returns false when the remainder vanishes within `zero`.
  bool neg_rem(const Poly &u, const Poly &v, double zero, Poly &r)
  {
    double w[5];
    for (int i = 0; i <= u.deg; ++i) w[i] = u.c[i];
    const double ilead = 1.0 / v.c[v.deg];
    for (int k = u.deg; k >= v.deg; --k) {
      const double q = w[k] * ilead;
      for (int j = 0; j <= v.deg; ++j) w[k - v.deg + j] -= q * v.c[j];
      w[k] = 0.0;
    }
    r.deg = v.deg - 1;
    double m = 0.0;
    for (int i = 0; i <= r.deg; ++i) {
      r.c[i] = -w[i];
      m = std::max(m, std::fabs(w[i]));
    }
    if (!(m > zero)) return false;
    // trim leading coefficients at round-off level so the next division is well defined
    while (r.deg > 0 && std::fabs(r.c[r.deg]) <= 64.0 * kEps * m) --r.deg;
    normalise(r);
    return true;
  }

  // Number of distinct positive roots of a monic quartic with p(0) > 0 (Sturm's theorem
  // on (0, inf)). A remainder whose size is below `band` relative to the normalised
  // chain ends the chain: that is a (numerical) multiple root.
  int positive_roots(const double b[5], double band)
  {
    Poly chain[5];
    int len = 0;
    Poly p0;
    p0.deg = 4;
    for (int i = 0; i < 5; ++i) p0.c[i] = b[i];
    normalise(p0);
    Poly p1;
    p1.deg = 3;
    for (int i = 0; i < 4; ++i) p1.c[i] = (i + 1) * b[i + 1];
    normalise(p1);
    chain[len++] = p0;
    chain[len++] = p1;
    while (chain[len - 1].deg > 0 && len < 5) {
      Poly r;
      if (!neg_rem(chain[len - 2], chain[len - 1], band, r)) break;
      chain[len++] = r;
    }
    auto changes = [&](bool at_zero) {
      int v = 0;
      double prev = 0.0;
      for (int i = 0; i < len; ++i) {
        const double s = at_zero ? chain[i].c[0] : chain[i].c[chain[i].deg];
        if (s == 0.0) continue;
        if (prev != 0.0 && (s > 0.0) != (prev > 0.0)) ++v;
        prev = s;
      }
      return v;
    };
    return changes(true) - changes(false);
  }

}    // namespace

// ---------------------------------------------------------------------------

Mat4 Ellipsoid::homogeneous() const
{
  Mat4 h;
  const Vec3 qc = form * center;
  h.topLeftCorner<3, 3>() = form;
  h.topRightCorner<3, 1>() = -qc;
  h.bottomLeftCorner<1, 3>() = -qc.transpose();
  h(3, 3) = center.dot(qc) - 1.0;
  return h;
}

double Ellipsoid::volume() const
{
  return 4.0 / 3.0 * kPi * semi_axes[0] * semi_axes[1] * semi_axes[2];
}

Ellipsoid make_ellipsoid(const Vec3 &center, const Mat3 &rotation, const Vec3 &semi_axes)
{
  Ellipsoid e;
  e.center = center;
  e.rotation = rotation;
  e.semi_axes = semi_axes;
  const Vec3 inv2 = semi_axes.cwiseProduct(semi_axes).cwiseInverse();
  const Vec3 sq = semi_axes.cwiseProduct(semi_axes);
  e.form = rotation * inv2.asDiagonal() * rotation.transpose();
  e.inverse_form = rotation * sq.asDiagonal() * rotation.transpose();
  // exact symmetry so that both triangles agree bit for bit
  e.form = 0.5 * (e.form + e.form.transpose()).eval();
  e.inverse_form = 0.5 * (e.inverse_form + e.inverse_form.transpose()).eval();
  e.bounding_radius = semi_axes.maxCoeff();
  const double lo = semi_axes.minCoeff();
  e.sphere = (e.bounding_radius - lo) <= 1e-14 * e.bounding_radius;
  e.finite = finite3(center) && finite3(semi_axes) && lo > 0.0 && e.form.allFinite() &&
      e.inverse_form.allFinite();
  return e;
}

Ellipsoid make_ellipsoid(const Vec3 &center, const double quat[4], const Vec3 &semi_axes)
{
  Eigen::Quaterniond q(quat[0], quat[1], quat[2], quat[3]);
  const double nq = q.norm();
  Mat3 r = Mat3::Identity();
  if (nq > 0.0 && std::isfinite(nq)) {
    q.coeffs() /= nq;
    r = q.toRotationMatrix();
  } else {
    r.setConstant(std::numeric_limits<double>::quiet_NaN());    // flagged Degenerate later
  }
  return make_ellipsoid(center, r, semi_axes);
}

double gaussian_radius(const Ellipsoid &e, const Vec3 &unit_normal)
{
  const double nmn = unit_normal.dot(e.inverse_form * unit_normal);
  return e.semi_axes[0] * e.semi_axes[1] * e.semi_axes[2] / nmn;
}

bool plane_separates(const SeparatingPlane &plane, const Ellipsoid &a, const Ellipsoid &b)
{
  const Vec3 &n = plane.normal;
  const double top_a = n.dot(a.center) + std::sqrt(n.dot(a.inverse_form * n));
  const double bot_b = n.dot(b.center) - std::sqrt(n.dot(b.inverse_form * n));
  return top_a < plane.offset && bot_b > plane.offset;
}

// f(nu) = det(nu A + B) in A's body frame scaled to the unit sphere, where A becomes
// diag(1,1,1,-1). With Q, c the form and centre of B in that frame, s = c^T Q c, g = Q c,
// t = tr Q, e2 = sum of principal 2x2 minors, dq = det Q:
//   -f(nu) = nu^4 + (1 + t - s) nu^3 + (e2 + g.g - t(s-1)) nu^2
//            + (dq + t g.g - g^T Q g - e2 (s-1)) nu + dq
Status wang_classify(const Ellipsoid &a, const Ellipsoid &b, const ContactSettings &settings)
{
  if (!valid(a) || !valid(b)) return Status::Degenerate;
  // x = c_A + R_A S y, S = diag(axes_A): A is the unit sphere in y
  const Mat3 rs = a.rotation * a.semi_axes.asDiagonal();
  const Mat3 q = rs.transpose() * b.form * rs;
  const Vec3 c =
      (a.semi_axes.cwiseInverse()).asDiagonal() * (a.rotation.transpose() * (b.center - a.center));
  const Vec3 g = q * c;
  const double s = c.dot(g);
  const double t = q.trace();
  const double e2 = q(0, 0) * q(1, 1) - q(0, 1) * q(1, 0) + q(0, 0) * q(2, 2) - q(0, 2) * q(2, 0) +
      q(1, 1) * q(2, 2) - q(1, 2) * q(2, 1);
  // det Q = det(S)^2 det(Q_B) in closed form
  const double vr = (a.semi_axes[0] * a.semi_axes[1] * a.semi_axes[2]) /
      (b.semi_axes[0] * b.semi_axes[1] * b.semi_axes[2]);
  const double dq = vr * vr;
  const double gg = g.dot(g);
  const double gqg = g.dot(q * g);
  double p[5];
  p[4] = 1.0;
  p[3] = 1.0 + t - s;
  p[2] = e2 + gg - t * (s - 1.0);
  p[1] = dq + t * gg - gqg - e2 * (s - 1.0);
  p[0] = dq;
  if (!(dq > 0.0)) return Status::Degenerate;
  // rescale nu = k mu with k = dq^(1/4) so the constant and leading terms are both 1
  const double k = std::sqrt(std::sqrt(dq));
  double kp = k;
  for (int i = 3; i >= 0; --i) {
    p[i] /= kp;
    kp *= k;
  }
  for (int i = 0; i < 5; ++i)
    if (!std::isfinite(p[i])) return Status::Degenerate;
  const int npos = positive_roots(p, settings.wang_band);
  if (npos >= 2) return Status::Separated;
  if (npos == 1) return Status::Touching;
  return Status::Overlapping;
}

bool build_separating_plane(const Ellipsoid &a, const Ellipsoid &b, SeparatingPlane &plane,
                            const Vec3 *start)
{
  if (!valid(a) || !valid(b)) return false;
  const Vec3 dc = b.center - a.center;
  Vec3 n0;
  if (start && finite3(*start) && start->norm() > 0.0)
    n0 = start->normalized();
  else
    n0 = cold_start(a, b, dc).n;
  // A loose minimisation of d suffices: any n with d(n) < 0 gives a proven plane; the
  // minimiser maximises the clearance so the cached plane survives longest.
  const MinResult m = minimise_gap(a, b, dc, n0, 1e-6, 20);
  if (!(m.ev.d < 0.0)) return false;
  plane.normal = m.n;
  const double top_a = m.n.dot(a.center) + m.ev.ha;
  const double bot_b = m.n.dot(b.center) - m.ev.hb;
  plane.offset = 0.5 * (top_a + bot_b);
  return plane_separates(plane, a, b);
}

WangResult wang_test(const Ellipsoid &a, const Ellipsoid &b, const ContactSettings &settings)
{
  WangResult w;
  w.status = wang_classify(a, b, settings);
  w.plane.normal = Vec3::Zero();
  w.plane.offset = 0.0;
  if (w.status == Status::Separated) {
    // Separated but no plane found to round-off: defer to the exact iteration
    if (!build_separating_plane(a, b, w.plane, nullptr)) w.status = Status::Touching;
  }
  return w;
}

ContactGeometry sphere_contact(const Ellipsoid &a, const Ellipsoid &b)
{
  ContactGeometry g;
  if (!valid(a) || !valid(b)) {
    g.status = Status::Degenerate;
    return g;
  }
  const double ra = a.bounding_radius, rb = b.bounding_radius;
  const Vec3 dc = b.center - a.center;
  const double dist = dc.norm();
  // coincident centres: any direction is a minimiser; +z by convention
  const Vec3 n = dist > 0.0 ? Vec3(dc / dist) : Vec3(0.0, 0.0, 1.0);
  g.normal = n;
  g.overlap = (ra + rb) - dist;
  g.point_a = a.center + ra * n;
  g.point_b = b.center - rb * n;
  g.point = 0.5 * (g.point_a + g.point_b);
  g.effective_radius = ra * rb / (ra + rb);
  g.status = g.overlap > 0.0 ? Status::Overlapping : Status::Separated;
  return g;
}

ContactGeometry ellipsoid_contact(const Ellipsoid &a, const Ellipsoid &b,
                                  const ContactSettings &settings, const Vec3 *warm_normal)
{
  if (!valid(a) || !valid(b)) {
    ContactGeometry g;
    g.status = Status::Degenerate;
    return g;
  }
  if (a.sphere && b.sphere) return sphere_contact(a, b);
  ContactGeometry g;
  const Vec3 dc = b.center - a.center;
  const double tol = settings.tolerance > 0.0 ? settings.tolerance : 1e-12;
  const int max_iter = std::max(settings.max_iterations, 1);
  Vec3 n0;
  int it0 = 0;
  bool have_warm = false;
  if (warm_normal && finite3(*warm_normal)) {
    const double wn = warm_normal->norm();
    if (wn > 0.0) {
      n0 = *warm_normal / wn;
      have_warm = true;
    }
  }
  Start s{Vec3::Zero(), 0, false, Vec3::Zero(), Vec3::Zero()};
  if (!have_warm) {
    s = cold_start(a, b, dc);
    n0 = s.n;
    it0 = s.iterations;
  }
  // Paper's fast mode: accept the uncorrected vector when it agrees with the averaged
  // surface gradients at the contact point within correction_angle.
  if (settings.correction_angle > 0.0) {
    Vec3 xa = Vec3::Zero(), xb = Vec3::Zero(), dir = Vec3::Zero();
    if (have_warm || !s.perram) {
      const Eval ev = evaluate(a, b, dc, n0);
      xa = a.center + ev.man / ev.ha;
      xb = b.center - ev.mbn / ev.hb;
      dir = n0;
    } else if (s.perram) {
      xa = s.xb;
      xb = s.xa;
      dir = s.n;
    }
    if (dir.squaredNorm() > 0.0) {
      const Vec3 xc = 0.5 * (xa + xb);
      Vec3 ga = a.form * (xc - a.center), gb = -(b.form * (xc - b.center));
      const double gan = ga.norm(), gbn = gb.norm();
      if (gan > 0.0 && gbn > 0.0) {
        const Vec3 avg = ga / gan + gb / gbn;
        const double an = avg.norm();
        const double cosang = an > 0.0 ? std::clamp(avg.dot(dir) / an, -1.0, 1.0) : -1.0;
        if (std::acos(cosang) < settings.correction_angle) {
          const Vec3 xi = xa - xb;
          const double sgn = xi.dot(dir) >= 0.0 ? 1.0 : -1.0;
          // overlapping: X_m^(B) - X_m^(A) points along n, length = overlap
          g.normal = dir;
          g.point_a = xa;
          g.point_b = xb;
          g.point = xc;
          g.overlap = sgn * xi.norm();
          if (have_warm || !s.perram) g.overlap = evaluate(a, b, dc, n0).d;
          const double ra = gaussian_radius(a, dir), rb = gaussian_radius(b, -dir);
          g.effective_radius = ra * rb / (ra + rb);
          g.iterations = it0;
          g.corrected = false;
          g.status = g.overlap > 0.0 ? Status::Overlapping : Status::Separated;
          return g;
        }
      }
    }
  }
  MinResult m = minimise_gap(a, b, dc, n0, tol, max_iter);
  // A warm start from a stale normal can land in the wrong basin on a deep overlap; a
  // non-converged warm run gets one cold retry before giving up.
  if (!m.converged && have_warm) {
    s = cold_start(a, b, dc);
    const MinResult mc = minimise_gap(a, b, dc, s.n, tol, max_iter);
    it0 += s.iterations + m.iterations;
    m = mc;
  }
  fill_geometry(a, b, m.n, m.ev, g);
  g.iterations = it0 + m.iterations;
  g.corrected = true;
  if (g.overlap <= 0.0)
    g.status = Status::Separated;    // d(n) <= 0 for some n proves separation
  else
    g.status = m.converged ? Status::Overlapping : Status::NotConverged;
  if (!finite3(g.normal) || !std::isfinite(g.overlap) || !finite3(g.point)) {
    g = ContactGeometry();
    g.status = Status::Degenerate;
  }
  return g;
}

ContactGeometry ellipsoid_plane_contact(const Ellipsoid &e, const Vec3 &wall_normal,
                                        double wall_offset)
{
  ContactGeometry g;
  if (!valid(e) || !finite3(wall_normal) || !std::isfinite(wall_offset) ||
      !(wall_normal.norm() > 0.0)) {
    g.status = Status::Degenerate;
    return g;
  }
  const Vec3 n = wall_normal.normalized();
  const Vec3 mn = e.inverse_form * n;
  const double h = std::sqrt(n.dot(mn));
  const Vec3 p = e.center - mn / h;    // lowest point along n
  g.overlap = wall_offset - n.dot(p);
  g.normal = -n;
  g.point_a = p;
  g.point_b = p + g.overlap * n;    // projection on the wall
  g.point = 0.5 * (g.point_a + g.point_b);
  g.effective_radius = gaussian_radius(e, -n);
  g.status = g.overlap > 0.0 ? Status::Overlapping : Status::Separated;
  return g;
}

double ellipsoid_slab_volume(const Ellipsoid &e, double zlo, double zhi)
{
  if (!valid(e) || !(zhi > zlo)) return 0.0;
  // z half-extent h = sqrt(M_zz); section area(z) = (3V/4h)(1 - ((z-cz)/h)^2)
  const double h = std::sqrt(e.inverse_form(2, 2));
  const double t1 = std::clamp((zlo - e.center[2]) / h, -1.0, 1.0);
  const double t2 = std::clamp((zhi - e.center[2]) / h, -1.0, 1.0);
  if (!(t2 > t1)) return 0.0;
  const double integral = (t2 - t1) - (t2 * t2 * t2 - t1 * t1 * t1) / 3.0;    // in [0, 4/3]
  return 0.75 * e.volume() * integral;
}

void PipelineCounters::add(const PipelineCounters &o)
{
  pairs += o.pairs;
  bounding_rejects += o.bounding_rejects;
  plane_hits += o.plane_hits;
  wang_calls += o.wang_calls;
  wang_separated += o.wang_separated;
  contacts += o.contacts;
  iterations += o.iterations;
  corrections += o.corrections;
  not_converged += o.not_converged;
  degenerate += o.degenerate;
  continued += o.continued;
}

namespace {
  inline void clear_cache(double *cache)
  {
    for (int i = 0; i < PAIR_CACHE_SIZE; ++i) cache[i] = 0.0;
  }

  // plane {n.x = offset} stored as (n, u): it passes through c_A + (1/2 + u)(c_B - c_A)
  inline void store_plane(double *cache, const Vec3 &n, double offset, const Vec3 &ca,
                          const Vec3 &dc)
  {
    const double nd = n.dot(dc);
    if (!(nd > 0.0)) {
      clear_cache(cache);
      return;
    }
    cache[0] = 1.0;
    cache[1] = n[0];
    cache[2] = n[1];
    cache[3] = n[2];
    cache[4] = (offset - n.dot(ca)) / nd - 0.5;
  }
}    // namespace

ContactGeometry evaluate_pair(const Ellipsoid &a, const Ellipsoid &b,
                              const PipelineSettings &settings, double *cache,
                              PipelineCounters &counters)
{
  ++counters.pairs;
  ContactGeometry g;
  const Vec3 dc = b.center - a.center;
  const double dist = dc.norm();
  const double reach = a.bounding_radius + b.bounding_radius;
  // NaN compares false: non-finite input falls through to the validity check
  if (dist > reach && std::isfinite(dist) && std::isfinite(reach)) {
    ++counters.bounding_rejects;
    clear_cache(cache);
    g.status = Status::Separated;
    g.normal = dc / dist;
    g.overlap = reach - dist;    // minus a lower bound of the distance
    return g;
  }
  const int state = static_cast<int>(std::fabs(cache[0]) + 0.5);
  const Vec3 cached_n(cache[1], cache[2], cache[3]);
  const bool have_n =
      (state == 1 || state == 2) && finite3(cached_n) && cached_n.squaredNorm() > 0.25;
  if (state == 1 && have_n && settings.use_planes) {
    SeparatingPlane pl;
    pl.normal = cached_n;
    pl.offset = cached_n.dot(a.center + (0.5 + cache[4]) * dc);
    // any NaN makes the test false, so invalid input cannot hit here
    if (plane_separates(pl, a, b)) {
      ++counters.plane_hits;
      g.status = Status::Separated;
      g.normal = cached_n;
      return g;
    }
  }
  if (!valid(a) || !valid(b) || !std::isfinite(dist)) {
    ++counters.degenerate;
    clear_cache(cache);
    g.status = Status::Degenerate;
    return g;
  }
  // A pair in contact at the previous evaluation goes straight to the iteration, warm-started
  // from its own last normal: the sign of min d(n) decides separation exactly, and the
  // continuing contact keeps its basin. The Wang test screens pairs that newly come close.
  const bool continuing_contact = state == 2 && have_n;
  if (continuing_contact) ++counters.continued;
  if (settings.use_wang && !continuing_contact) {
    ++counters.wang_calls;
    const Status ws = wang_classify(a, b, settings.contact);
    if (ws == Status::Degenerate) {
      ++counters.degenerate;
      clear_cache(cache);
      g.status = Status::Degenerate;
      return g;
    }
    if (ws == Status::Separated) {
      SeparatingPlane pl;
      if (build_separating_plane(a, b, pl, have_n ? &cached_n : nullptr)) {
        ++counters.wang_separated;
        store_plane(cache, pl.normal, pl.offset, a.center, dc);
        g.status = Status::Separated;
        g.normal = pl.normal;
        return g;
      }
      // no plane to round-off: fall through to the exact iteration
    }
  }
  g = ellipsoid_contact(a, b, settings.contact, have_n ? &cached_n : nullptr);
  counters.iterations += g.iterations;
  if (g.corrected) ++counters.corrections;
  if (g.status == Status::Degenerate) {
    ++counters.degenerate;
    clear_cache(cache);
    return g;
  }
  if (g.overlap <= 0.0) {
    // a disjoint pair's minimiser gives a separating plane through the gap midpoint
    store_plane(cache, g.normal, g.normal.dot(g.point), a.center, dc);
    g.status = Status::Separated;
    return g;
  }
  ++counters.contacts;
  if (g.status == Status::NotConverged) ++counters.not_converged;
  cache[0] = 2.0;
  cache[1] = g.normal[0];
  cache[2] = g.normal[1];
  cache[3] = g.normal[2];
  cache[4] = 0.0;
  return g;
}

}    // namespace EllipsoidDep
