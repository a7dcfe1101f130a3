/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: the overlap over a patch of directions (see ellipsoid_normal_patch.h)
------------------------------------------------------------------------- */

#include "ellipsoid_normal_patch.h"

#include <algorithm>
#include <vector>

namespace EllipsoidDep {

Vec3 NormalPatch::normal(double phi, double psi) const
{
  return std::cos(psi) * a + std::sin(psi) * (std::cos(phi) * e1 + std::sin(phi) * e2);
}

double NormalPatch::value(double phi, double psi) const
{
  const Vec3 n = normal(phi, psi);
  return support(m, n) + n.dot(d) + rim_radius * std::sin(psi);
}

void NormalArc::derivatives(double phi, double &df, double &ddf) const
{
  // n = cos(phi) e1 + sin(phi) e2: n' = t (the tangent), n'' = -n
  const Vec3 n = patch.normal(phi, 0.5 * PI);
  const Vec3 t = -std::sin(phi) * patch.e1 + std::cos(phi) * patch.e2;
  const Vec3 mn = patch.m * n;
  const double h = std::sqrt(n.dot(mn));
  const double along = mn.dot(t);
  df = along / h + t.dot(patch.d);
  ddf = (t.dot(patch.m * t) - along * along / (h * h)) / h - h - n.dot(patch.d);
}

double NormalPatch::overlap(const Vec3 &n) const
{
  return support(m, n) + n.dot(d) + rim_radius * (n - n.dot(a) * a).norm();
}

namespace {

  constexpr int NEWTON_STEPS = 50;
  constexpr int HALVINGS = 40;
  constexpr double SHORT_STEP = 1e-4;    // radians

  // F(v) = sqrt(v^T M v) + v.d + r |v_perp| on R^3 (degree-1 homogeneous, f on the sphere):
  // its gradient and Hessian
  void overlap_terms(const NormalPatch &f, const Vec3 &v, Vec3 &gradient, Mat3 &hessian)
  {
    const Vec3 mv = f.m * v;
    const double h = std::sqrt(v.dot(mv));
    gradient = mv / h + f.d;
    hessian = f.m / h - mv * mv.transpose() / (h * h * h);
    if (f.rim_radius > 0.0) {
      const Mat3 across = Mat3::Identity() - f.a * f.a.transpose();
      const Vec3 w = across * v;
      const double l = w.norm();
      gradient += f.rim_radius * w / l;
      hessian += f.rim_radius * (across / l - w * w.transpose() / (l * l * l));
    }
  }

