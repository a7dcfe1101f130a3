// The curved wall shapes (sphere, cylinder; inside and outside) against an independent
// brute-force oracle: the ellipsoid surface parametrised by two angles in long double, the
// depth beyond the wall's surface sampled densely and refined by a shrinking pattern search.
// The oracle shares no code with the kernel's secular equation (ellipsoid_point_extremum).

#include "ellipsoid_kernel.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>

using namespace EllipsoidDep;

namespace {

using LD = long double;
using V3L = std::array<LD, 3>;

// an ellipsoid by its raw inputs: centre, quaternion (w, x, y, z), semi-axes
struct RawEllipsoid {
  double c[3], q[4], axes[3];
};

// the surface point at angles (theta, phi), the rotation built from the quaternion here
V3L surface_point(const RawEllipsoid &r, LD theta, LD phi)
{
  LD w = r.q[0], x = r.q[1], y = r.q[2], z = r.q[3];
  const LD n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n, x /= n, y /= n, z /= n;
  const LD rot[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                        {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                        {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
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
