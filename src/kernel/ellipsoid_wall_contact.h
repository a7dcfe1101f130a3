/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: contact of an ellipsoid with a wall of any supported shape, the seam
   for new wall shapes. A wall is a WallSurface: its shape and the parameters of that shape;
   wall_clearance() and wall_contact() dispatch on the shape, one row per shape.

   Add a wall shape: its contact in a kernel file of its own (as ellipsoid_plane_contact.*),
   a WallShape entry with its parameters in WallSurface, and its row in
   shaped_wall_clearance() and wall_contact() (ellipsoid_wall_contact.cpp); the fix gives it
   a keyword.

   Conventions (every shape)
   - The ellipsoid is body A, the wall body B. The result's normal points from the particle
     into the wall, overlap > 0 in contact, R* from the curvatures at the contact point.
   - wall_clearance(w, x): the signed distance of point x from the surface, positive on the
     particle side (a centre past an end of a finite side: its distance from that end's
     rim). A particle whose bounding radius is below its centre's clearance cannot touch the
     wall.
   - wall_clear(e, w): the particle lies on the particle side, apart from the surface (a
     touching particle is not clear, as a pour's overlap test counts touching pairs). A new
     particle must be clear of every wall (fix pour/ellipsoid); an iteration that stopped at
     its cap proves nothing, so the particle is not clear.

   - R*: the particle's Gaussian radius at the contact and the wall's contact radius, LAMMPS's
     region convention (wall_effective_radius, ellipsoid_shape.h).

   Degenerate cases: those of the shape's contact (ellipsoid_plane_contact.h,
   ellipsoid_sphere_contact.h, ellipsoid_cylinder_contact.h, ellipsoid_cone_contact.h,
   ellipsoid_rim_contact.h, ellipsoid_box_contact.h, ellipsoid_capped_cylinder_contact.h).
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_WALL_CONTACT_H
#define ELLIPSOID_DEP_ELLIPSOID_WALL_CONTACT_H

#include "ellipsoid_contact.h"

namespace EllipsoidDep {

enum class WallShape {
  Plane,         // the solid half-space {x : normal.x <= offset}
  Sphere,        // the sphere |x - center| = radius; inside: particles in the ball
  Cylinder,      // the cylinder through center along axis; inside: particles in it
  Cone,          // particles inside rho = radius + slope s about center, axis (s along axis)
  Box            // the solid box lower <= frame^T (x - center) <= upper; particles outside
};

struct WallSurface {
  WallShape shape = WallShape::Plane;
  Vec3 normal = Vec3::UnitZ();    // Plane: unit, into the particle region
  double offset = 0.0;            // Plane: where the solid ends along normal
  Vec3 center = Vec3::Zero();     // Sphere: centre; Cylinder, Cone: a point of the axis
  Vec3 axis = Vec3::UnitZ();      // Cylinder, Cone: unit axis
  double radius = 0.0;            // Sphere, Cylinder; Cone: its radius at center
  double slope = 0.0;             // Cone: d rho / d s
  bool inside = true;             // Sphere, Cylinder: the particles' side
  // Cylinder, Cone: where the side ends along axis from center (infinite: nowhere). Met from
  // inside, the side between them and their rims (ellipsoid_rim_contact.h; the caps, when
  // closed, are faces of their own); a cylinder met from outside: the solid's caps
  double cap_lo = -INFINITY, cap_hi = INFINITY;
  // Box: its unit edge directions (columns) and its faces along them (infinite: none)
  Mat3 frame = Mat3::Identity();
  Vec3 lower = Vec3::Constant(-INFINITY), upper = Vec3::Constant(INFINITY);
};

// wall_clearance of the curved and bounded shapes (every shape but the plane)
double shaped_wall_clearance(const WallSurface &w, const Vec3 &x);
inline double wall_clearance(const WallSurface &w, const Vec3 &x)
{
  // a plane inline: the walls test every atom against it at every step
  return w.shape == WallShape::Plane ? w.normal.dot(x) - w.offset : shaped_wall_clearance(w, x);
}
// the deepest contact
ContactGeometry wall_contact(const Ellipsoid &e, const WallSurface &w);
// the same surface, every field equal (a field added to WallSurface belongs here too)
bool operator==(const WallSurface &a, const WallSurface &b);
inline bool operator!=(const WallSurface &a, const WallSurface &b) { return !(a == b); }

// Every separate contact region of the face: a cone's side and a cylinder's from inside (the
// cone of slope 0; ellipsoid_cone_contact.h, concave_side_contacts) and a sphere from inside
// (ellipsoid_sphere_contact.h, sphere_inside_contacts) may have two; a side's contact past
// an end becomes that end's rim's (one per end). Other faces: wall_contact's one.
constexpr int MAX_FACE_CONTACTS = 2;
struct FaceContacts {
  int count = 0;
  ContactGeometry contact[MAX_FACE_CONTACTS];
};
bool several_contacts(const WallSurface &w);
FaceContacts wall_contacts(const Ellipsoid &e, const WallSurface &w);

// Two contacts of one face whose regions join above the neck (neck > 0: the particle lies
// beyond the face all the way between them) share it: the shallower loses the neck's depth,
// the deeper the neck's depth times the ratio of their excesses over it. Apart (neck <= 0)
// both keep their depths. So a contact region that splits in two, a second maximum that
// appears or vanishes, or two maxima that swap order change the overlaps continuously.
void share_neck(ContactGeometry &deeper, ContactGeometry &other, double neck);

bool wall_clear(const Ellipsoid &e, const WallSurface &w);

}    // namespace EllipsoidDep

#endif
