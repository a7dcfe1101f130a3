// The curved wall shapes (sphere, cylinder; inside and outside) against an independent
// brute-force oracle: the ellipsoid surface parametrised by two angles in long double, the
// depth beyond the wall's surface sampled densely and refined by a shrinking pattern search.
// The oracle shares no code with the kernel's secular equation (ellipsoid_point_extremum).
// The solids met from outside (a block's faces, edges and corners; a capped cylinder's side,
// caps and rims) against their own brute-force oracle (below).

#include "ellipsoid_kernel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

using namespace EllipsoidDep;

namespace {

using LD = long double;
using V3L = std::array<LD, 3>;

// an ellipsoid by its raw inputs: centre, quaternion (w, x, y, z), semi-axes
struct RawEllipsoid {
  double c[3], q[4], axes[3];
};

// the rotation (body to box) of the quaternion, built here
std::array<V3L, 3> rotation_rows(const RawEllipsoid &r)
{
  LD w = r.q[0], x = r.q[1], y = r.q[2], z = r.q[3];
  const LD n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n, x /= n, y /= n, z /= n;
  return {V3L{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
          V3L{2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
          V3L{2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
}

// the surface point at angles (theta, phi)
V3L surface_point(const RawEllipsoid &r, LD theta, LD phi)
{
  const std::array<V3L, 3> rot = rotation_rows(r);
  const LD body[3] = {r.axes[0] * std::sin(theta) * std::cos(phi),
                      r.axes[1] * std::sin(theta) * std::sin(phi), r.axes[2] * std::cos(theta)};
  V3L p;
  for (int i = 0; i < 3; i++) p[i] = r.c[i] + rot[i][0] * body[0] + rot[i][1] * body[1] + rot[i][2] * body[2];
  return p;
}

struct OracleResult {
  LD depth;
  V3L point;
};

// the largest depth over the surface: a 60 x 120 grid, then pattern search from the best
// eight grid points
OracleResult deepest(const RawEllipsoid &r, const std::function<LD(const V3L &)> &depth)
{
  const LD pi = 3.141592653589793238462643383279502884L;
  struct Start { LD d, t, p; };
  std::vector<Start> grid;
  for (int i = 0; i <= 60; i++)
    for (int j = 0; j < 120; j++) {
      const LD t = pi * i / 60, p = 2 * pi * j / 120;
      grid.push_back({depth(surface_point(r, t, p)), t, p});
    }
  std::partial_sort(grid.begin(), grid.begin() + 8, grid.end(),
                    [](const Start &a, const Start &b) { return a.d > b.d; });
  OracleResult best{-1e300L, {}};
  for (int s = 0; s < 8; s++) {
    LD t = grid[s].t, p = grid[s].p, d = grid[s].d, step = pi / 60;
    while (step > 1e-15L) {
      bool moved = false;
      for (const auto &dir : {std::array<int, 2>{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1},
                              {-1, -1}, {1, -1}, {-1, 1}}) {
        const LD tn = t + dir[0] * step, pn = p + dir[1] * step;
        const LD dn = depth(surface_point(r, tn, pn));
        if (dn > d) t = tn, p = pn, d = dn, moved = true;
      }
      if (!moved) step *= 0.5L;
    }
    if (d > best.depth) best = {d, surface_point(r, t, p)};
  }
  return best;
}

LD norm3(const V3L &v)
{
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

RawEllipsoid random_ellipsoid(std::mt19937_64 &rng)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  RawEllipsoid r{};
  // aspect ratios up to 10: the largest semi-axis 1, the others in [0.1, 1]
  r.axes[0] = 1.0;
  r.axes[1] = 0.1 + 0.9 * u(rng);
  r.axes[2] = 0.1 + 0.9 * u(rng);
  for (double &qk : r.q) qk = g(rng);
  return r;
}

Ellipsoid kernel_ellipsoid(const RawEllipsoid &r)
{
  return make_ellipsoid(Vec3(r.c[0], r.c[1], r.c[2]), r.q, Vec3(r.axes[0], r.axes[1], r.axes[2]));
}

// the kernel's contact against the oracle's deepest point: overlap, normal, contact point
void expect_matches_oracle(const RawEllipsoid &r, const WallSurface &w,
                           const std::function<LD(const V3L &)> &depth,
                           const std::function<V3L(const V3L &)> &wall_normal_at)
{
  const ContactGeometry g = wall_contact(kernel_ellipsoid(r), w);
  ASSERT_TRUE(g.status == Status::Overlapping || g.status == Status::Separated)
      << "status " << static_cast<int>(g.status);
  const OracleResult o = deepest(r, depth);
  EXPECT_NEAR(g.overlap, static_cast<double>(o.depth), 1e-10);
  EXPECT_EQ(g.status, o.depth > 0 ? Status::Overlapping : Status::Separated);
  const V3L n = wall_normal_at(o.point);
  for (int d = 0; d < 3; d++) {
    EXPECT_NEAR(g.normal[d], static_cast<double>(n[d]), 1e-6) << "normal " << d;
    EXPECT_NEAR(g.point_a[d], static_cast<double>(o.point[d]), 1e-6) << "point " << d;
  }
}

constexpr int CASES = 40;

}    // namespace

TEST(WallShapes, SphereAgainstBruteForce)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double radius = 5.0, s[3] = {0.3, -0.2, 0.7};
  for (const bool inside : {true, false}) {
    for (int k = 0; k < CASES; k++) {
      RawEllipsoid r = random_ellipsoid(rng);
      // a centre within a semi-axis or so of the surface, on the particles' side
      Vec3 dir(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
      dir.normalize();
      const double rho = inside ? radius - 1.2 * u(rng) : radius + 1.2 * u(rng);
      for (int d = 0; d < 3; d++) r.c[d] = s[d] + rho * dir[d];
      WallSurface w;
      w.shape = WallShape::Sphere;
      w.center = Vec3(s[0], s[1], s[2]);
      w.radius = radius;
      w.inside = inside;
      auto offset = [&](const V3L &p) {
        return V3L{p[0] - s[0], p[1] - s[1], p[2] - s[2]};
      };
      expect_matches_oracle(
          r, w,
          [&](const V3L &p) { return inside ? norm3(offset(p)) - radius : radius - norm3(offset(p)); },
          [&](const V3L &p) {
            V3L v = offset(p);
            const LD l = norm3(v) * (inside ? 1 : -1);
            return V3L{v[0] / l, v[1] / l, v[2] / l};
          });
    }
  }
}

TEST(WallShapes, CylinderAgainstBruteForce)
{
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double radius = 4.0, a[3] = {0.5, 0.1, -0.3};
  for (const bool inside : {true, false}) {
    for (int k = 0; k < CASES; k++) {
      RawEllipsoid r = random_ellipsoid(rng);
      Vec3 axis(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
      axis.normalize();
      const Vec3 radial = axis.unitOrthogonal();
      const double rho = inside ? radius - 1.2 * u(rng) : radius + 1.2 * u(rng);
      const Vec3 c = Vec3(a[0], a[1], a[2]) + rho * radial + 3.0 * (u(rng) - 0.5) * axis;
      for (int d = 0; d < 3; d++) r.c[d] = c[d];
      WallSurface w;
      w.shape = WallShape::Cylinder;
      w.center = Vec3(a[0], a[1], a[2]);
      w.axis = axis;
      w.radius = radius;
      w.inside = inside;
      const V3L ax{axis[0], axis[1], axis[2]};
      auto perp = [&](const V3L &p) {
        V3L v{p[0] - a[0], p[1] - a[1], p[2] - a[2]};
        const LD along = v[0] * ax[0] + v[1] * ax[1] + v[2] * ax[2];
        for (int d = 0; d < 3; d++) v[d] -= along * ax[d];
        return v;
      };
      expect_matches_oracle(
          r, w,
          [&](const V3L &p) { return inside ? norm3(perp(p)) - radius : radius - norm3(perp(p)); },
          [&](const V3L &p) {
            V3L v = perp(p);
            const LD l = norm3(v) * (inside ? 1 : -1);
            return V3L{v[0] / l, v[1] / l, v[2] / l};
          });
    }
  }
}

TEST(WallShapes, ConeAgainstBruteForce)
{
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double a[3] = {-0.2, 0.4, 0.1};
  for (int k = 0; k < CASES; k++) {
    RawEllipsoid r = random_ellipsoid(rng);
    // hoppers from steep to flat (half-angles 0 to about 63 degrees, either way up), the apex
    // far from the particle
    const double radius = 4.0, slope = 4.0 * (u(rng) - 0.5);
    Vec3 axis(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    axis.normalize();
    const double s = 0.8 * (u(rng) - 0.5);
    // a centre within a semi-axis or so of the side, measured normal to it
    const Vec3 radial = axis.unitOrthogonal();
    const double cosine = 1.0 / std::sqrt(1.0 + slope * slope);
    const double depth = 1.2 * u(rng);
    const Vec3 side = Vec3(a[0], a[1], a[2]) + s * axis + (radius + slope * s) * radial;
    const Vec3 inward = cosine * (slope * axis - radial);
    const Vec3 c = side + depth * inward;
    for (int d = 0; d < 3; d++) r.c[d] = c[d];
    WallSurface w;
    w.shape = WallShape::Cone;
    w.center = Vec3(a[0], a[1], a[2]);
    w.axis = axis;
    w.radius = radius;
    w.slope = slope;
    const V3L ax{axis[0], axis[1], axis[2]};
    // the depth beyond the side, normal to it, and the wall's normal there
    auto parts = [&](const V3L &p, LD &along, V3L &perp) {
      V3L v{p[0] - a[0], p[1] - a[1], p[2] - a[2]};
      along = v[0] * ax[0] + v[1] * ax[1] + v[2] * ax[2];
      for (int d = 0; d < 3; d++) perp[d] = v[d] - along * ax[d];
    };
    const LD cos_l = 1 / std::sqrt(1 + (LD) slope * slope);
    expect_matches_oracle(
        r, w,
        [&](const V3L &p) {
          LD along;
          V3L perp;
          parts(p, along, perp);
          return (norm3(perp) - radius - slope * along) * cos_l;
        },
        [&](const V3L &p) {
          LD along;
          V3L perp;
          parts(p, along, perp);
          const LD l = norm3(perp);
          V3L n;
          for (int d = 0; d < 3; d++) n[d] = (perp[d] / l - slope * ax[d]) * cos_l;
          return n;
        });
  }
}

// a sphere: LAMMPS's region geometry in closed form, R* by its -2R / -R convention
TEST(WallShapes, SphereParticleClosedForm)
{
  const double r = 0.5, quat[4] = {1, 0, 0, 0};
  const Ellipsoid e = make_ellipsoid(Vec3(3.8, 0.0, 1.0), quat, Vec3(r, r, r));
  WallSurface cyl;
  cyl.shape = WallShape::Cylinder;
  cyl.axis = Vec3::UnitZ();
  cyl.radius = 4.0;
  const ContactGeometry g = wall_contact(e, cyl);
  EXPECT_EQ(g.status, Status::Overlapping);
  EXPECT_NEAR(g.overlap, 3.8 + r - 4.0, 1e-15);
  EXPECT_NEAR(g.normal[0], 1.0, 1e-15);
  EXPECT_NEAR(g.effective_radius, r * (-8.0) / (r - 8.0), 1e-15);
  WallSurface ball;
  ball.shape = WallShape::Sphere;
  ball.radius = 4.0;
  ball.center = Vec3(0.0, 0.0, 1.0);
  const ContactGeometry s = wall_contact(e, ball);
  EXPECT_NEAR(s.overlap, 3.8 + r - 4.0, 1e-15);
  EXPECT_NEAR(s.effective_radius, r * (-4.0) / (r - 4.0), 1e-15);
  // the hard case: the ellipsoid centred on the ball's centre, its longest axis doubled
  const Ellipsoid spheroid = make_ellipsoid(Vec3(0.0, 0.0, 1.0), quat, Vec3(1.0, 1.0, 0.3));
  const ContactGeometry h = wall_contact(spheroid, ball);
  EXPECT_EQ(h.status, Status::Separated);
  EXPECT_NEAR(h.overlap, 1.0 - 4.0, 1e-15);
}

// ---------------------------------------------------------------------------------------
// Solids met from outside (a block, a capped cylinder): the penetration depth is the smallest
// separating-axis overlap delta(n) = h_B(n) + sqrt(n^T M n) - n.c over unit directions n
// (from the solid to the particle). The oracle minimises it in long double by brute force on
// the patches of directions where the solid's support function h_B is one formula: a box's
// eight octants (h_B = n.corner), a capped cylinder's two hemispheres (h_B = n.cap centre +
// R |n_perp|), each over a region of two coordinates: a grid, then a pattern search from each
// of its local minima kept in the region. It shares no code with the kernel's features, cones
// and searches.

namespace {

// sqrt(n^T M n) from the quaternion's rotation and the semi-axes
LD half_width(const RawEllipsoid &r, const V3L &n)
{
  const std::array<V3L, 3> rot = rotation_rows(r);
  LD sum = 0;
  for (int k = 0; k < 3; k++) {
    const LD along = rot[0][k] * n[0] + rot[1][k] * n[1] + rot[2][k] * n[2];
    sum += (LD) r.axes[k] * r.axes[k] * along * along;
  }
  return std::sqrt(sum);
}

LD dot3(const V3L &a, const V3L &b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

struct SolidOracle {
  LD overlap = 1e300L;
  V3L n{};
};

// the smallest delta(direction(x, y)) over the region of the plane [x0, x1] x [y0, y1] that
// `inside` accepts: a 40 x 40 grid, then a pattern search from each of its local minima
// (over the 8 neighbours), moves that leave the region refused
void patch_minimum(const std::function<V3L(LD, LD)> &direction,
                   const std::function<bool(LD, LD)> &inside,
                   const std::function<LD(const V3L &)> &delta, const std::array<LD, 4> &box,
                   SolidOracle &best)
{
  const int cells = 40;
  const LD dx = (box[1] - box[0]) / cells, dy = (box[3] - box[2]) / cells;
  std::vector<LD> values((cells + 1) * (cells + 1), 1e300L);
  auto at = [&](int i, int j) -> LD & { return values[i * (cells + 1) + j]; };
  for (int i = 0; i <= cells; i++)
    for (int j = 0; j <= cells; j++) {
      const LD x = box[0] + i * dx, y = box[2] + j * dy;
      if (inside(x, y)) at(i, j) = delta(direction(x, y));
    }
  struct Start { LD v, x, y; };
  std::vector<Start> starts;
  for (int i = 0; i <= cells; i++)
    for (int j = 0; j <= cells; j++) {
      if (at(i, j) >= 1e300L) continue;
      bool lowest = true;
      for (int di = -1; di <= 1; di++)
        for (int dj = -1; dj <= 1; dj++) {
          const int ni = i + di, nj = j + dj;
          if (ni >= 0 && nj >= 0 && ni <= cells && nj <= cells && at(ni, nj) < at(i, j))
            lowest = false;
        }
      if (lowest) starts.push_back({at(i, j), box[0] + i * dx, box[2] + j * dy});
    }
  for (const Start &start : starts) {
    LD x = start.x, y = start.y, v = start.v, step = dx;
    while (step > 1e-13L) {
      bool moved = false;
      for (const auto &dir : {std::array<int, 2>{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1},
                              {-1, -1}, {1, -1}, {-1, 1}}) {
        const LD xn = x + dir[0] * step, yn = y + dir[1] * step;
        if (!inside(xn, yn)) continue;
        const LD vn = delta(direction(xn, yn));
        if (vn < v) x = xn, y = yn, v = vn, moved = true;
      }
      step = moved ? std::min(2 * step, dx) : step / 2;    // long valleys in few moves
    }
    if (v < best.overlap) best = {v, direction(x, y)};
  }
}

V3L to_ld(const Vec3 &v)
{
  return {v[0], v[1], v[2]};
}

V3L unit(const V3L &v)
{
  const LD l = norm3(v);
  return {v[0] / l, v[1] / l, v[2] / l};
}

// the box lower <= F^T (x - o) <= upper, F's columns the frame; an octant's directions
// n ~ (s0 x, s1 y, s2 (1 - x - y)) in the frame over the triangle x, y >= 0, x + y <= 1
SolidOracle box_oracle(const RawEllipsoid &r, const Vec3 &o, const Mat3 &frame, const Vec3 &lower,
                       const Vec3 &upper)
{
  SolidOracle best;
  const V3L c{r.c[0], r.c[1], r.c[2]};
  for (int octant = 0; octant < 8; octant++) {
    const LD sign[3] = {octant & 1 ? 1.0L : -1.0L, octant & 2 ? 1.0L : -1.0L,
                        octant & 4 ? 1.0L : -1.0L};
    V3L corner = to_ld(o);
    for (int k = 0; k < 3; k++) {
      const LD at = sign[k] > 0 ? upper[k] : lower[k];
      for (int i = 0; i < 3; i++) corner[i] += frame(i, k) * at;
    }
    auto direction = [&](LD x, LD y) {
      const LD local[3] = {sign[0] * x, sign[1] * y, sign[2] * (1 - x - y)};
      V3L n{};
      for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) n[i] += frame(i, k) * local[k];
      return unit(n);
    };
    auto triangle = [](LD x, LD y) { return x >= 0 && y >= 0 && x + y <= 1; };
    auto delta = [&](const V3L &n) { return half_width(r, n) + dot3(n, corner) - dot3(n, c); };
    patch_minimum(direction, triangle, delta, {0, 1, 0, 1}, best);
  }
  return best;
}

// the cylinder of radius R about the axis through o along u, caps at s = lo, hi; a
// hemisphere's directions in the frame (e1, e2, +-u) over two charts, the lower minimum of
// the two: n = (x, y, sqrt(1 - x^2 - y^2)) over the unit disc (the kink at the cap's normal
// is a point of it) and the angles (phi, psi) from the cap's normal (the side's directions
// at psi = pi/2 a line of it; its pole left to the disc)
SolidOracle post_oracle(const RawEllipsoid &r, const Vec3 &o, const Vec3 &u, double radius,
                        double lo, double hi)
{
  SolidOracle best;
  const V3L c{r.c[0], r.c[1], r.c[2]};
  const V3L ul = to_ld(u), e1 = to_ld(u.unitOrthogonal()), e2 = to_ld(u.cross(u.unitOrthogonal()));
  const LD pi = 3.141592653589793238462643383279502884L;
  for (const LD sign : {-1.0L, 1.0L}) {
    V3L cap = to_ld(o);
    for (int i = 0; i < 3; i++) cap[i] += (sign > 0 ? hi : lo) * ul[i];
    auto frame = [&](LD x, LD y, LD z) {
      V3L n;
      for (int i = 0; i < 3; i++) n[i] = sign * z * ul[i] + x * e1[i] + y * e2[i];
      return unit(n);
    };
    auto disc_direction = [&](LD x, LD y) {
      return frame(x, y, std::sqrt(std::max((LD) 0, 1 - x * x - y * y)));
    };
    auto angle_direction = [&](LD phi, LD psi) {
      return frame(std::sin(psi) * std::cos(phi), std::sin(psi) * std::sin(phi), std::cos(psi));
    };
    auto delta = [&](const V3L &n) {
      const LD axial = dot3(n, ul);
      const V3L across{n[0] - axial * ul[0], n[1] - axial * ul[1], n[2] - axial * ul[2]};
      return half_width(r, n) + dot3(n, cap) - dot3(n, c) + radius * norm3(across);
    };
    patch_minimum(disc_direction, [](LD x, LD y) { return x * x + y * y <= 1; }, delta,
                  {-1, 1, -1, 1}, best);
    patch_minimum(angle_direction, [&](LD phi, LD psi) {
      return phi >= -pi && phi <= 3 * pi && psi > 0 && psi <= pi / 2; }, delta,
                  {0, 2 * pi, 0, pi / 2}, best);
  }
  return best;
}

// the kernel's contact against the oracle: in contact, the overlap to 1e-10 (the semi-axes
// are at most 1) and the normal; apart, Separated. Returns whether the normal is a face's
// (along one of `axes`).
bool expect_solid_matches(const ContactGeometry &g, const SolidOracle &o,
                          const std::vector<Vec3> &axes)
{
  EXPECT_TRUE(g.status == Status::Overlapping || g.status == Status::Separated)
      << "status " << static_cast<int>(g.status);
  if (o.overlap <= 0) {
    EXPECT_EQ(g.status, Status::Separated) << "oracle " << (double) o.overlap;
    EXPECT_LE(g.overlap, 0.0);
    return false;
  }
  EXPECT_EQ(g.status, Status::Overlapping);
  EXPECT_NEAR(g.overlap, (double) o.overlap, 1e-10);
  for (int d = 0; d < 3; d++) EXPECT_NEAR(g.normal[d], -(double) o.n[d], 1e-7) << "normal " << d;
  // the particle's deepest point moved by the overlap lies on the solid's supporting plane
  EXPECT_NEAR(g.normal.dot(g.point_b - g.point_a), -g.overlap, 1e-12);
  for (const Vec3 &a : axes)
    if (std::fabs(std::fabs(g.normal.dot(a)) - 1.0) < 1e-9) return true;
  return false;
}

Vec3 random_unit(std::mt19937_64 &rng)
{
  std::normal_distribution<double> g;
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

constexpr int SOLID_CASES = 60;
constexpr int POST_CASES = 30;    // its oracle's two charts cost more

}    // namespace

// centres near a box's edges and corners, at distances from 0 to about a largest semi-axis
// beyond them in directions of the feature's normal cone: overlapping (edge, corner and face
// contacts) and apart
TEST(WallShapes, BoxFromOutsideAgainstBruteForce)
{
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Vec3 o(0.3, -0.2, 0.5), lower(-1.5, -1.0, -2.0), upper(1.2, 0.8, 1.6);
  const double quat[4] = {0.9, 0.2, -0.3, 0.25};
  const Mat3 frame = quaternion_rotation(quat);
  int touching = 0, at_edges = 0;
  for (int k = 0; k < SOLID_CASES; k++) {
    RawEllipsoid r = random_ellipsoid(rng);
    // a corner or an edge's point (the third coordinate along the edge), a direction in its cone
    Vec3 point, outward;
    const bool corner = k % 2 == 0;
    const int along = static_cast<int>(3 * u(rng));
    for (int d = 0; d < 3; d++) {
      const bool up = u(rng) < 0.5;
      if (!corner && d == along) {
        point[d] = lower[d] + (upper[d] - lower[d]) * u(rng);
        outward[d] = 0.0;
      } else {
        point[d] = up ? upper[d] : lower[d];
        outward[d] = (up ? 1.0 : -1.0) * (0.05 + u(rng));
      }
    }
    const Vec3 c = o + frame * (point + 1.1 * u(rng) * outward.normalized());
    for (int d = 0; d < 3; d++) r.c[d] = c[d];
    WallSurface w;
    w.shape = WallShape::Box;
    w.center = o;
    w.frame = frame;
    w.lower = lower;
    w.upper = upper;
    const ContactGeometry g = wall_contact(kernel_ellipsoid(r), w);
    const SolidOracle oracle = box_oracle(r, o, frame, lower, upper);
    const bool face = expect_solid_matches(g, oracle, {frame.col(0), frame.col(1), frame.col(2)});
    if (oracle.overlap > 0) touching++, at_edges += face ? 0 : 1;
  }
  // the cases reach contacts, most of them at an edge or a corner
  EXPECT_GE(touching, SOLID_CASES / 3);
  EXPECT_GE(at_edges, touching / 2);
}

// centres near a capped cylinder's rims (tilted from the cap's normal to the side's), overlapping
// (rim, cap and side contacts) and apart
TEST(WallShapes, CappedCylinderFromOutsideAgainstBruteForce)
{
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Vec3 o(-0.4, 0.2, 0.1);
  const double radius = 1.2, lo = -1.0, hi = 1.5;
  int touching = 0, at_rims = 0;
  for (int k = 0; k < POST_CASES; k++) {
    RawEllipsoid r = random_ellipsoid(rng);
    const Vec3 axis = random_unit(rng);
    const Vec3 e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
    const bool top = u(rng) < 0.5;
    const double phi = 2.0 * PI * u(rng), psi = 0.5 * PI * u(rng);
    const Vec3 radial = std::cos(phi) * e1 + std::sin(phi) * e2;
    const Vec3 rim = o + (top ? hi : lo) * axis + radius * radial;
    const Vec3 outward = (top ? 1.0 : -1.0) * std::cos(psi) * axis + std::sin(psi) * radial;
    const Vec3 c = rim + 1.1 * u(rng) * outward;
    for (int d = 0; d < 3; d++) r.c[d] = c[d];
    WallSurface w;
    w.shape = WallShape::Cylinder;
    w.inside = false;
    w.center = o;
    w.axis = axis;
    w.radius = radius;
    w.cap_lo = lo;
    w.cap_hi = hi;
    const ContactGeometry g = wall_contact(kernel_ellipsoid(r), w);
    const SolidOracle oracle = post_oracle(r, o, axis, radius, lo, hi);
    const bool cap = expect_solid_matches(g, oracle, {axis});
    const bool side = std::fabs(g.normal.dot(axis)) < 1e-9;
    if (oracle.overlap > 0) touching++, at_rims += cap || side ? 0 : 1;
  }
  EXPECT_GE(touching, POST_CASES / 3);
  EXPECT_GE(at_rims, touching / 2);
}

// spheres: the distance to the nearest point of the solid in closed form; R* flat at a
// block's edge, LAMMPS's 2R at a cylinder's rim, flat on its cap
TEST(WallShapes, SphereOutsideSolidsClosedForm)
{
  const double r = 0.5, quat[4] = {1, 0, 0, 0};
  WallSurface block;
  block.shape = WallShape::Box;
  block.lower = Vec3(0.0, 0.0, 0.0);
  block.upper = Vec3(2.0, 3.0, 4.0);
  // near the edge x = 2, y = 3 and near the corner (0, 0, 0)
  const Vec3 edge_gap(0.2, 0.25, 0.0), corner_gap(-0.15, -0.2, -0.1);
  const ContactGeometry edge =
      wall_contact(make_ellipsoid(Vec3(2.0, 3.0, 1.0) + edge_gap, quat, Vec3(r, r, r)), block);
  EXPECT_EQ(edge.status, Status::Overlapping);
  EXPECT_NEAR(edge.overlap, r - edge_gap.norm(), 1e-13);
  EXPECT_NEAR((edge.normal + edge_gap.normalized()).norm(), 0.0, 1e-9);
  EXPECT_NEAR(edge.point_b.x(), 2.0, 1e-12);
  EXPECT_NEAR(edge.point_b.y(), 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(edge.effective_radius, r);
  const ContactGeometry corner = wall_contact(make_ellipsoid(corner_gap, quat, Vec3(r, r, r)), block);
  EXPECT_NEAR(corner.overlap, r - corner_gap.norm(), 1e-13);
  EXPECT_NEAR(corner.point_b.norm(), 0.0, 1e-7);
  const ContactGeometry apart =
      wall_contact(make_ellipsoid(Vec3(2.4, 3.4, 1.0), quat, Vec3(r, r, r)), block);
  EXPECT_EQ(apart.status, Status::Separated);

  WallSurface post;
  post.shape = WallShape::Cylinder;
  post.inside = false;
  post.radius = 1.0;
  post.cap_lo = -1.0;
  post.cap_hi = 2.0;
  // beyond the top rim at (1, 0, 2), and above the cap
  const Vec3 rim_gap(0.3, 0.0, 0.35);
  const ContactGeometry rim =
      wall_contact(make_ellipsoid(Vec3(1.0, 0.0, 2.0) + rim_gap, quat, Vec3(r, r, r)), post);
  EXPECT_EQ(rim.status, Status::Overlapping);
  EXPECT_NEAR(rim.overlap, r - rim_gap.norm(), 1e-13);
  EXPECT_NEAR(rim.effective_radius, r * 2.0 / (r + 2.0), 1e-14);
  const ContactGeometry cap =
      wall_contact(make_ellipsoid(Vec3(0.3, 0.2, 2.4), quat, Vec3(r, r, r)), post);
  EXPECT_NEAR(cap.overlap, 0.1, 1e-13);
  EXPECT_NEAR(cap.normal.z(), -1.0, 1e-15);
  EXPECT_DOUBLE_EQ(cap.effective_radius, r);
}

// an infinite bound is no face: the same contact as a bound far beyond the particle
TEST(WallShapes, BoxInfiniteBoundIsAFarFace)
{
  std::mt19937_64 rng(23);
  for (int k = 0; k < 10; k++) {
    RawEllipsoid r = random_ellipsoid(rng);
    r.c[0] = 1.3, r.c[1] = 1.2, r.c[2] = 0.5 * k;
    WallSurface open, far;
    open.shape = far.shape = WallShape::Box;
    open.lower = far.lower = Vec3(-1.0, -1.0, -1.0);
    far.upper = Vec3(1.0, 1.0, 1e6);
    open.upper = Vec3(1.0, 1.0, INFINITY);
    const ContactGeometry a = wall_contact(kernel_ellipsoid(r), open);
    const ContactGeometry b = wall_contact(kernel_ellipsoid(r), far);
    EXPECT_EQ(a.status, b.status);
    EXPECT_NEAR(a.overlap, b.overlap, 1e-12);
    EXPECT_NEAR((a.normal - b.normal).norm(), 0.0, 1e-9);
  }
}

// ---------------------------------------------------------------------------------------
// A finite side met from inside (a cylinder's or cone's side between its ends) and the rims
// where it ends. The rim's oracle: the depth of a rim point in the particle is its distance
// from the surface (the oracle's search above, on -|p - q|), signed by the body frame's
// inside test; the rim's deepest point from 60 angles, the best two refined by golden section.

namespace {

bool inside_raw(const RawEllipsoid &r, const V3L &q)
{
  const std::array<V3L, 3> rot = rotation_rows(r);
  LD sum = 0;
  for (int k = 0; k < 3; k++) {
    LD body = 0;
    for (int i = 0; i < 3; i++) body += rot[i][k] * (q[i] - r.c[i]);
    sum += body * body / ((LD) r.axes[k] * r.axes[k]);
  }
  return sum < 1;
}

// the distance of q from the surface: a 24 x 48 grid of angles, then a pattern search from
// the best three
LD rim_point_depth(const RawEllipsoid &r, const V3L &q)
{
  const LD pi = 3.141592653589793238462643383279502884L;
  auto distance = [&](LD t, LD p) {
    const V3L y = surface_point(r, t, p);
    return norm3(V3L{y[0] - q[0], y[1] - q[1], y[2] - q[2]});
  };
  struct Start { LD d, t, p; };
  std::vector<Start> grid;
  for (int i = 0; i <= 24; i++)
    for (int j = 0; j < 48; j++) grid.push_back({distance(pi * i / 24, 2 * pi * j / 48), pi * i / 24, 2 * pi * j / 48});
  std::partial_sort(grid.begin(), grid.begin() + 3, grid.end(),
                    [](const Start &a, const Start &b) { return a.d < b.d; });
  LD best = grid[0].d;
  for (int s = 0; s < 3; s++) {
    LD t = grid[s].t, p = grid[s].p, d = grid[s].d, step = pi / 24;
    while (step > 1e-13L) {
      bool moved = false;
      for (const auto &dir : {std::array<int, 2>{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1},
                              {-1, -1}, {1, -1}, {-1, 1}}) {
        const LD dn = distance(t + dir[0] * step, p + dir[1] * step);
        if (dn < d) d = dn, t += dir[0] * step, p += dir[1] * step, moved = true;
      }
      if (!moved) step /= 2;
    }
    best = std::min(best, d);
  }
  return inside_raw(r, q) ? best : -best;
}

V3L rim_point(const Vec3 &k, const Vec3 &u, double rho, LD theta)
{
  const Vec3 e1 = u.unitOrthogonal(), e2 = u.cross(e1);
  V3L q;
  for (int d = 0; d < 3; d++) q[d] = k[d] + rho * (std::cos(theta) * e1[d] + std::sin(theta) * e2[d]);
  return q;
}

LD rim_oracle(const RawEllipsoid &r, const Vec3 &k, const Vec3 &u, double rho)
{
  const LD pi = 3.141592653589793238462643383279502884L;
  constexpr int N = 60;
  std::vector<std::pair<LD, int>> samples;
  for (int j = 0; j < N; j++) samples.push_back({rim_point_depth(r, rim_point(k, u, rho, 2 * pi * j / N)), j});
  std::partial_sort(samples.begin(), samples.begin() + 2, samples.end(),
                    [](const auto &a, const auto &b) { return a.first > b.first; });
  LD best = samples[0].first;
  for (int s = 0; s < 2; s++) {
    LD a = 2 * pi * (samples[s].second - 1) / N, b = 2 * pi * (samples[s].second + 1) / N;
    const LD ratio = (std::sqrt(5.0L) - 1) / 2;
    for (int it = 0; it < 36; it++) {
      const LD x1 = b - ratio * (b - a), x2 = a + ratio * (b - a);
      if (rim_point_depth(r, rim_point(k, u, rho, x1)) > rim_point_depth(r, rim_point(k, u, rho, x2)))
        b = x2;
      else
        a = x1;
    }
    best = std::max(best, rim_point_depth(r, rim_point(k, u, rho, (a + b) / 2)));
  }
  return best;
}

}    // namespace

TEST(WallShapes, RimAgainstBruteForce)
{
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int overlapping = 0;
  for (int k = 0; k < 8; k++) {
    RawEllipsoid r = random_ellipsoid(rng);
    r.c[0] = r.c[1] = r.c[2] = 0.0;
    const Vec3 axis = random_unit(rng), centre(0.3, -0.2, 0.1);
    const double rho = 1.5 + 2.0 * u(rng);
    // a rim point within -0.05 to 0.3 of the smallest semi-axis of the particle's supporting
    // plane along a random direction n normal to the rim there, inside it (the rim grazes the
    // particle, shallower than its medial surface, where the depth along the rim has a kink)
    const double theta = 2.0 * PI * u(rng);
    const V3L q0 = rim_point(centre, axis, rho, theta);
    const Vec3 e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
    const Vec3 tangent = -std::sin(theta) * e1 + std::cos(theta) * e2;
    Vec3 n = random_unit(rng);
    n = (n - n.dot(tangent) * tangent).normalized();
    const double depth = (0.35 * u(rng) - 0.05) * std::min(r.axes[1], r.axes[2]);
    const Vec3 offset = -(support(kernel_ellipsoid(r).inverse_form, n) - depth) * n;
    for (int d = 0; d < 3; d++) r.c[d] = static_cast<double>(q0[d]) + offset[d];
    const ContactGeometry g = ellipsoid_rim_contact(kernel_ellipsoid(r), centre, axis, rho, -2.0 * rho);
    ASSERT_TRUE(g.status == Status::Overlapping || g.status == Status::Separated)
        << static_cast<int>(g.status) << " case " << k;
    // the reported point's depth is the oracle's, and no rim point is deeper
    EXPECT_NEAR(g.overlap, static_cast<double>(rim_point_depth(r, to_ld(g.point_b))), 1e-10);
    EXPECT_NEAR(g.overlap, static_cast<double>(rim_oracle(r, centre, axis, rho)), 1e-10);
    EXPECT_NEAR(std::fabs(axis.dot(g.point_b - centre)), 0.0, 1e-12);
    EXPECT_NEAR((g.point_a - g.overlap * g.normal - g.point_b).norm(), 0.0, 1e-12);
    if (g.status == Status::Overlapping) overlapping++;
  }
  EXPECT_GE(overlapping, 4);
}

// a sphere meets a rim at the rim point nearest to its centre: LAMMPS's segment clamped to
// the end (overlap r - |c - q|, R* from -2 rho)
TEST(WallShapes, SphereAtRimClosedForm)
{
  const double r = 0.5, quat[4] = {1, 0, 0, 0};
  WallSurface cone;
  cone.shape = WallShape::Cone;
  cone.center = Vec3(0.0, 0.0, 1.0);
  cone.radius = 1.0;
  cone.slope = 0.5;
  cone.cap_lo = 0.0;    // the outlet: radius 1 at z = 1
  // the first centre above the outlet (its foot on the side would lie below it), two below
  for (const Vec3 &c : {Vec3(0.7, 0.1, 1.05), Vec3(0.75, -0.05, 0.9), Vec3(0.5, 0.5, 0.8)}) {
    const Ellipsoid e = make_ellipsoid(c, quat, Vec3(r, r, r));
    const ContactGeometry g = wall_contact(e, cone);
    const Vec3 radial = Vec3(c[0], c[1], 0.0).normalized();
    const Vec3 q = Vec3(0.0, 0.0, 1.0) + radial;
    ASSERT_EQ(g.status, Status::Overlapping);
    EXPECT_NEAR(g.overlap, r - (q - c).norm(), 1e-13);
    EXPECT_NEAR((g.normal - (q - c).normalized()).norm(), 0.0, 1e-9);
    EXPECT_NEAR((g.point_b - q).norm(), 0.0, 1e-9);
    EXPECT_NEAR(g.effective_radius, r * (-2.0) / (r - 2.0), 1e-13);
  }
}

// the finite side's overlap and normal are continuous where its foot crosses the end (the side
// gives way to the rim): a tilted ellipsoid slid along a hopper's axis past its outlet
TEST(WallShapes, FiniteSideContinuousAcrossItsEnd)
{
  const double quat[4] = {0.9, 0.3, -0.2, 0.25};
  WallSurface cone;
  cone.shape = WallShape::Cone;
  cone.radius = 1.2;
  cone.slope = 0.6;
  cone.cap_lo = 0.0;
  int side = 0, rims = 0;
  ContactGeometry last;
  for (int k = 0; k <= 400; k++) {
    const double s = 0.6 - 0.002 * k;
    // the centre kept near the side as it slides
    const Ellipsoid e = make_ellipsoid(Vec3(1.2 + 0.6 * s - 0.35, 0.05, s), quat, Vec3(0.5, 0.3, 0.2));
    const ContactGeometry g = wall_contact(e, cone);
    if (g.status != Status::Overlapping) break;    // the particle left the rim
    (g.point_b[2] > 1e-12 ? side : rims)++;
    if (k > 0) {
      EXPECT_LT(std::fabs(g.overlap - last.overlap), 0.004) << s;
      EXPECT_LT((g.normal - last.normal).norm(), 0.02) << s;
    }
    last = g;
  }
  EXPECT_GT(side, 20);
  EXPECT_GT(rims, 20);
}

// a particle passing through an outlet wider than it meets nothing; the side continued past
// the outlet (the infinite cone) would cut it
TEST(WallShapes, OutletWiderThanTheParticleIsAHole)
{
  const double quat[4] = {1, 0.2, 0.1, 0};
  const Ellipsoid e = make_ellipsoid(Vec3(0.02, 0.0, 0.1), quat, Vec3(0.75, 0.6, 0.5));
  WallSurface cone;
  cone.shape = WallShape::Cone;
  cone.radius = 0.8;    // region cone z 0 0 0.8 3.0 0 4
  cone.slope = 2.2 / 4.0;
  EXPECT_EQ(wall_contact(e, cone).status, Status::Overlapping);    // the infinite cone
  cone.cap_lo = 0.0;
  cone.cap_hi = 4.0;
  EXPECT_EQ(wall_contact(e, cone).status, Status::Separated);
  // past the outlet: free of the rim
  EXPECT_EQ(wall_contact(make_ellipsoid(Vec3(0.02, 0.0, -0.3), quat, Vec3(0.75, 0.6, 0.5)), cone)
                .status,
            Status::Separated);
}

// ---------------------------------------------------------------------------------------
// Several contact regions of one concave face

namespace {

Ellipsoid rod(const Vec3 &centre, const Mat3 &rotation, const Vec3 &semi_axes)
{
  return make_ellipsoid(centre, rotation, semi_axes);
}

Mat3 turn(const Vec3 &axis, double angle)
{
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

}    // namespace

// a rod (shape 6 1 1) tilted across a pipe narrower than it, centred on its axis: both ends
// touch, as deep as each other, pushed in opposite directions (net force 0, as two planes at
// the same places give); the deepest contact alone was one of them
TEST(WallShapes, SymmetricRodInAPipeTouchesBothSides)
{
  WallSurface pipe;
  pipe.shape = WallShape::Cylinder;
  pipe.axis = Vec3::UnitZ();
  pipe.radius = 2.5;
  // the axis through the rod's centre, or a round-off away (the secular equation's roots
  // next to its poles: counted from them)
  for (const Vec3 &offset : {Vec3(0.0, 0.0, 0.0), Vec3(1e-15, -3e-16, 0.0)})
  for (const WallShape shape : {WallShape::Cylinder, WallShape::Cone}) {
    pipe.shape = shape;    // a cone of slope 0 is the cylinder
    pipe.center = offset;
    const Ellipsoid e = rod(Vec3::Zero(), turn(Vec3(0.3, 1.0, 0.0), 0.5), Vec3(3.0, 0.5, 0.5));
    const FaceContacts found = wall_contacts(e, pipe);
    ASSERT_EQ(found.count, 2);
    const ContactGeometry &a = found.contact[0], &b = found.contact[1];
    EXPECT_EQ(a.status, Status::Overlapping);
    EXPECT_EQ(b.status, Status::Overlapping);
    EXPECT_NEAR(a.overlap, b.overlap, 1e-12);
    EXPECT_NEAR((a.normal + b.normal).norm(), 0.0, 1e-9);
    EXPECT_NEAR((a.point_a + b.point_a).norm(), 0.0, 1e-9);
    EXPECT_NEAR(a.overlap, wall_contact(e, pipe).overlap, 1e-12);
  }
}

// a flat rod lying along the wall of a pipe, its ends beyond it, turned about its long axis:
// its middle leaves the wall (the neck between the two contact regions crosses zero: one
// region splits into two) and the overlaps and normals change continuously through it
TEST(WallShapes, ContactsContinuousWhereARegionSplits)
{
  WallSurface pipe;
  pipe.shape = WallShape::Cylinder;
  pipe.axis = Vec3::UnitZ();
  pipe.radius = 2.0;
  const Vec3 semi(1.2, 0.3, 0.12), long_axis = turn(Vec3::UnitZ(), 0.03) * Vec3::UnitY();
  FaceContacts last;
  double neck_first = 0.0, neck_last = 0.0;
  for (int k = 0; k <= 800; k++) {
    const double angle = 0.5 * PI * k / 800;
    // the rod's long axis along y (tilted a little), its width along x turning towards z
    const Mat3 r = turn(long_axis, angle) * turn(Vec3::UnitZ(), 0.03) * turn(Vec3::UnitZ(), 0.5 * PI);
    const Ellipsoid e = rod(Vec3(1.75, 0.0, 0.0), r, semi);
    const FaceContacts found = wall_contacts(e, pipe);
    ASSERT_EQ(found.count, 2) << angle;
    // the middle's reach beyond the wall: the neck
    const double middle = 1.75 + support(e.inverse_form, Vec3::UnitX()) - pipe.radius;
    (k == 0 ? neck_first : neck_last) = middle;
    if (k > 0)
      for (int c = 0; c < 2; c++) {
        EXPECT_LT(std::fabs(found.contact[c].overlap - last.contact[c].overlap), 1e-3) << angle;
        EXPECT_LT((found.contact[c].normal - last.contact[c].normal).norm(), 1e-3) << angle;
      }
    last = found;
  }
  EXPECT_GT(neck_first, 0.02);    // one region at first
  EXPECT_LT(neck_last, -0.05);    // two at the end
}

// the same rod centred in a bowl narrower than it (or a round-off away), every way round:
// both tips, as deep
TEST(WallShapes, SymmetricRodInABowlTouchesBothSides)
{
  WallSurface bowl;
  bowl.shape = WallShape::Sphere;
  bowl.center = Vec3(0.2, -0.1, 0.3);
  bowl.radius = 2.9;
  for (const double angle : {0.0, 0.4, 1.3, 2.9}) {
    const Vec3 nudge = angle > 2.0 ? Vec3(3e-19, -1e-18, 2e-19)
        : angle > 1.0              ? Vec3(1e-15, 2e-16, -1e-15)
                                   : Vec3(0.0, 0.0, 0.0);
    const Ellipsoid e =
        rod(bowl.center + nudge, turn(Vec3(0.3, 1.0, -0.5), angle), Vec3(3.0, 0.5, 0.4));
    const FaceContacts found = wall_contacts(e, bowl);
    ASSERT_EQ(found.count, 2) << angle;
    const ContactGeometry &a = found.contact[0], &b = found.contact[1];
    EXPECT_EQ(a.status, Status::Overlapping);
    EXPECT_NEAR(a.overlap, 0.1, 1e-12);
    EXPECT_NEAR(b.overlap, 0.1, 1e-12);
    EXPECT_NEAR((a.normal + b.normal).norm(), 0.0, 1e-12);
    EXPECT_NEAR((a.point_a - b.point_a).norm(), 6.0, 1e-12);
  }
}

// the local maxima of the distance from a point over an ellipsoid's surface and the neck
// between two of them against a grid of 100 x 200 angles: its local maxima refined by pattern
// search (to 1e-10), and the neck by flooding the grid from the top (the value at which the
// two maxima's regions join: to the grid's spacing)
TEST(WallShapes, TwoMaximaAndTheirNeckAgainstBruteForce)
{
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const LD pi = 3.141592653589793238462643383279502884L;
  constexpr int NT = 100, NP = 200;
  int pairs = 0;
  for (int k = 0; k < 16; k++) {
    RawEllipsoid r = random_ellipsoid(rng);
    r.axes[1] = 0.1 + 0.5 * u(rng), r.axes[2] = 0.1 + 0.5 * u(rng);    // elongated
    for (double &c : r.c) c = 0.0;
    const Vec3 s = 0.35 * u(rng) * random_unit(rng);    // the bowl's centre
    auto dist = [&](int i, int j) {
      const V3L p = surface_point(r, pi * (i + 0.5) / NT, 2 * pi * j / NP);
      return norm3(V3L{p[0] - s[0], p[1] - s[1], p[2] - s[2]});
    };
    std::vector<LD> d(NT * NP);
    for (int i = 0; i < NT; i++)
      for (int j = 0; j < NP; j++) d[i * NP + j] = dist(i, j);
    auto neighbours = [&](int n) {
      const int i = n / NP, j = n % NP;
      std::vector<int> out;
      for (int di = -1; di <= 1; di++)
        for (int dj = -1; dj <= 1; dj++) {
          if (di == 0 && dj == 0) continue;
          const int ii = i + di;
          if (ii < 0 || ii >= NT) continue;
          out.push_back(ii * NP + (j + dj + NP) % NP);
        }
      return out;
    };
    // flooding: join cells from the highest down; two regions with a grid maximum each meet
    std::vector<int> order(NT * NP), parent(NT * NP, -1);
    for (int n = 0; n < NT * NP; n++) order[n] = n;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return d[a] > d[b]; });
    std::function<int(int)> find = [&](int n) { return parent[n] == n ? n : parent[n] = find(parent[n]); };
    // a region whose top rises less than 1e-4 above where it joins a higher one is the
    // grid's, not a maximum
    std::vector<LD> top(NT * NP, 0);
    int regions = 1;
    LD neck = -1;
    for (int n : order) {
      parent[n] = n;
      top[n] = d[n];
      std::vector<int> roots;
      for (int m : neighbours(n))
        if (parent[m] >= 0) roots.push_back(find(m));
      std::sort(roots.begin(), roots.end());
      roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
      if (roots.empty()) continue;
      std::sort(roots.begin(), roots.end(), [&](int a, int b) { return top[a] > top[b]; });
      for (std::size_t q = 1; q < roots.size(); q++)
        if (top[roots[q]] - d[n] > 1e-4L && neck < 0) regions++, neck = d[n];
      for (int root : roots) parent[root] = n;
      top[n] = top[roots[0]];
    }
    // the kernel's maxima and neck (as a distance: radius 0)
    ContactGeometry two[2];
    double kernel_neck = 0.0;
    const int count = sphere_inside_contacts(kernel_ellipsoid(r), s, 1e-300, two, kernel_neck);
    ASSERT_EQ(count == 2, regions >= 2) << "case " << k;
    if (count < 2) continue;
    pairs++;
    // each kernel maximum is a local maximum of the distance: no surface point nearby farther
    for (const ContactGeometry &g : two) {
      const LD depth = g.overlap;
      const OracleResult o = deepest(r, [&](const V3L &p) {
        const LD dx = p[0] - g.point_a[0], dy = p[1] - g.point_a[1], dz = p[2] - g.point_a[2];
        if (dx * dx + dy * dy + dz * dz > 0.04L) return (LD) -1e300;
        return norm3(V3L{p[0] - s[0], p[1] - s[1], p[2] - s[2]});
      });
      EXPECT_NEAR(static_cast<double>(o.depth), static_cast<double>(depth), 1e-10) << "case " << k;
    }
    EXPECT_GT((two[0].point_a - two[1].point_a).norm(), 0.2);
    EXPECT_NEAR(kernel_neck, static_cast<double>(neck), 2e-3) << "case " << k;
  }
  EXPECT_GE(pairs, 6);
}
