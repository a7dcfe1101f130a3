/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: contact geometry of two general (triaxial) ellipsoids.

   Engine independent: C++17 + Eigen only. No LAMMPS header, no MPI, no I/O,
   no exceptions. LAMMPS styles, the LIGGGHTS adapter, tests and benchmarks
   all call these functions.

   Conventions
   - An ellipsoid is {x : (x-c)^T Q (x-c) <= 1}, Q = R diag(1/a^2,1/b^2,1/c^2) R^T,
     R the body-to-box rotation (columns = body axes), semi-axes in any order.
   - M = Q^-1 = R diag(a^2,b^2,c^2) R^T gives the support function
     h(n) = n.c + sqrt(n^T M n) and the support point s(n) = c + M n / sqrt(n^T M n).
   - The signed penetration depth of A and B along a unit direction n (from A
     towards B) is  d(n) = sqrt(n^T M_A n) + sqrt(n^T M_B n) - n.(c_B - c_A).
     Its minimum over unit n is the penetration depth when the bodies overlap
     and minus their distance when they are disjoint (separating axis theorem).
     At the minimiser both surface normals are +-n and the support points lie
     on a common normal line: this is the "exact" contact the paper's
     correction step approximates, and what the correction converges to.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_CONTACT_H
#define ELLIPSOID_DEP_ELLIPSOID_CONTACT_H

#include <Eigen/Dense>

namespace EllipsoidDep {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;

struct Ellipsoid {
  Vec3 center;
  Mat3 rotation;             // body -> box; columns are the body axes in box coordinates
  Vec3 semi_axes;            // along the body axes, any order, all > 0
  Mat3 form;                 // Q = R diag(1/a^2) R^T  (the paper's A)
  Mat3 inverse_form;         // M = R diag(a^2) R^T  (support function)
  double bounding_radius;    // largest semi-axis
  bool sphere;               // all semi-axes equal to round-off: closed-form path
  bool finite = false;       // every entry finite and semi-axes > 0 (checked once, here)

