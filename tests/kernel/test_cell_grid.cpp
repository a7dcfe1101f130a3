// GoogleTest suite of the cell grid (ellipsoid_cell_grid.h) against brute force: every point
// within reach of a query's nearest periodic image is visited, once, for every combination of
// periodic dimensions, boxes narrower than three cells, points outside the box and points
// at the reach itself; and the grid visits only a small part of a large box.
#include "ellipsoid_cell_grid.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace EllipsoidDep;

namespace {

struct Box {
  Eigen::Vector3d lo, hi;
  std::array<bool, 3> periodic;
};

// LAMMPS's Domain::minimum_image of an orthogonal box, one dimension at a time
Eigen::Vector3d minimum_image(Eigen::Vector3d d, const Box &box)
{
  for (int k = 0; k < 3; k++) {
    if (!box.periodic[k]) continue;
    const double prd = box.hi[k] - box.lo[k], half = 0.5 * prd;
    while (std::fabs(d[k]) > half) d[k] += d[k] < 0.0 ? prd : -prd;
  }
  return d;
}

// per point, how often any_near visited it
std::vector<int> visits(const CellGrid &grid, const Eigen::Vector3d &x)
{
  std::vector<int> seen(grid.size(), 0);
  const bool stopped = grid.any_near(x, [&](int i) {
    seen[i]++;
    return false;
  });
  EXPECT_FALSE(stopped);
  return seen;
}

Eigen::Vector3d uniform_in(std::mt19937_64 &rng, const Eigen::Vector3d &lo,
                           const Eigen::Vector3d &hi)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  return lo + (hi - lo).cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
}

}    // namespace

TEST(CellGrid, VisitsEveryPointWithinReachOnce)
{
  std::mt19937_64 rng(20261202);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  int found = 0;
  for (int flags = 0; flags < 8; flags++) {
    for (int trial = 0; trial < 20; trial++) {
      Box box;
      const double reach = 0.2 + 1.8 * u(rng);
      for (int k = 0; k < 3; k++) {
        box.periodic[k] = (flags >> k) & 1;
        box.lo[k] = -10.0 + 20.0 * u(rng);
        box.hi[k] = box.lo[k] + reach * (0.3 + 8.0 * u(rng));    // 0 to 8 cells wide
      }
      // some grids capped to few cells, down to one
      const std::size_t max_cells = trial % 4 == 0 ? 1 + trial % 7 : 100000;
      CellGrid grid(box.lo, box.hi, box.periodic, reach, max_cells);

      const Eigen::Vector3d margin = Eigen::Vector3d::Constant(reach);
      std::vector<Eigen::Vector3d> queries, points;
      for (int q = 0; q < 30; q++) queries.push_back(uniform_in(rng, box.lo, box.hi));
      for (int p = 0; p < 200; p++)    // also outside the box, as a periodic pour's neighbours
        points.push_back(uniform_in(rng, box.lo - margin, box.hi + margin));
      // points at the reach of a query, often across a periodic boundary
      for (int p = 0; p < 100; p++) {
        Eigen::Vector3d x = queries[p % queries.size()] +
            reach * (1.0 - 1e-14 * u(rng)) * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
        for (int k = 0; k < 3; k++)
          if (box.periodic[k] && (x[k] < box.lo[k] || x[k] >= box.hi[k]))
            x[k] += x[k] < box.lo[k] ? box.hi[k] - box.lo[k] : box.lo[k] - box.hi[k];
        points.push_back(x);
      }
      for (const Eigen::Vector3d &x : points) grid.insert(x);
      ASSERT_EQ(grid.size(), points.size());

      for (const Eigen::Vector3d &q : queries) {
        const std::vector<int> seen = visits(grid, q);
        for (std::size_t i = 0; i < points.size(); i++) {
          ASSERT_LE(seen[i], 1) << "point " << i << " visited twice, flags " << flags;
          if (minimum_image(q - points[i], box).norm() > reach) continue;
          found++;
          ASSERT_EQ(seen[i], 1) << "point " << i << " within reach not visited, flags " << flags
                                << ", trial " << trial;
        }
      }
    }
  }
  EXPECT_GT(found, 8 * 20 * 100);    // the points at the reach were there to be found
}

