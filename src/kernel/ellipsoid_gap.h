/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: the gap function of two ellipsoids, its minimiser over the unit
   sphere and the cold start of that minimisation. Used by the contact (ellipsoid_contact.h)
   and by the separating-plane construction (ellipsoid_wang.h); callers outside the kernel
   use those two.

   Conventions
   - dc = c_B - c_A. For a unit direction n from A towards B the signed penetration depth is
       d(n) = sqrt(n^T M_A n) + sqrt(n^T M_B n) - n.dc,
     the support function of the Minkowski difference A - B. Its minimum over unit n is the
     penetration depth when the bodies overlap and minus their distance when they are
     disjoint (separating axis theorem); any n with d(n) < 0 proves separation.
   - The gradient of the degree-1 extension of d is p_A - p_B (the two support points).

   Degenerate cases
   - n^T M n is floored at the smallest normal double, so d and its gradient stay finite for
     any finite input; callers check validity of the bodies first.
   - A start that is already stationary may be a saddle (symmetric configurations): the
     minimiser checks the curvature there and leaves along the negative-curvature direction.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_GAP_H
#define ELLIPSOID_DEP_ELLIPSOID_GAP_H

#include "ellipsoid_shape.h"

#include <limits>

namespace EllipsoidDep {

// The gap function and what it is made of, at one unit n.
struct GapEval {
  double ha, hb, d;    // sqrt(n^T M_A n), sqrt(n^T M_B n), d(n)
  Vec3 ua, ub;         // M_A n / h_A = s_A(n) - c_A, M_B n / h_B = c_B - s_B(-n)
  Vec3 grad;           // gradient of the degree-1 extension = p_A - p_B
};

inline GapEval evaluate_gap(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc, const Vec3 &n)
{
  GapEval e;
  const Vec3 man = a.inverse_form * n, mbn = b.inverse_form * n;
  e.ha = std::sqrt(std::max(n.dot(man), std::numeric_limits<double>::min()));
  e.hb = std::sqrt(std::max(n.dot(mbn), std::numeric_limits<double>::min()));
  e.ua = man / e.ha;
  e.ub = mbn / e.hb;
  e.grad = e.ua + e.ub - dc;
  e.d = e.ha + e.hb - n.dot(dc);
  return e;
}

// Result of the minimisation of d over the unit sphere.
struct GapMinimum {
  Vec3 n;
  GapEval ev;
  int iterations;
  bool converged;
};

// Safeguarded Riemannian Newton on d from the unit start n; converged when the tangential
// gradient is below max(tol * smallest semi-axis, round-off floor).
GapMinimum minimise_gap(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc, Vec3 n, double tol,
                        int max_iter);

// Start direction (A to B) of the iteration and the Perram-type estimate.
struct ColdStart {
  Vec3 n;
  int iterations;    // Lagrange iterations spent
  bool perram;       // the Perram points are valid
  Vec3 xa, xb;       // X_m^(B) (on A, deepest in B) and X_m^(A) (on B, deepest in A)
};

ColdStart cold_start(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc);

}    // namespace EllipsoidDep

#endif
