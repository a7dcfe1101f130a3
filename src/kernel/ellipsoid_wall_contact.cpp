/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: the wall shapes' dispatch (see ellipsoid_wall_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_wall_contact.h"

#include "ellipsoid_plane_contact.h"

namespace EllipsoidDep {

double wall_clearance(const WallSurface &w, const Vec3 &x)
{
  switch (w.shape) {
    case WallShape::Plane:
      return w.normal.dot(x) - w.offset;
  }
  return 0.0;
}

ContactGeometry wall_contact(const Ellipsoid &e, const WallSurface &w)
{
  switch (w.shape) {
    case WallShape::Plane:
      return ellipsoid_plane_contact(e, w.normal, w.offset);
  }
  ContactGeometry degenerate;
  degenerate.status = Status::Degenerate;
  return degenerate;
}

}    // namespace EllipsoidDep
