/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: contact of an ellipsoid outside a solid capped cylinder (a cylinder
   region with side out whose caps lie in the box: a finite post): its side, its caps (discs)
   and the caps' rims.

   The solid is {x : |x_perp| <= R, cap_lo <= s <= cap_hi}, s = u.(x - axis_point) along the
   unit axis u and x_perp the part of x - axis_point normal to it; a cap at +-infinity is none.
   The contact is the smallest separating-axis overlap over the directions
   (ellipsoid_normal_patch.h), taken feature by feature over their normal cones:
   - the side: the radial directions, the outside cylinder's contact
     (ellipsoid_cylinder_contact.h; when the axis crosses the particle's projection, the
     one-parameter search over the circle of radial directions instead);
   - a cap: its axial normal, one value;
   - a rim: the directions between the cap's normal and the side's radial ones, tilt psi in
     [0, pi/2] at each rim angle phi, a two-parameter search.
   A rim farther from the centre than the largest semi-axis plus the larger of the smallest
   overlap of the side and the caps and the centre's distance from the solid cannot hold the
   minimum and is skipped (the argument of ellipsoid_box_contact.h).

   Conventions (those of ellipsoid_wall_contact.h)
   - the normal points from the particle into the post, the overlap the penetration depth,
     point_a the particle's deepest point, point_b on the post's supporting plane.
   - the wall's contact radius is LAMMPS's region cylinder's from outside: 2R at the side and
     at a rim (LAMMPS takes 2R wherever the centre is radially outside the cylinder, which a
     sphere touching a rim is), flat at a cap. A rim is sharp and has no Hertz radius of its
     own; this keeps the stiffness finite and equal to LAMMPS's in the sphere limit.

   Degenerate cases
   - Invalid ellipsoid, non-finite or zero axis, R <= 0, a NaN cap, cap_lo > cap_hi:
     Degenerate.
   - a search that does not settle: NotConverged with its geometry (counted by the caller).
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_CAPPED_CYLINDER_CONTACT_H
#define ELLIPSOID_DEP_ELLIPSOID_CAPPED_CYLINDER_CONTACT_H

#include "ellipsoid_contact.h"

namespace EllipsoidDep {

ContactGeometry ellipsoid_capped_cylinder_contact(const Ellipsoid &e, const Vec3 &axis_point,
                                                  const Vec3 &axis, double radius, double cap_lo,
                                                  double cap_hi);

// the distance of x from the capped cylinder, or minus its depth inside (unit axis)
double capped_cylinder_clearance(const Vec3 &axis_point, const Vec3 &axis, double radius,
                                 double cap_lo, double cap_hi, const Vec3 &x);

}    // namespace EllipsoidDep

#endif
