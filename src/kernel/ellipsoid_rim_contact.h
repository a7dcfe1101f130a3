/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: the finite side of a cylinder or cone met from inside, and the rims
   where it ends (LAMMPS's region cylinder and cone: the side is the segment between the
   caps, open or closed, and a particle near an end meets the rim there).

   A rim is a circle (centre k, unit axis u, radius rho): a sharp edge with no thickness. Its
   depth in the particle is that of its deepest point,
       D = max over the circle's points q of  -sd(q),
   sd(q) the signed distance of q from the ellipsoid's surface (negative inside; the nearest
   surface point from the secular equation, ellipsoid_point_extremum.h). D(theta) along the
   circle is sampled at 64 angles, the best discrete maxima refined by golden section and
   Newton's method on D'(theta) = -n.q'(theta) (n the surface's outward normal at the nearest
   point; D'' by a central difference of D'), ellipsoid_interval_search.h. The contact:
   normal n (from the particle towards the rim), overlap D, point_a the particle's nearest
   surface point p, point_b = q. For a sphere this is LAMMPS's contact with the end of the
   side's segment: the rim point nearest to the centre, overlap r - |c - q|.

   The finite side (ellipsoid_wall_contact.cpp): the contact with the infinite side
   (ellipsoid_cylinder_contact.h, ellipsoid_cone_contact.h) holds while the wall's point of it (point_b, the foot of the
   deepest point) lies between the ends; beyond an end the particle meets that end's rim
   instead (a sphere: LAMMPS's clamp of the nearest point to the segment), and a particle
   whose centre lies beyond an end (it left through an open face) meets only that rim. Where
   the foot crosses an end the two agree to first order in the overlap (the rim lies on the
   side and the particle is more curved than the side there), exactly for a sphere.

   Conventions (those of ellipsoid_wall_contact.h): the rim's wall contact radius is given by
   the caller (LAMMPS's convention: the side's radius at the end, -2 rho, for a particle
   inside; from beyond the end a cylinder's 0 or 2R as LAMMPS's surface_exterior).

   Degenerate cases: as the side's; a rim of radius 0 (a cone's apex as an end) is its one
   point.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_RIM_CONTACT_H
#define ELLIPSOID_DEP_ELLIPSOID_RIM_CONTACT_H

#include "ellipsoid_contact.h"

namespace EllipsoidDep {

ContactGeometry ellipsoid_rim_contact(const Ellipsoid &e, const Vec3 &rim_center, const Vec3 &axis,
                                      double rim_radius, double wall_radius);

}    // namespace EllipsoidDep

#endif
