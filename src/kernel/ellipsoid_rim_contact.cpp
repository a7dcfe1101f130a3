/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: ellipsoid against a rim (see ellipsoid_rim_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_rim_contact.h"

#include "ellipsoid_interval_search.h"
#include "ellipsoid_point_extremum.h"

namespace EllipsoidDep {

namespace {

  constexpr int SAMPLES = 64;
  constexpr double DIFFERENCE_STEP = 1e-6;    // of D'' by a central difference

  // a point's nearest surface point p and outward normal there, its signed distance
  struct SurfaceFoot {
    Vec3 p, n;
    double signed_distance;
    bool converged;
  };

  SurfaceFoot foot(const Ellipsoid &e, const Vec3 &q)
  {
    const Vec3 a2 = e.semi_axes.cwiseProduct(e.semi_axes);
    const Vec3 x = e.rotation.transpose() * (q - e.center);
    const SurfaceExtremum<3> near = nearest_surface_point<3>(a2, x);
    const bool inside = x.cwiseProduct(x).cwiseQuotient(a2).sum() <= 1.0;
    return {e.center + e.rotation * near.point,
            e.rotation * near.point.cwiseQuotient(a2).normalized(),
            inside ? -near.distance : near.distance, near.converged};
  }

  // sd(q(theta)) along the rim, minimised (the rim's deepest point)
  struct RimDistance {
    const Ellipsoid &e;
    Vec3 k, e1, e2;
    double rho;

    Vec3 q(double theta) const { return k + rho * (std::cos(theta) * e1 + std::sin(theta) * e2); }
    double value(double theta) const { return foot(e, q(theta)).signed_distance; }
    double slope(double theta) const
    {
      const Vec3 dq = rho * (-std::sin(theta) * e1 + std::cos(theta) * e2);
      return foot(e, q(theta)).n.dot(dq);
    }
    void derivatives(double theta, double &df, double &ddf) const
    {
      df = slope(theta);
      ddf = (slope(theta + DIFFERENCE_STEP) - slope(theta - DIFFERENCE_STEP)) /
          (2.0 * DIFFERENCE_STEP);
    }
  };

}    // namespace

ContactGeometry ellipsoid_rim_contact(const Ellipsoid &e, const Vec3 &rim_center, const Vec3 &axis,
                                      double rim_radius, double wall_radius)
{
  ContactGeometry g;
  g.status = Status::Degenerate;
  if (!valid(e) || !finite3(rim_center) || !finite3(axis) || !(axis.norm() > 0.0) ||
      !(rim_radius >= 0.0) || !std::isfinite(rim_radius))
    return g;
  const Vec3 u = axis.normalized();
  const Vec3 e1 = u.unitOrthogonal();
  const RimDistance rim{e, rim_center, e1, u.cross(e1), rim_radius};
  Vec3 q = rim_center;
  bool converged = true;
  if (rim_radius > 0.0) {
    const IntervalMinimum best = minimise_on_interval(rim, 0.0, 2.0 * PI, true, SAMPLES, 2);
    q = rim.q(best.x);
    converged = best.converged;
  }
  const SurfaceFoot f = foot(e, q);
  g.normal = f.n;
  g.overlap = -f.signed_distance;
  g.point_a = f.p;
  g.point_b = q;
  g.point = 0.5 * (g.point_a + g.point_b);
  g.effective_radius = wall_effective_radius(gaussian_radius(e, g.normal), wall_radius);
  // no rim point found inside the particle: no contact, whether the refinement settled or not
  g.status = surface_status((converged && f.converged) || g.overlap <= 0.0, g.overlap);
  return g;
}

}    // namespace EllipsoidDep
