/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: ellipsoid inside a cone (see ellipsoid_cone_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_cone_contact.h"

#include "ellipsoid_interval_search.h"

#include <array>

namespace EllipsoidDep {

namespace {

  constexpr int SAMPLES = 64;

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

  // the search minimises: the cone's objective negated
  struct NegatedCone {
    const ConeObjective &f;
    double value(double phi) const { return -f.value(phi); }
    void derivatives(double phi, double &df, double &ddf) const
    {
      f.derivatives(phi, df, ddf);
      df = -df, ddf = -ddf;
    }
  };

}    // namespace

namespace {

  // the contact at the profile's maximum phi (f = deepest there)
  ContactGeometry contact_at(const Ellipsoid &e, const ConeObjective &f, const Vec3 &center,
                             double radius, const IntervalMinimum &maximum)
  {
    ContactGeometry g;
    const Vec3 w = f.w(maximum.x);
    const double length = w.norm();
    const Vec3 normal = w / length;
    const Vec3 mn = e.inverse_form * normal;
    const Vec3 p = e.center + mn / std::sqrt(normal.dot(mn));    // support point along normal
    g.normal = normal;
    g.overlap = (-maximum.value - radius) / length;
    g.point_a = p;
    g.point_b = p - g.overlap * normal;
    g.point = 0.5 * (g.point_a + g.point_b);
    const double local_radius = radius + f.slope * f.u.dot(g.point_b - center);
    g.effective_radius = wall_effective_radius(gaussian_radius(e, normal), -2.0 * local_radius);
    g.status = surface_status(maximum.converged, g.overlap);
    return g;
  }

  bool usable(const Ellipsoid &e, const Vec3 &center, const Vec3 &axis, double radius,
              double slope)
  {
    return valid(e) && finite3(center) && finite3(axis) && axis.norm() > 0.0 && radius > 0.0 &&
        std::isfinite(radius) && std::isfinite(slope);
  }

  ConeObjective objective(const Ellipsoid &e, const Vec3 &center, const Vec3 &axis, double slope)
  {
    const Vec3 u = axis.normalized();
    const Vec3 e1 = u.unitOrthogonal();
    return ConeObjective{e.inverse_form, e1, u.cross(e1), u, e.center - center, slope};
  }

}    // namespace

ContactGeometry ellipsoid_cone_contact(const Ellipsoid &e, const Vec3 &center, const Vec3 &axis,
                                       double radius, double slope)
{
  if (!usable(e, center, axis, radius, slope)) {
    ContactGeometry g;
    g.status = Status::Degenerate;
    return g;
  }
  const ConeObjective f = objective(e, center, axis, slope);
  // the two best discrete maxima of the samples refined
  return contact_at(e, f, center, radius,
                    minimise_on_interval(NegatedCone{f}, 0.0, 2.0 * PI, true, SAMPLES, 2));
}

int concave_side_contacts(const Ellipsoid &e, const Vec3 &center, const Vec3 &axis, double radius,
                          double slope, ContactGeometry contacts[2], double &neck)
{
  if (!usable(e, center, axis, radius, slope)) return 0;
  const ConeObjective f = objective(e, center, axis, slope);
  std::vector<IntervalMinimum> peaks =
      local_minima_on_interval(NegatedCone{f}, 0.0, 2.0 * PI, true, SAMPLES, 2);
  // the deeper first (the first of equals, as minimise_on_interval)
  if (peaks.size() == 2 && peaks[1].value < peaks[0].value) std::swap(peaks[0], peaks[1]);
  contacts[0] = contact_at(e, f, center, radius, peaks[0]);
  if (peaks.size() < 2) return 1;
  // the same peak reached from two samples
  const double apart = std::remainder(peaks[1].x - peaks[0].x, 2.0 * PI);
  if (std::fabs(apart) < 2.0 * PI / SAMPLES) return 1;
  // the neck: the higher of the profile's lowest points on the two arcs between the peaks
  const double a = peaks[0].x, b = a + (apart > 0.0 ? apart : apart + 2.0 * PI);
  const double length = std::sqrt(1.0 + slope * slope);    // |w(phi)|
  neck = -HUGE_VAL;
  for (const auto &arc : {std::array<double, 2>{a, b}, std::array<double, 2>{b, a + 2.0 * PI}}) {
    const IntervalMinimum low = minimise_on_interval(f, arc[0], arc[1], false, SAMPLES / 2, 1);
    neck = std::max(neck, (low.value - radius) / length);
  }
  contacts[1] = contact_at(e, f, center, radius, peaks[1]);
  return 2;
}

}    // namespace EllipsoidDep