// a grid that visited every point would pass the test above
TEST(CellGrid, VisitsFewPointsOfALargeBox)
{
  std::mt19937_64 rng(7);
  const Box box{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(20, 20, 20), {true, true, false}};
  CellGrid grid(box.lo, box.hi, box.periodic, 1.0, 8000);
  for (int p = 0; p < 8000; p++) grid.insert(uniform_in(rng, box.lo, box.hi));
  std::size_t visited = 0;
  for (int q = 0; q < 100; q++) {
    const std::vector<int> seen = visits(grid, uniform_in(rng, box.lo, box.hi));
    for (int s : seen) visited += s;
  }
  // 27 cells of 1 in 8000 cells: about 27 points a query
  EXPECT_LT(visited, 100u * 50u);
}

TEST(CellGrid, StopsAtTheFirstTrueVisit)
{
  const Box box{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 3, 3), {true, true, true}};
  CellGrid grid(box.lo, box.hi, box.periodic, 1.0, 100);
  int calls = 0;
  auto stop = [&](int) {
    calls++;
    return true;
  };
  EXPECT_FALSE(grid.any_near(Eigen::Vector3d(1, 1, 1), stop));
  EXPECT_EQ(calls, 0);
  for (int p = 0; p < 5; p++) grid.insert(Eigen::Vector3d(1.5, 1.5, 1.5));
  EXPECT_TRUE(grid.any_near(Eigen::Vector3d(1, 1, 1), stop));
  EXPECT_EQ(calls, 1);
}

// a region far larger than its particles: uncapped, 1e15 cells could not be allocated
TEST(CellGrid, AtMostMaxCells)
{
  const Box box{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1e5, 1e5, 1e5), {true, false, false}};
  CellGrid grid(box.lo, box.hi, box.periodic, 1.0, 1000);
  grid.insert(Eigen::Vector3d(0.5, 0.5, 0.5));
  grid.insert(Eigen::Vector3d(1e5 - 0.2, 0.5, 0.5));    // a periodic neighbour of the first
  const std::vector<int> seen = visits(grid, Eigen::Vector3d(0.1, 0.5, 0.5));
  EXPECT_EQ(seen, std::vector<int>({1, 1}));
}

// the pour stops at the first overlap, most often in the candidate's own cell
TEST(CellGrid, VisitsTheQuerysOwnCellFirst)
{
  // 5 cells of 1.2 per dimension
  const Box box{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(6, 6, 6), {true, true, false}};
  CellGrid grid(box.lo, box.hi, box.periodic, 1.0, 1000);
  grid.insert(Eigen::Vector3d(2.0, 2.0, 2.0));    // a neighbouring cell, in every dimension
  grid.insert(Eigen::Vector3d(3.5, 3.5, 3.5));    // the query's cell
  int first = -1;
  grid.any_near(Eigen::Vector3d(3.0, 3.0, 3.0), [&](int i) {
    first = i;
    return true;
  });
  EXPECT_EQ(first, 1);
}

// a point or a query that is nowhere (NaN, inf) falls into some cell instead of an undefined
// integer conversion; a finite query far from it does not see it
TEST(CellGrid, NonFinitePointsHaveACell)
{
  const Box box{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(6, 6, 6), {true, true, false}};
  CellGrid grid(box.lo, box.hi, box.periodic, 1.0, 1000);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  grid.insert(Eigen::Vector3d(nan, 1.0, 1.0));
  grid.insert(Eigen::Vector3d(1.0, inf, -inf));
  grid.insert(Eigen::Vector3d(3.5, 3.5, 3.5));
  EXPECT_EQ(visits(grid, Eigen::Vector3d(3.5, 3.5, 3.5)), std::vector<int>({0, 0, 1}));
  EXPECT_EQ(grid.size(), 3u);
  visits(grid, Eigen::Vector3d(nan, nan, inf));    // defined, whatever it visits
}
