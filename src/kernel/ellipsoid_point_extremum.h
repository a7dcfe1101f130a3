/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: the farthest and the nearest point of an ellipse or ellipsoid surface
   from a point, the curved walls' common problem (a sphere wall: the ellipsoid in 3-D; a
   cylinder wall: the ellipsoid's projection on the plane normal to the axis, in 2-D).

   In the principal frame of the surface sum_k y_k^2 / A_k = 1 (A_k the squared semi-axes), the
   stationary points of |y - x|^2 are y_k = A_k x_k / (A_k + t), with t a root of the secular
   equation F(t) = sum_k A_k x_k^2 / (A_k + t)^2 = 1. F is monotone on each interval below:
   - farthest point: the root in (-A_max - sqrt(A_max) |x|, -A_max);
   - nearest point of a surface that x lies outside of: the root in (0, sqrt(A_max) |x|);
     of one that x lies inside of: the root in (-A_min, 0].
   Both are found by Newton's method kept inside a shrinking bracket (bisection when a step
   leaves it); the cap on iterations is reported (converged = false), never hidden.
   The farthest point's "hard case" (x has no component along the largest axes, e.g. a centre
   on the ellipsoid's mid-plane) has t = -A_max and is handled in closed form; so has the
   nearest point's from inside (no component along the smallest axes: t = -A_min).
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_POINT_EXTREMUM_H
#define ELLIPSOID_DEP_ELLIPSOID_POINT_EXTREMUM_H

#include <Eigen/Dense>

#include <vector>

namespace EllipsoidDep {

template <int N> struct SurfaceExtremum {
  Eigen::Matrix<double, N, 1> point;    // y on the surface, principal frame
  double distance = 0.0;                // |y - x|
  bool converged = true;
};

// A stationary point of |y - x| on the surface: its point, distance, whether it is a local
// maximum (on the tangent plane the Lagrangian's Hessian diag(1 + t/A_k) is negative).
template <int N> struct StationaryPoint {
  Eigen::Matrix<double, N, 1> point;
  double distance = 0.0;
  bool maximum = false;
  bool converged = true;
};

// Every stationary point: F's roots on each interval between its poles (outside the outer
// poles one each; between two poles F is convex: none or two, around its lowest point, found
// by bisection on F'), and the hard cases' points (x without a component along the axes of a
// squared semi-axis A: t = -A, the free components closing the surface; a circle of them is
// given by two of its points).
template <int N>
std::vector<StationaryPoint<N>> stationary_surface_points(
    const Eigen::Matrix<double, N, 1> &squared_axes, const Eigen::Matrix<double, N, 1> &x);

// squared_axes: A_k > 0; x: the point in the principal frame.
template <int N>
SurfaceExtremum<N> farthest_surface_point(const Eigen::Matrix<double, N, 1> &squared_axes,
                                          const Eigen::Matrix<double, N, 1> &x);
// x outside the surface (sum x_k^2 / A_k > 1) or inside it.
template <int N>
SurfaceExtremum<N> nearest_surface_point(const Eigen::Matrix<double, N, 1> &squared_axes,
                                         const Eigen::Matrix<double, N, 1> &x);

}    // namespace EllipsoidDep

#endif