  // the paper's 4x4 homogeneous matrix: X^T H X = 0 on the surface, X = (x,1)
  Mat4 homogeneous() const;
  double volume() const;
};

// quaternion (w, x, y, z), unit; semi-axes (a, b, c) along body x, y, z
Ellipsoid make_ellipsoid(const Vec3 &center, const double quat[4], const Vec3 &semi_axes);
Ellipsoid make_ellipsoid(const Vec3 &center, const Mat3 &rotation, const Vec3 &semi_axes);

// Knobs that trade speed for accuracy; pair_style keywords map onto these.
struct ContactSettings {
  double tolerance = 1e-12;         // relative convergence of the contact iteration
  int max_iterations = 50;          // per contact evaluation
  double correction_angle = 0.0;    // radians; correct the Perram-type vector when it deviates
                                    // from the surface gradients by more than this (0: always)
  double wang_band = 1e-9;          // relative band around a double root: "touching" (see .cpp)
};

enum class Status {
  Separated = 0,       // disjoint; a separating plane is returned
  Touching = 1,        // inside the tangency band of the Wang test; resolved by the iteration
  Overlapping = 2,     // contact geometry is valid
  NotConverged = 3,    // iteration cap reached; geometry holds the last iterate, flagged
  Degenerate = 4       // input cannot be handled (non-finite, zero axis); nothing computed
};

// Separating plane {x : n.x = offset}; A lies on the side n.x < offset, B on n.x > offset.
struct SeparatingPlane {
  Vec3 normal;    // unit, from A towards B
  double offset;
};

// Support-function test: true when A lies strictly below and B strictly above the plane.
bool plane_separates(const SeparatingPlane &plane, const Ellipsoid &a, const Ellipsoid &b);

// Wang et al. decision from the roots of det(nu*A + B) (4x4 homogeneous matrices).
struct WangResult {
  Status status;            // Separated, Touching or Overlapping (or Degenerate)
  SeparatingPlane plane;    // valid when Separated: built from the self-polar tetrahedron
};
WangResult wang_test(const Ellipsoid &a, const Ellipsoid &b, const ContactSettings &settings);

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

// Closed-form sphere-sphere contact (used automatically when both are spheres).
ContactGeometry sphere_contact(const Ellipsoid &a, const Ellipsoid &b);

// Ellipsoid against the half-space {x : n.x <= offset} being solid (a wall whose
// material is on the side opposite to n; n is the wall's unit normal pointing into
// the particle region). Overlap > 0 when the ellipsoid dips below the plane.
// normal in the result points from the particle into the wall (i.e. -n).
ContactGeometry ellipsoid_plane_contact(const Ellipsoid &e, const Vec3 &wall_normal,
                                        double wall_offset);

// Volume of an ellipsoid between the planes z = zlo and z = zhi (closed form).
double ellipsoid_slab_volume(const Ellipsoid &e, double zlo, double zhi);

// Gaussian-curvature radius sqrt(R1 R2) of the surface where its outer normal is n.
double gaussian_radius(const Ellipsoid &e, const Vec3 &unit_normal);

// ---------------------------------------------------------------------------
// The whole per-pair pipeline of the paper (Fig. 2), for callers that keep a
// small per-pair cache between steps: bounding spheres -> cached separating plane
// -> Wang test (disjoint: build and cache a plane) -> contact iteration warm-started
// from the cached normal -> normal correction.

struct PipelineSettings {
  ContactSettings contact;
  bool use_planes = true;    // cache separating planes of disjoint pairs
  bool use_wang = true;      // false: go straight to the contact iteration
};

// Per-pair cache, PAIR_CACHE_SIZE doubles. Every entry changes sign when A and B are
// swapped, so LAMMPS's default history transfer (negate on i/j flip) is exact:
//   [0]   state: |s| = 0 nothing cached, 1 separating plane, 2 contact normal
//   [1-3] unit normal from A to B (plane normal or last contact normal)
//   [4]   u: the plane passes through c_A + (1/2 + u)(c_B - c_A)
constexpr int PAIR_CACHE_SIZE = 5;

struct PipelineCounters {
  long long pairs = 0;               // pairs evaluated
  long long bounding_rejects = 0;    // bounding spheres disjoint
  long long plane_hits = 0;          // cached plane still separates
  long long wang_calls = 0;
  long long wang_separated = 0;    // Wang said disjoint (plane built)
  long long contacts = 0;          // overlapping results
  long long iterations = 0;        // summed over contact evaluations
  long long corrections = 0;       // normal-correcting step applied
  long long not_converged = 0;     // iteration cap reached (contact still used, flagged)
  long long degenerate = 0;
  long long continued = 0;    // contacts of the previous step re-evaluated without Wang
  void add(const PipelineCounters &o);
};

// Evaluates one pair; updates cache and counters. Returns Overlapping (or NotConverged, still
// with usable geometry) when there is a contact, else Separated.
ContactGeometry evaluate_pair(const Ellipsoid &a, const Ellipsoid &b,
                              const PipelineSettings &settings, double *cache,
                              PipelineCounters &counters);

// --- additions (kernel issue 3): the two halves of wang_test, for the pipeline and benchmarks.
// Decision only (no plane): Separated, Touching (inside wang_band), Overlapping or Degenerate.
Status wang_classify(const Ellipsoid &a, const Ellipsoid &b, const ContactSettings &settings);
// Proven separating plane (plane_separates() is true on success) from a loose minimisation of
// d(n), started at *start (A to B) when given; false when none is found to round-off.
bool build_separating_plane(const Ellipsoid &a, const Ellipsoid &b, SeparatingPlane &plane,
                            const Vec3 *start = nullptr);

}    // namespace EllipsoidDep

#endif
