/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: contact of an ellipsoid with the lateral surface of an infinite
   circular cylinder (a point on its axis, the unit axis u, radius R).

   The problem lives in the plane normal to u: the ellipsoid projects onto an ellipse (the
   2x2 form B^T M B of the projection, B an orthonormal basis normal to u) and the axis onto a
   point x. The ellipse point farthest from (inside) or nearest to (outside) x solves the
   2-D secular equation (ellipsoid_point_extremum.h); the radial direction m through it
   (normal to u, outwards inside, towards the axis outside) is the wall's normal, and the
   ellipsoid's deepest point is its support point along m (its projection is that ellipse
   point).

   Conventions (those of ellipsoid_wall_contact.h)
   - inside: the particle is in the cylinder, the solid outside it; overlap = |p_perp| - R,
     normal = m (outwards), the wall's contact radius -2R (LAMMPS's region cylinder).
   - outside: the solid is the cylinder; overlap = R - distance, normal towards the axis,
     the wall's contact radius 2R.
   - point_a = p (3-D), point_b = p moved radially onto the surface; R* by
     wall_effective_radius.

   Degenerate cases
   - Invalid ellipsoid, non-finite or zero axis, R <= 0: Degenerate.
   - outside, with the axis through the ellipsoid's projection: Degenerate.
   - the secular equation's iteration cap: NotConverged, with the last iterate's geometry.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_CYLINDER_CONTACT_H
#define ELLIPSOID_DEP_ELLIPSOID_CYLINDER_CONTACT_H

#include "ellipsoid_contact.h"

namespace EllipsoidDep {

ContactGeometry ellipsoid_cylinder_contact(const Ellipsoid &e, const Vec3 &axis_point,
                                           const Vec3 &axis, double radius, bool inside);

}    // namespace EllipsoidDep

#endif
