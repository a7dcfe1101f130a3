// wall_clear: a particle lies on the particle side of a wall surface, apart from it (the test
// fix pour/ellipsoid makes of a new particle). Against closed forms for a plane (the support
// function along the normal) and an independent oracle for the inside of a cylinder (the
// largest distance of the particle's shadow from the axis, by the support function sampled
// over the directions normal to the axis, in long double).

#include "ellipsoid_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace EllipsoidDep;

namespace {

// a needle (1, 0.1, 0.1) whose long axis is tilted by theta from x towards z
Ellipsoid tilted_needle(const Vec3 &centre, double theta)
{
  const double q[4] = {std::cos(0.5 * theta), 0.0, -std::sin(0.5 * theta), 0.0};
  return make_ellipsoid(centre, q, Vec3(1.0, 0.1, 0.1));
}

WallSurface floor_plane()
{
  WallSurface w;    // the solid z <= 0
  w.normal = Vec3::UnitZ();
  w.offset = 0.0;
  return w;
}

// the largest distance from the z axis of the ellipsoid's points: max over unit u in the xy
// plane of sqrt(u^T M u) + u.c
long double farthest_from_z_axis(const Ellipsoid &e)
{
  const long double pi = 3.141592653589793238462643383279502884L;
  auto reach = [&](long double t) {
    const long double u[2] = {std::cos(t), std::sin(t)};
    long double m = 0;
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) m += u[i] * static_cast<long double>(e.inverse_form(i, j)) * u[j];
    return std::sqrt(m) + u[0] * e.center[0] + u[1] * e.center[1];
  };
  constexpr int SAMPLES = 4000;
  long double best = 0, at = 0;
  for (int k = 0; k < SAMPLES; k++) {
    const long double t = 2 * pi * k / SAMPLES, r = reach(t);
    if (r > best) best = r, at = t;
  }
  long double lo = at - 2 * pi / SAMPLES, hi = at + 2 * pi / SAMPLES;
  for (int it = 0; it < 200; it++) {    // golden section on the bracketing interval
    const long double a = hi - 0.618033988749894848L * (hi - lo);
    const long double b = lo + 0.618033988749894848L * (hi - lo);
    if (reach(a) > reach(b))
      hi = b;
    else
      lo = a;
  }
  return std::max(best, reach(0.5L * (lo + hi)));
}

}    // namespace

TEST(WallClear, PlaneByTheExactExtent)
{
  const WallSurface w = floor_plane();
  // the centre 0.5 above: lying flat (extent 0.1) it is clear though its bounding sphere
  // (radius 1) crosses the plane; the extent sqrt(sin^2 + 0.01 cos^2) reaches 0.5 at
  // sin^2 theta = 0.24 / 0.99
  const double critical = std::asin(std::sqrt(0.24 / 0.99));
  EXPECT_TRUE(wall_clear(tilted_needle(Vec3(0, 0, 0.5), 0.0), w));
  EXPECT_TRUE(wall_clear(tilted_needle(Vec3(0, 0, 0.5), critical - 1e-6), w));
  EXPECT_FALSE(wall_clear(tilted_needle(Vec3(0, 0, 0.5), critical + 1e-6), w));
  EXPECT_FALSE(wall_clear(tilted_needle(Vec3(0, 0, 0.5), 0.5 * M_PI), w));
  // the bounding sphere clear of the plane
  EXPECT_TRUE(wall_clear(tilted_needle(Vec3(0, 0, 1.0 + 1e-9), 0.5 * M_PI), w));
}

TEST(WallClear, CentreBeyondTheSurface)
{
  // a small particle wholly on the solid side is not clear (no contact would be found)
  EXPECT_FALSE(wall_clear(tilted_needle(Vec3(0, 0, -5.0), 0.0), floor_plane()));
  WallSurface solid;
  solid.shape = WallShape::Box;
  solid.lower = Vec3(-3, -3, -3);
  solid.upper = Vec3(3, 3, 3);
  EXPECT_FALSE(wall_clear(tilted_needle(Vec3(0.5, 0, 0), 0.0), solid));
  EXPECT_TRUE(wall_clear(tilted_needle(Vec3(4.2, 0, 0), 0.0), solid));
  EXPECT_FALSE(wall_clear(tilted_needle(Vec3(3.9, 0, 0), 0.0), solid));
}

TEST(WallClear, InsideCylinderAgainstOracle)
{
  WallSurface w;
  w.shape = WallShape::Cylinder;
  w.radius = 2.0;
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  int clear = 0, blocked = 0;
  for (int k = 0; k < 400; k++) {
    double q[4];
    for (double &qk : q) qk = g(rng);
    const Vec3 axes(1.0, 0.05 + 0.95 * u(rng), 0.05 + 0.4 * u(rng));
    const double r = 1.9 * std::sqrt(u(rng)), phi = 2 * M_PI * u(rng);
    const Ellipsoid e = make_ellipsoid(Vec3(r * std::cos(phi), r * std::sin(phi), u(rng)), q, axes);
    const long double reach = farthest_from_z_axis(e);
    if (std::fabs(static_cast<double>(reach) - w.radius) < 1e-9) continue;
    const bool expected = reach < w.radius;
    EXPECT_EQ(wall_clear(e, w), expected) << "case " << k << " reach " << (double) reach;
    (expected ? clear : blocked)++;
  }
  EXPECT_GT(clear, 50);
  EXPECT_GT(blocked, 50);
}
