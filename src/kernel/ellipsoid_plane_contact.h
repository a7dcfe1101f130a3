/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: contact of an ellipsoid with a flat wall.

   Conventions
   - The wall is the solid half-space {x : n.x <= offset}; its unit normal n points into the
     particle region (away from the wall material). The ellipsoid is body A, the wall body B.
   - The result's normal points from the particle into the wall (-n); overlap > 0 when the
     ellipsoid dips below the plane, by the depth of its lowest point p = c - M n / h(n);
     point_a = p, point_b = its projection on the plane, R* = the Gaussian radius at p (the
     plane's radius is infinite).

   Degenerate cases
   - Invalid ellipsoid, non-finite or zero wall normal, non-finite offset: Degenerate.
   - A wall normal of any length is normalised.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_PLANE_CONTACT_H
#define ELLIPSOID_DEP_ELLIPSOID_PLANE_CONTACT_H

#include "ellipsoid_contact.h"

namespace EllipsoidDep {

ContactGeometry ellipsoid_plane_contact(const Ellipsoid &e, const Vec3 &wall_normal,
                                        double wall_offset);

}    // namespace EllipsoidDep

#endif
