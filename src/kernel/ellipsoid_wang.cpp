/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: Wang et al. quartic, its Sturm chain, the classification and the
   separating plane (see ellipsoid_wang.h for the conventions, doc/kernel.md for the maths).
------------------------------------------------------------------------- */

#include "ellipsoid_wang.h"

#include "ellipsoid_gap.h"

namespace EllipsoidDep {

namespace {

  constexpr double kEps = std::numeric_limits<double>::epsilon();

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
  const GapMinimum m = minimise_gap(a, b, dc, n0, 1e-6, 20);
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

}    // namespace EllipsoidDep
