/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: ellipsoid inside a cone (see ellipsoid_cone_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_cone_contact.h"

#include "ellipsoid_interval_search.h"

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

  // the two best discrete maxima of the samples refined
  const IntervalMinimum best =
      minimise_on_interval(NegatedCone{f}, 0.0, 2.0 * PI, true, SAMPLES, 2);
  const double deepest = -best.value;

  const Vec3 w = f.w(best.x);
  const double length = w.norm();
  const Vec3 normal = w / length;
  const Vec3 mn = e.inverse_form * normal;
  const Vec3 p = e.center + mn / std::sqrt(normal.dot(mn));    // support point along normal
  g.normal = normal;
  g.overlap = (deepest - radius) / length;
  g.point_a = p;
  g.point_b = p - g.overlap * normal;
  g.point = 0.5 * (g.point_a + g.point_b);
  const double local_radius = radius + slope * u.dot(g.point_b - center);
  g.effective_radius = wall_effective_radius(gaussian_radius(e, normal), -2.0 * local_radius);
  g.status = surface_status(best.converged, g.overlap);
  return g;
}

}    // namespace EllipsoidDep
