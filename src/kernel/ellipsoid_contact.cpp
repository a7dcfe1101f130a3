/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: contact of two ellipsoids (see ellipsoid_contact.h for the
   conventions, doc/kernel.md for the maths).
------------------------------------------------------------------------- */

#include "ellipsoid_contact.h"

#include "ellipsoid_gap.h"

namespace EllipsoidDep {

namespace {

  // The geometry of a contact with unit normal n (A to B), the two surface points and R*.
  void fill_geometry(const Vec3 &n, const Vec3 &point_a, const Vec3 &point_b, double overlap,
                     double radius, ContactGeometry &g)
  {
    g.normal = n;
    g.overlap = overlap;
    g.point_a = point_a;
    g.point_b = point_b;
    g.point = 0.5 * (point_a + point_b);
    g.effective_radius = radius;
  }

  // ... at the support points of n, where the overlap is d(n); R* from the support
  // half-widths h = sqrt(n^T M n) the evaluation already has
  void fill_geometry(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &n, const GapEval &ev,
                     ContactGeometry &g)
  {
    fill_geometry(n, a.center + ev.ua, b.center - ev.ub, ev.d,
                  effective_radius(gaussian_radius_of_nmn(a, ev.ha * ev.ha),
                                   gaussian_radius_of_nmn(b, ev.hb * ev.hb)),
                  g);
  }

  // The fast mode's test: the angle between dir and the average of the unit surface gradients
  // Q_A (x - c_A) and -Q_B (x - c_B) at x is below max_angle.
  bool gradients_agree(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &x, const Vec3 &dir,
                       double max_angle)
  {
    if (!(dir.squaredNorm() > 0.0)) return false;
    const Vec3 ga = a.form * (x - a.center), gb = -(b.form * (x - b.center));
    const double gan = ga.norm(), gbn = gb.norm();
    if (!(gan > 0.0 && gbn > 0.0)) return false;
    const Vec3 avg = ga / gan + gb / gbn;
    const double an = avg.norm();
    const double cosang = an > 0.0 ? std::clamp(avg.dot(dir) / an, -1.0, 1.0) : -1.0;
    return std::acos(cosang) < max_angle;
  }

}    // namespace

ContactGeometry sphere_contact(const Ellipsoid &a, const Ellipsoid &b)
{
  if (!valid(a) || !valid(b)) {
    ContactGeometry g;
    g.status = Status::Degenerate;
    return g;
  }
  const Vec3 dc = b.center - a.center;
  return valid_sphere_contact(a, b, dc, dc.norm());
}

ContactGeometry valid_sphere_contact(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc,
                                     double dist)
{
  ContactGeometry g;
  const double ra = a.bounding_radius, rb = b.bounding_radius;
  // coincident centres: any direction is a minimiser; +z by convention
  const Vec3 n = dist > 0.0 ? Vec3(dc / dist) : Vec3(0.0, 0.0, 1.0);
  g.normal = n;
  g.overlap = (ra + rb) - dist;
  g.point_a = a.center + ra * n;
  g.point_b = b.center - rb * n;
  g.point = 0.5 * (g.point_a + g.point_b);
  g.effective_radius = effective_radius(ra, rb);
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
  return valid_ellipsoid_contact(a, b, settings, warm_normal);
}

ContactGeometry valid_ellipsoid_contact(const Ellipsoid &a, const Ellipsoid &b,
                                        const ContactSettings &settings, const Vec3 *warm_normal)
{
  // one result object returned on every path, so that it is built in the caller's place
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
  ColdStart s{Vec3::Zero(), 0, false, Vec3::Zero(), Vec3::Zero()};
  if (!have_warm) {
    s = cold_start(a, b, dc);
    n0 = s.n;
    it0 = s.iterations;
  }
  // Paper's fast mode: accept the uncorrected vector when it agrees with the averaged
  // surface gradients at the contact point within correction_angle. The uncorrected points
  // are the Perram-type points of a cold start, else the support points of the start.
  if (settings.correction_angle > 0.0) {
    const bool perram = !have_warm && s.perram;
    Vec3 xa, xb;
    double overlap;
    if (perram) {
      xa = s.xb;
      xb = s.xa;
      const Vec3 xi = xa - xb;    // overlapping: X_m^(B) - X_m^(A) points along n
      overlap = (xi.dot(n0) >= 0.0 ? 1.0 : -1.0) * xi.norm();
    } else {
      const GapEval ev = evaluate_gap(a, b, dc, n0);
      xa = a.center + ev.ua;
      xb = b.center - ev.ub;
      overlap = ev.d;
    }
    if (gradients_agree(a, b, 0.5 * (xa + xb), n0, settings.correction_angle)) {
      fill_geometry(n0, xa, xb, overlap, effective_radius(a, b, n0), g);
      g.iterations = it0;
      g.corrected = false;
      g.status = g.overlap > 0.0 ? Status::Overlapping : Status::Separated;
      return g;
    }
  }
  GapMinimum m = minimise_gap(a, b, dc, n0, tol, max_iter);
  // A warm start from a stale normal can land in the wrong basin on a deep overlap; a
  // non-converged warm run gets one cold retry before giving up.
  if (!m.converged && have_warm) {
    s = cold_start(a, b, dc);
    const GapMinimum mc = minimise_gap(a, b, dc, s.n, tol, max_iter);
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

}    // namespace EllipsoidDep
