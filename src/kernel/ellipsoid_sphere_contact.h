/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: contact of an ellipsoid with a spherical wall (centre s, radius R).

   Conventions (those of ellipsoid_wall_contact.h)
   - inside: the particle is in the ball, the solid outside it. The deepest point of the
     ellipsoid beyond the surface is its farthest point p from s (ellipsoid_point_extremum.h):
     overlap = |p - s| - R, normal = (p - s) / |p - s|, the wall's contact radius -R.
   - outside: the solid is the ball. The deepest point is the ellipsoid's nearest point p to s:
     overlap = R - |p - s|, normal = (s - p) / |s - p|, the wall's contact radius +R.
   - point_a = p, point_b = the point of the sphere on the line through s and p; R* from the
     particle's Gaussian radius at p and the wall's contact radius (wall_effective_radius).

   Degenerate cases
   - Invalid ellipsoid, non-finite centre, R <= 0: Degenerate.
   - outside, with s inside the ellipsoid (the particle has swallowed the ball's centre):
     Degenerate (no normal is defined).
   - the secular equation's iteration cap: NotConverged, with the last iterate's geometry.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_SPHERE_CONTACT_H
#define ELLIPSOID_DEP_ELLIPSOID_SPHERE_CONTACT_H

#include "ellipsoid_contact.h"

namespace EllipsoidDep {

ContactGeometry ellipsoid_sphere_contact(const Ellipsoid &e, const Vec3 &center, double radius,
                                         bool inside);

// Inside, a particle may reach beyond the sphere in two places (a rod longer than the bowl is
// wide): |p - s| has a second local maximum on the ellipsoid (at most two: one multiplier t
// below -A_max, the other between -A_max and -A_mid). From every stationary point of the
// secular equation (ellipsoid_point_extremum.h, stationary_surface_points) this gives both
// maxima's contacts, the deeper first, and the neck between them: the highest stationary
// value that is neither a maximum nor the lowest (the saddles between the maxima), as a
// depth; returns 2, or 0 with one maximum (ellipsoid_sphere_contact's).
int sphere_inside_contacts(const Ellipsoid &e, const Vec3 &center, double radius,
                           ContactGeometry contacts[2], double &neck);

}    // namespace EllipsoidDep

#endif
