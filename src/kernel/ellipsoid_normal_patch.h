/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: the overlap of an ellipsoid with a convex solid (a block, a capped
   cylinder) along a direction, and its minimum over a patch of directions: the common part of
   the walls that a particle meets from outside (ellipsoid_box_contact.h,
   ellipsoid_capped_cylinder_contact.h).

   Along a unit direction n pointing from the solid B to the particle E (centre c, inverse
   form M), the two bodies' extents overlap by the separating-axis overlap
       delta(n) = h_B(n) - min_{x in E} n.x = h_B(n) + sqrt(n^T M n) - n.c,
   h_B(n) = max_{x in B} n.x the solid's support function. delta(n) <= 0 for some n proves
   the bodies disjoint; otherwise the smallest delta is the penetration depth (the shortest
   translation of the particle, along its minimiser n*, that separates them: the distance of c
   to the boundary of B + (E - c)). The contact normal is -n* (from the particle into the
   wall) and the particle's deepest point its support point along -n*.

   The sphere of directions splits into the normal cones of B's features: a face's normal, an
   arc for an edge, a spherical triangle for a corner, a quarter circle of tilts per rim angle
   for a rim. Over one cone h_B(n) = n.p + r sin(psi), p a point of the feature, r a rim's
   radius, so delta is smooth there. A NormalPatch parametrises such a cone:
       n(phi, psi) = cos(psi) a + sin(psi) (cos(phi) e1 + sin(phi) e2)     (a, e1, e2 orthonormal)
       f(phi, psi) = sqrt(n^T M n) + n.(p - c) + r sin(psi)
   (an edge or a cylinder's side: psi = pi/2, one parameter; a corner: phi, psi in [0, pi/2];
   a rim: phi around the circle, psi from the cap's normal (0) to the side's (pi/2)). The
   smallest delta over the sphere is the smallest of the features' minima over their closed
   cones: a value at any direction of a cone is delta there, so a candidate never undercuts
   the true minimum, and the minimiser lies inside some feature's cone, where that feature's
   search finds it.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_NORMAL_PATCH_H
#define ELLIPSOID_DEP_ELLIPSOID_NORMAL_PATCH_H

#include "ellipsoid_contact.h"
#include "ellipsoid_interval_search.h"

namespace EllipsoidDep {

struct NormalPatch {
  const Mat3 &m;    // the particle's inverse form
  Vec3 a, e1, e2;
  Vec3 d;               // the feature's point minus the particle's centre
  double rim_radius;    // r: 0 but for a cylinder's rim or side

  Vec3 normal(double phi, double psi) const;
  double value(double phi, double psi) const;
  // the same at a unit direction n of the cone: sqrt(n^T M n) + n.d + r |n - (n.a) a|
  double overlap(const Vec3 &n) const;
};

// the patch at psi = pi/2 as a function of phi (an edge, a cylinder's side), for
// minimise_on_interval
struct NormalArc {
  const NormalPatch &patch;
  double value(double phi) const { return patch.value(phi, 0.5 * PI); }
  void derivatives(double phi, double &df, double &ddf) const;
};

struct PatchMinimum {
  Vec3 n = Vec3::Zero();
  double value = HUGE_VAL;
  bool converged = false;
};

// The smallest f over phi in [0, phi_span] (2 pi: the whole circle, a rim; pi/2: a corner's
// octant) and psi in [0, pi/2]: a grid of phi_samples x psi_samples cell centres, each
// discrete minimum refined by Newton's method on the sphere (charts of angles have a pole
// at psi = 0), kept inside the cone: a refinement that reaches the cone's edge goes on
// along it, and one that reaches its corner stops there (a value of delta; that corner's own
// feature holds its minimum); one that does not settle is reported (converged = false).
PatchMinimum minimise_on_patch(const NormalPatch &patch, double phi_span, int phi_samples,
                               int psi_samples);

// The contact geometry of the minimiser: n from the solid to the particle, the overlap
// delta(n), the solid's contact radius there (0: flat, LAMMPS's convention) and whether the
// search converged.
ContactGeometry solid_contact(const Ellipsoid &e, const Vec3 &n, double overlap, double wall_radius,
                              bool converged);

}    // namespace EllipsoidDep

#endif