  // Newton's method on the sphere from a start inside the cone {n : n.q >= 0 for each
  // bound q}: each step in the plane tangent at the iterate (gradient P G, Hessian
  // P H P - (n.G) P, P the projection on that plane), the new direction normalize(n + s);
  // a bound that the iterate lies on and that the descent leads out of holds the step to
  // its line (a corner of two such bounds ends the search); a step that would cross a
  // bound is cut at it; a gradient step where the Hessian is not positive definite
  PatchMinimum refine(const NormalPatch &f, Vec3 n, const std::vector<Vec3> &bounds)
  {
    double value = f.overlap(n);
    for (int it = 0; it < NEWTON_STEPS; it++) {
      // at the rim's kink (the cap's normal) the cap's own value stands
      if (f.rim_radius > 0.0 && (n - n.dot(f.a) * f.a).norm() < 1e-12) return {n, value, true};
      Vec3 g3;
      Mat3 h3;
      overlap_terms(f, n, g3, h3);
      const Mat3 p = Mat3::Identity() - n * n.transpose();
      const Vec3 gradient = p * g3;
      const Mat3 hessian = p * h3 * p - n.dot(g3) * p;
      // the tangent directions the search may take: both, or along one bound's line
      Eigen::Matrix<double, 3, Eigen::Dynamic> basis(3, 2);
      basis.col(0) = n.unitOrthogonal();
      basis.col(1) = n.cross(basis.col(0));
      std::vector<bool> held(bounds.size(), false);
      int holding = 0;
      for (std::size_t k = 0; k < bounds.size(); k++)
        if (n.dot(bounds[k]) <= 1e-14 && gradient.dot(bounds[k]) > 0.0) {
          if (++holding == 2) return {n, value, true};
          held[k] = true;
          basis.resize(3, 1);
          basis.col(0) = n.cross(bounds[k]).normalized();
        }
      const Eigen::VectorXd g = basis.transpose() * gradient;
      const Eigen::MatrixXd h = basis.transpose() * hessian * basis;
      const Eigen::LLT<Eigen::MatrixXd> llt(h);
      const bool newton = llt.info() == Eigen::Success;
      Vec3 step;
      if (newton) {
        step = basis * llt.solve(-g);
      } else {
        const double length = g.norm();
        if (!(length > 0.0)) return {n, value, false};
        step = basis * (-g * (0.05 / length));    // a short descent step, trimmed below
      }
      if (newton && step.norm() <= 1e-12) return {n, value, true};
      // the part of the step inside the cone (a held bound's line is followed)
      double t_edge = 1.0;
      for (std::size_t k = 0; k < bounds.size(); k++) {
        const double approach = -step.dot(bounds[k]);
        if (!held[k] && approach > 0.0)
          t_edge = std::min(t_edge, std::max(0.0, n.dot(bounds[k])) / approach);
      }
      // the longest step, halved, that does not rise; a short Newton step is taken whole
      // (near the minimum the value's change falls below its round-off)
      const bool whole = newton && step.norm() < SHORT_STEP;
      double t = t_edge;
      bool accepted = false;
      for (int k = 0; k < HALVINGS && !accepted; k++, t *= 0.5) {
        const Vec3 next = (n + t * step).normalized();
        const double next_value = f.overlap(next);
        if (whole || next_value <= value) {
          n = next;
          value = next_value;
          accepted = true;
        }
      }
      // a Newton step that cannot lower the value: settled to round-off
      if (!accepted) return {n, value, newton};
    }
    return {n, value, false};
  }

}    // namespace

PatchMinimum minimise_on_patch(const NormalPatch &f, double phi_span, int phi_samples,
                               int psi_samples)
{
  const bool periodic = phi_span >= 2.0 * PI;
  const double dphi = phi_span / phi_samples, dpsi = 0.5 * PI / psi_samples;
  auto at = [&](int i, int j) {
    return f.normal((i + 0.5) * dphi, (j + 0.5) * dpsi);
  };
  std::vector<double> values(phi_samples * psi_samples);
  auto cell = [&](int i, int j) -> double & {
    return values[i * psi_samples + j];
  };
  for (int i = 0; i < phi_samples; i++)
    for (int j = 0; j < psi_samples; j++) cell(i, j) = f.overlap(at(i, j));
  // discrete minima over the 8 neighbours
  std::vector<int> dips;
  for (int i = 0; i < phi_samples; i++)
    for (int j = 0; j < psi_samples; j++) {
      bool lowest = true;
      for (int di = -1; di <= 1 && lowest; di++)
        for (int dj = -1; dj <= 1 && lowest; dj++) {
          int ni = i + di;
          const int nj = j + dj;
          if (periodic) ni = (ni + phi_samples) % phi_samples;
          if ((di == 0 && dj == 0) || ni < 0 || ni >= phi_samples || nj < 0 || nj >= psi_samples)
            continue;
          if (cell(ni, nj) < cell(i, j)) lowest = false;
        }
      if (lowest) dips.push_back(i * psi_samples + j);
    }
  // the cone: n.a >= 0, and a corner's two sides
  std::vector<Vec3> bounds{f.a};
  if (!periodic) bounds.insert(bounds.end(), {f.e1, f.e2});
  PatchMinimum best;
  for (const int dip : dips) {
    const PatchMinimum candidate = refine(f, at(dip / psi_samples, dip % psi_samples), bounds);
    if (candidate.value < best.value) best = candidate;
  }
  return best;
}

ContactGeometry solid_contact(const Ellipsoid &e, const Vec3 &n, double overlap, double wall_radius,
                              bool converged)
{
  ContactGeometry g;
  const Vec3 mn = e.inverse_form * n;
  g.normal = -n;
  g.overlap = overlap;
  g.point_a = e.center - mn / std::sqrt(n.dot(mn));    // the particle's lowest point along n
  g.point_b = g.point_a + overlap * n;                 // on the solid's supporting plane
  g.point = 0.5 * (g.point_a + g.point_b);
  g.effective_radius = wall_effective_radius(gaussian_radius(e, n), wall_radius);
  g.status = surface_status(converged, overlap);
  return g;
}

}    // namespace EllipsoidDep
