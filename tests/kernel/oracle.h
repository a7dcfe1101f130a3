// Independent long-double oracle for the ellipsoid contact kernel tests.
// It never calls the code under test: it rebuilds M = R diag(a^2) R^T in long double from
// the raw inputs (rotation, semi-axes, centre), samples d(n) on a Fibonacci sphere and
// refines the best candidates by a damped Newton method whose Hessian comes from central
// finite differences of the analytic long-double gradient (a different algorithm from the
// kernel's analytic Riemannian Newton).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace Oracle {

using LD = long double;
using V3 = std::array<LD, 3>;
using M3 = std::array<std::array<LD, 3>, 3>;

struct Body {
  V3 c;
  M3 m;    // R diag(a^2) R^T
};

inline LD dot(const V3 &a, const V3 &b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline V3 mul(const M3 &m, const V3 &v)
{
  V3 r;
  for (int i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
  return r;
}
inline V3 axpy(LD s, const V3 &x, const V3 &y)
{
  return {s * x[0] + y[0], s * x[1] + y[1], s * x[2] + y[2]};
}
inline LD norm(const V3 &v)
{
  return std::sqrt(dot(v, v));
}
inline V3 unit(const V3 &v)
{
  const LD n = norm(v);
  return {v[0] / n, v[1] / n, v[2] / n};
}

// rot[i][j]: row i, column j (columns = body axes)
inline Body make_body(const double c[3], const double rot[3][3], const double axes[3])
{
  Body b;
  for (int i = 0; i < 3; ++i) b.c[i] = c[i];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      LD s = 0;
      for (int k = 0; k < 3; ++k)
        s += (LD) rot[i][k] * (LD) axes[k] * (LD) axes[k] * (LD) rot[j][k];
      b.m[i][j] = s;
    }
  return b;
}

inline LD h(const Body &b, const V3 &n)
{
  return std::sqrt(dot(n, mul(b.m, n)));
}

inline LD gap(const Body &a, const Body &b, const V3 &n)
{
  V3 dc = {b.c[0] - a.c[0], b.c[1] - a.c[1], b.c[2] - a.c[2]};
  return h(a, n) + h(b, n) - dot(n, dc);
}

// gradient of the degree-1 extension: p_A - p_B
inline V3 grad(const Body &a, const Body &b, const V3 &n)
{
  const V3 ma = mul(a.m, n), mb = mul(b.m, n);
  const LD ha = std::sqrt(dot(n, ma)), hb = std::sqrt(dot(n, mb));
  V3 g;
  for (int i = 0; i < 3; ++i) g[i] = ma[i] / ha + mb[i] / hb - (b.c[i] - a.c[i]);
  return g;
}

inline void basis(const V3 &n, V3 &t1, V3 &t2)
{
  V3 e = std::fabs(n[0]) < 0.6L ? V3{1, 0, 0} : V3{0, 1, 0};
  t1 = unit(axpy(-dot(e, n), n, e));
  t2 = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2], n[0] * t1[1] - n[1] * t1[0]};
}

struct Result {
  V3 n;
  LD d;
};

// Local minimum of d near n0.
inline Result refine(const Body &a, const Body &b, V3 n)
{
  n = unit(n);
  LD d = gap(a, b, n);
  for (int it = 0; it < 200; ++it) {
    V3 t1, t2;
    basis(n, t1, t2);
    auto chart_grad = [&](LD u, LD v, LD &g1, LD &g2) {
      const V3 m = unit(axpy(v, t2, axpy(u, t1, n)));
      const V3 g = grad(a, b, m);
      // derivative of d(normalize(n + u t1 + v t2)) w.r.t. u, v
      const LD r = std::sqrt(1 + u * u + v * v);
      V3 du, dv;
      for (int i = 0; i < 3; ++i) {
        du[i] = (t1[i] - m[i] * u / r) / r;
        dv[i] = (t2[i] - m[i] * v / r) / r;
      }
      g1 = dot(g, du);
      g2 = dot(g, dv);
    };
    LD g1, g2;
    chart_grad(0, 0, g1, g2);
    const LD gn = std::sqrt(g1 * g1 + g2 * g2);
    if (gn < 1e-17L * (h(a, n) + h(b, n))) break;
    const LD e = 1e-7L;
    LD a1, a2, b1, b2, c1, c2, e1, e2;
    chart_grad(e, 0, a1, a2);
    chart_grad(-e, 0, b1, b2);
    chart_grad(0, e, c1, c2);
    chart_grad(0, -e, e1, e2);
    LD H11 = (a1 - b1) / (2 * e), H21 = (a2 - b2) / (2 * e);
    LD H12 = (c1 - e1) / (2 * e), H22 = (c2 - e2) / (2 * e);
    LD H12s = 0.5L * (H12 + H21);
    LD det = H11 * H22 - H12s * H12s;
    LD su, sv;
    if (H11 > 0 && det > 0) {
      su = -(H22 * g1 - H12s * g2) / det;
      sv = -(H11 * g2 - H12s * g1) / det;
    } else {
      const LD s = 0.1L / (gn + 1e-30L);
      su = -g1 * s;
      sv = -g2 * s;
    }
    const LD len = std::sqrt(su * su + sv * sv);
    if (len > 0.3L) {
      su *= 0.3L / len;
      sv *= 0.3L / len;
    }
    V3 m;
    LD dm = 0;
    int k = 0;
    for (; k < 60; ++k) {
      m = unit(axpy(sv, t2, axpy(su, t1, n)));
      dm = gap(a, b, m);
      if (dm <= d) break;
      su *= 0.5L;
      sv *= 0.5L;
    }
    if (k == 60) break;
    const bool tiny = std::sqrt(su * su + sv * sv) < 1e-19L;
    n = m;
    d = dm;
    if (tiny) break;
  }
  return {n, d};
}

// Global minimum of d over the sphere: Fibonacci sampling + refinement of the best few.
inline Result global_min(const Body &a, const Body &b, int samples = 6000)
{
  std::vector<std::pair<LD, V3>> best;
  const LD ga = 3.14159265358979323846264338L * (3 - std::sqrt(5.0L));
  for (int i = 0; i < samples; ++i) {
    const LD z = 1 - (2 * i + 1) / (LD) samples;
    const LD r = std::sqrt(1 - z * z);
    const V3 n = {r * std::cos(ga * i), r * std::sin(ga * i), z};
    const LD d = gap(a, b, n);
    best.push_back({d, n});
  }
  std::partial_sort(best.begin(), best.begin() + 8, best.end(), [](const auto &x, const auto &y) {
    return x.first < y.first;
  });
  Result r{best[0].second, best[0].first};
  for (int i = 0; i < 8; ++i) {
    const Result q = refine(a, b, best[i].second);
    if (q.d < r.d) r = q;
  }
  return r;
}

inline LD angle(const V3 &a, const V3 &b)
{
  const V3 c = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return std::atan2(norm(c), dot(a, b));
}

}    // namespace Oracle
