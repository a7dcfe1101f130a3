/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: ellipsoid-wall contact (see ellipsoid_plane_contact.h).
------------------------------------------------------------------------- */

#include "ellipsoid_plane_contact.h"

namespace EllipsoidDep {

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

}    // namespace EllipsoidDep
