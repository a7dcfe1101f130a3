/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: the ellipsoid itself.

   Engine independent: C++17 + Eigen only. No LAMMPS header, no MPI, no I/O, no exceptions.

   Conventions
   - An ellipsoid is {x : (x-c)^T Q (x-c) <= 1}, Q = R diag(1/a^2,1/b^2,1/c^2) R^T,
     R the body-to-box rotation (columns = body axes), semi-axes in any order.
   - M = Q^-1 = R diag(a^2,b^2,c^2) R^T gives the support function
     h(n) = n.c + sqrt(n^T M n) and the support point s(n) = c + M n / sqrt(n^T M n).
   - Quaternions are (w, x, y, z), body -> box; make_ellipsoid normalises them.

   Degenerate cases
   - A zero, negative or non-finite semi-axis, a non-finite centre or a quaternion of zero or
     non-finite norm gives finite = false; every query then answers Degenerate (or 0 for the
     volumes) instead of computing with it. valid() re-checks the centre, which callers move
     (periodic images) after construction.
   - sphere is set when the semi-axes agree within 1e-14 relative: the queries take their
     closed-form sphere paths.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_SHAPE_H
#define ELLIPSOID_DEP_ELLIPSOID_SHAPE_H

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace EllipsoidDep {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;

inline constexpr double PI = 3.14159265358979323846;    // the kernel's one pi

// Centre and bounding radius first (the bounding test reads them for every candidate pair),
// then inverse_form (cached plane, Newton iteration); form (cold starts, the Wang test) last.
struct Ellipsoid {
  Vec3 center;
  double bounding_radius;    // largest semi-axis
  bool sphere;               // all semi-axes equal to round-off: closed-form path
  bool finite = false;       // every entry finite and semi-axes > 0 (checked once, here)
  Mat3 inverse_form;         // M = R diag(a^2) R^T  (support function)
  Mat3 rotation;             // body -> box; columns are the body axes in box coordinates
  Vec3 semi_axes;            // along the body axes, any order, all > 0
  Mat3 form;                 // Q = R diag(1/a^2) R^T  (the paper's A)

  // the paper's 4x4 homogeneous matrix: X^T H X = 0 on the surface, X = (x,1)
  Mat4 homogeneous() const;
  double volume() const;
};

// Rotation body -> box of a quaternion (w, x, y, z) of any non-zero length (normalised
// here); all NaN when its norm is zero or not finite.
Mat3 quaternion_rotation(const double quat[4]);

// quaternion (w, x, y, z), unit; semi-axes (a, b, c) along body x, y, z
Ellipsoid make_ellipsoid(const Vec3 &center, const double quat[4], const Vec3 &semi_axes);
Ellipsoid make_ellipsoid(const Vec3 &center, const Mat3 &rotation, const Vec3 &semi_axes);

// A quaternion make_ellipsoid can use: finite, of non-zero norm.
inline bool usable_quaternion(const double quat[4])
{
  const double q2 = quat[0] * quat[0] + quat[1] * quat[1] + quat[2] * quat[2] + quat[3] * quat[3];
  return q2 > 0.0 && std::isfinite(q2);
}

// Whether semi-axes describe a sphere: equal within 1e-14 relative. A sphere's contacts do not
// depend on its orientation (the queries take closed-form paths; the integrator fix
// nve/ellipsoid does not rotate it).
inline bool is_sphere(const Vec3 &semi_axes)
{
  const double hi = semi_axes.maxCoeff();
  return (hi - semi_axes.minCoeff()) <= 1e-14 * hi;
}

// A particle's ellipsoid: make_ellipsoid, except that a sphere with a usable quaternion is built
// in the identity frame. Its contacts do not depend on its orientation, so the state holds
// while it spins and an integrator need not rotate it; every engine-side caller builds
// particles through this one rule.
inline Ellipsoid make_particle(const Vec3 &center, const double quat[4], const Vec3 &semi_axes)
{
  if (is_sphere(semi_axes) && usable_quaternion(quat))
    return make_ellipsoid(center, Mat3::Identity(), semi_axes);
  return make_ellipsoid(center, quat, semi_axes);
}

// Radius of the bounding sphere about the centre: the largest semi-axis.
inline double bounding_radius_of(const Vec3 &semi_axes)
{
  return semi_axes.maxCoeff();
}

inline bool finite3(const Vec3 &v)
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// make_ellipsoid decides validity once per body; a centre moved afterwards (periodic images)
// is checked again because it is cheap
inline bool valid(const Ellipsoid &e)
{
  return e.finite && finite3(e.center);
}

// Support half-width sqrt(n^T M n) (n need not be unit: degree-1 homogeneous).
inline double support(const Mat3 &m, const Vec3 &n)
{
  return std::sqrt(std::max(n.dot(m * n), 0.0));
}

// Gaussian-curvature radius sqrt(R1 R2) of the surface where its outer unit normal is n:
// abc / (n^T M n), from the Gaussian curvature K = (n^T M n)^2 / (abc)^2. The first form takes
// n^T M n, for callers that have it (the square of the support half-width).
inline double gaussian_radius_of_nmn(const Ellipsoid &e, double nmn)
{
  return e.semi_axes[0] * e.semi_axes[1] * e.semi_axes[2] / nmn;
}
inline double gaussian_radius(const Ellipsoid &e, const Vec3 &unit_normal)
{
  return gaussian_radius_of_nmn(e, unit_normal.dot(e.inverse_form * unit_normal));
}

// The largest Gaussian-curvature radius of an ellipsoid with semi-axes a, b, c (any order):
// ab/c at the ends of the shortest axis c, the flattest place of its surface (with the
// lightest mass it bounds the shortest Hertz contact time).
inline double flattest_radius(double a, double b, double c)
{
  const double thinnest = std::min(a, std::min(b, c));
  return a * b * c / (thinnest * thinnest);
}

// An upper bound of q = m (r x t) . I^-1 (r x t) over the surface points r and unit vectors t
// of a solid ellipsoid of mass m, inertia I about its centre and semi-axes a, b, c (any
// order): how far a force along t at r moves that point by turning the body, against 1 for
// moving its centre. A contact's effective mass for sliding is then
// 1 / m_t = (1 + q_i) / m_i + (1 + q_j) / m_j. Scale-free (axis ratios only). Exact for a
// sphere (5/2) and a thin disc (5); 1.5 times the maximum for a needle (7.4 against 4.95), 1.83
// times for semi-axes 9:3:1 (8.9 against 4.85): a time step bound by it is that much safe.
double rotational_compliance(double a, double b, double c);

// The force laws' R* = R_A R_B / (R_A + R_B) of two surface radii.
inline double effective_radius(double ra, double rb)
{
  return ra * rb / (ra + rb);
}

// R* of a particle against a curved wall: the particle's surface radius r at the contact and
// the wall's contact radius, LAMMPS's region convention (region->contact[].radius: > 0 convex,
// < 0 concave, 0 flat; a sphere region's is -+R, a cylinder's lateral surface's -2R). A
// conformal contact (a flat side of a particle against a wall curved almost as much) is capped
// at CONFORMAL_CAP r; a sphere smaller than 0.9 R in a sphere region is below the cap.
constexpr double CONFORMAL_CAP = 10.0;
inline double wall_effective_radius(double particle_radius, double wall_radius)
{
  if (wall_radius == 0.0) return particle_radius;
  const double curvature = 1.0 / particle_radius + 1.0 / wall_radius;
  const double cap = CONFORMAL_CAP * particle_radius;
  return curvature * cap > 1.0 ? 1.0 / curvature : cap;
}

// R* of a contact with unit normal n from A to B: Gaussian radii of A at n and of B at -n.
inline double effective_radius(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &n)
{
  return effective_radius(gaussian_radius(a, n), gaussian_radius(b, -n));
}

// Volume of the part of an ellipsoid between the planes z = zlo and z = zhi (closed form);
// 0 for an invalid ellipsoid or zhi <= zlo.
double ellipsoid_slab_volume(const Ellipsoid &e, double zlo, double zhi);

}    // namespace EllipsoidDep

#endif
