/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: the Wang et al. (2004) separation test of two ellipsoids and the
   separating plane of a disjoint pair.

   Conventions
   - f(nu) = det(nu A + B) of the 4x4 homogeneous matrices (Ellipsoid::homogeneous). The
     bodies are disjoint iff f has two distinct positive roots; they touch externally at a
     positive double root; otherwise they overlap.
   - A separating plane {x : n.x = offset} has its unit normal from A towards B; A lies
     strictly on the side n.x < offset, B strictly on n.x > offset (checked with the
     support functions, plane_separates).

   Degenerate cases
   - An invalid body, a non-positive det Q or a non-finite quartic coefficient: Degenerate.
   - Roots closer than wang_band (relative, on the normalised Sturm chain) count as one
     double root: Touching, which callers resolve with the contact iteration.
   - Separated but no plane proven to round-off: wang_test reports Touching (callers fall
     through to the exact iteration), build_separating_plane returns false.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_WANG_H
#define ELLIPSOID_DEP_ELLIPSOID_WANG_H

#include "ellipsoid_contact.h"

namespace EllipsoidDep {

// Separating plane {x : n.x = offset}; A lies on the side n.x < offset, B on n.x > offset.
struct SeparatingPlane {
  Vec3 normal;    // unit, from A towards B
  double offset;
};

// Support-function test: true when A lies strictly below and B strictly above the plane.
// Any NaN makes it false.
inline bool plane_separates(const SeparatingPlane &plane, const Ellipsoid &a, const Ellipsoid &b)
{
  const Vec3 &n = plane.normal;
  const double top_a = n.dot(a.center) + std::sqrt(n.dot(a.inverse_form * n));
  const double bot_b = n.dot(b.center) - std::sqrt(n.dot(b.inverse_form * n));
  return top_a < plane.offset && bot_b > plane.offset;
}

// Decision only (no plane): Separated, Touching (inside wang_band), Overlapping or Degenerate.
Status wang_classify(const Ellipsoid &a, const Ellipsoid &b, const ContactSettings &settings);

// Proven separating plane (plane_separates() is true on success) from a loose minimisation of
// d(n), started at *start (A to B) when given; false when none is found to round-off.
bool build_separating_plane(const Ellipsoid &a, const Ellipsoid &b, SeparatingPlane &plane,
                            const Vec3 *start = nullptr);

// Both: the decision, and for Separated a proven plane.
struct WangResult {
  Status status;            // Separated, Touching or Overlapping (or Degenerate)
  SeparatingPlane plane;    // valid when Separated
};
WangResult wang_test(const Ellipsoid &a, const Ellipsoid &b, const ContactSettings &settings);

}    // namespace EllipsoidDep

#endif
