/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: contact of an ellipsoid outside a solid box (a block region with side
   out): its faces, edges and corners.

   The box is {x : lower <= F^T (x - center) <= upper}, F an orthonormal frame (columns: the
   box's edge directions); a bound at +-infinity is no face (the box runs on that way).
   The contact is the smallest separating-axis overlap over the directions
   (ellipsoid_normal_patch.h), taken feature by feature over their normal cones:
   - a face: its outward normal, one value;
   - an edge (two faces of different axes): the quarter arc of normals between the faces',
     a one-parameter search (ellipsoid_interval_search.h);
   - a corner (three faces): the octant of normals, a two-parameter search.
   An edge or a corner farther from the centre c than the largest semi-axis plus the larger of
   the smallest overlap found so far and the distance of c from the box cannot hold the
   minimum, and is skipped: in contact, the solid's point of the contact lies within the
   semi-axis plus the overlap of c; apart, the solid's point nearest the particle lies within
   the semi-axis plus their distance, at most c's. An overlap <= 0 separates the bodies.

   Conventions (those of ellipsoid_wall_contact.h)
   - the normal points from the particle into the box, the overlap the penetration depth,
     point_a the particle's deepest point, point_b on the box's supporting plane (the face's
     point, or the edge's or the corner's point itself at the minimum).
   - the box's contact radius is flat at faces, edges and corners alike, as LAMMPS's region
     block from outside (a sharp edge has no Hertz radius of its own): R* is the particle's
     Gaussian radius at the contact.

   Degenerate cases
   - Invalid ellipsoid, non-finite centre or frame, a bound NaN, lower > upper, no finite bound:
     Degenerate.
   - a search that does not settle: NotConverged with its geometry (counted by the caller).
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_BOX_CONTACT_H
#define ELLIPSOID_DEP_ELLIPSOID_BOX_CONTACT_H

#include "ellipsoid_contact.h"

namespace EllipsoidDep {

ContactGeometry ellipsoid_box_contact(const Ellipsoid &e, const Vec3 &center, const Mat3 &frame,
                                      const Vec3 &lower, const Vec3 &upper);

// the distance of x from the box, or minus its depth inside
double box_clearance(const Vec3 &center, const Mat3 &frame, const Vec3 &lower, const Vec3 &upper,
                     const Vec3 &x);

}    // namespace EllipsoidDep

#endif
