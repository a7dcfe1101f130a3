/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: contact of an ellipsoid inside a circular cone (a hopper): the
   lateral surface rho = radius + slope * s about the axis through `center` along the unit
   `axis`, s the axial coordinate from center; the solid lies outside (rho > radius + slope s).

   The depth of a point p beyond the surface, measured normal to it, is
   (rho(p) - radius - slope s(p)) cos(alpha), tan(alpha) = slope. rho(p) = max over unit m
   normal to the axis of m.(p - center), so the ellipsoid's largest depth is the largest of
       f(phi) = h(w) + w.(c - center),   w(phi) = m(phi) - slope axis,
   h(w) = sqrt(w^T M w) the support function, over the angle phi of m: a one-parameter
   maximisation. It is sampled at 64 angles; the two best discrete maxima are refined by
   golden-section search and finished by Newton's method on f'(phi) = 0 (analytic f', f'';
   ellipsoid_interval_search.h, on -f);
   a Newton iteration that does not settle is reported (NotConverged), never dropped.
   The wall's normal is w / |w| at the maximum (outwards and along -slope axis), the deepest
   point the support point along it, overlap = (f - radius) / |w|.

   Conventions (those of ellipsoid_wall_contact.h)
   - the wall's contact radius is LAMMPS's region cone's, -2 rho at the wall's point of the
     contact (point_b); R* by wall_effective_radius.
   - the surface is the infinite cone: near its apex (closer than a particle) the depth above
     is not the distance to the surface (a hopper's apex lies beyond its outlet); a finite
     side ends at its rims (ellipsoid_rim_contact.h, the wall seam's finite side).

   Degenerate cases
   - Invalid ellipsoid, non-finite or zero axis, radius <= 0, non-finite slope: Degenerate.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_CONE_CONTACT_H
#define ELLIPSOID_DEP_ELLIPSOID_CONE_CONTACT_H

#include "ellipsoid_contact.h"

namespace EllipsoidDep {

ContactGeometry ellipsoid_cone_contact(const Ellipsoid &e, const Vec3 &center, const Vec3 &axis,
                                       double radius, double slope);

// A particle may reach beyond a concave side in separate places (a rod across a pipe touches
// both sides): the profile f(phi) above has a second maximum. With two maxima (the two best
// discrete maxima of the 64 samples, refined, apart by more than a sample) this gives both
// contacts, the deeper first, and the neck between them (the higher of the profile's lowest
// values on the two arcs between the maxima, each a closed-interval search of 32 samples, as
// a depth) and returns 2; with one maximum its contact (ellipsoid_cone_contact's) and 1; 0
// for unusable input. A cylinder's side is the cone of slope 0.
int concave_side_contacts(const Ellipsoid &e, const Vec3 &center, const Vec3 &axis, double radius,
                          double slope, ContactGeometry contacts[2], double &neck);

}    // namespace EllipsoidDep

#endif
