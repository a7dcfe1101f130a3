/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: contact geometry of two general (triaxial) ellipsoids, and the result
   types every query shares (Status, ContactSettings, ContactGeometry).

   Engine independent: C++17 + Eigen only. No LAMMPS header, no MPI, no I/O, no exceptions.

   Conventions
   - A is the first body, B the second; every normal points from A towards B.
   - The contact is the minimiser n* of the gap function d(n) (ellipsoid_gap.h) reached from
     the start direction: overlap = d(n*) (> 0 in contact, minus the distance when disjoint),
     point_a = s_A(n*), point_b = s_B(-n*), point = (point_a + point_b) / 2, and
     R* = effective_radius(A, B, n*). At n* both surface normals are +-n* and the two support
     points lie on a common normal line: the "exact" contact that the paper's correction step
     approximates and converges to.

   Degenerate cases
   - Either body invalid (ellipsoid_shape.h), or a non-finite result: status Degenerate, the
     rest of the geometry zero.
   - Both spheres: closed form; coincident centres give n = +z (any direction is a minimiser).
   - Coincident centres of non-spheres: the cold start uses the thinnest axis of A.
   - Iteration cap reached with d > 0: NotConverged, the geometry of the last iterate (used by
     the callers, and counted). d <= 0 proves separation whatever the cap: Separated.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_CONTACT_H
#define ELLIPSOID_DEP_ELLIPSOID_CONTACT_H

#include "ellipsoid_shape.h"

namespace EllipsoidDep {

// Knobs that trade speed for accuracy; pair_style keywords map onto these.
struct ContactSettings {
  double tolerance = 1e-12;         // relative convergence of the contact iteration
  int max_iterations = 50;          // per contact evaluation
  double correction_angle = 0.0;    // radians; correct the Perram-type vector when it deviates
                                    // from the surface gradients by more than this (0: always)
  double wang_band = 1e-9;          // relative band around a double root: "touching" (see
                                    // ellipsoid_wang.h)
};

enum class Status {
  Separated = 0,       // disjoint; a separating plane is returned
  Touching = 1,        // inside the tangency band of the Wang test; resolved by the iteration
  Overlapping = 2,     // contact geometry is valid
  NotConverged = 3,    // iteration cap reached; geometry holds the last iterate, flagged
  Degenerate = 4       // input cannot be handled (non-finite, zero axis); nothing computed
};

// The status of a wall contact found by an iteration: its overlap decides, unless the
// iteration stopped at its cap.
inline Status surface_status(bool converged, double overlap)
{
  if (!converged) return Status::NotConverged;
  return overlap > 0.0 ? Status::Overlapping : Status::Separated;
}

// Geometry the force laws need. normal points from A to B.
struct ContactGeometry {
  Status status = Status::Separated;
  int iterations = 0;        // Lagrange + correction iterations used
  bool corrected = false;    // the normal-correcting step was applied
  Vec3 normal = Vec3::Zero();
  double overlap = 0.0;             // length of the contact vector xi (> 0 when overlapping)
  Vec3 point = Vec3::Zero();        // contact point X_c (box coordinates)
  Vec3 point_a = Vec3::Zero();      // surface point of A deepest in B
  Vec3 point_b = Vec3::Zero();      // surface point of B deepest in A
  double effective_radius = 0.0;    // R* = RA RB / (RA + RB), Gaussian-curvature radii at +-n
};

// Contact of two ellipsoids whose Wang test (or bounding test) says they may overlap.
// warm_normal: the previous step's normal (A to B) or a cached plane normal; null = cold start.
// Returns status Separated (with overlap <= 0 and the distance as -overlap) when they do not
// overlap after all, Overlapping with the geometry, or NotConverged with the count.
ContactGeometry ellipsoid_contact(const Ellipsoid &a, const Ellipsoid &b,
                                  const ContactSettings &settings,
                                  const Vec3 *warm_normal = nullptr);

// ellipsoid_contact for two bodies that valid() accepts and that are not both spheres, without
// those checks, for callers that made them (evaluate_pair).
ContactGeometry valid_ellipsoid_contact(const Ellipsoid &a, const Ellipsoid &b,
                                        const ContactSettings &settings, const Vec3 *warm_normal);

// Closed-form sphere-sphere contact (used automatically when both are spheres).
ContactGeometry sphere_contact(const Ellipsoid &a, const Ellipsoid &b);
// sphere_contact of two spheres that valid() accepts, without those checks, for callers that
// made them and have dc = c_B - c_A and dist = |dc| (as bounding_test computes them)
ContactGeometry valid_sphere_contact(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc,
                                     double dist);

}    // namespace EllipsoidDep

#endif
