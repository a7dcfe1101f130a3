/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: cells for the points near a query point (see ellipsoid_cell_grid.h)

   Why a point two or more cells away (in any dimension, counted around the period where it
   wraps) is beyond reach: the cells between them are at least `reach` wide. The cell
   index and the caller's distance are both rounded, by a few ulp of the coordinates; the
   cells are wider than reach by 1e-9 of reach plus the largest coordinate, far more than
   that.
------------------------------------------------------------------------- */

#include "ellipsoid_cell_grid.h"

#include <algorithm>
#include <cmath>

namespace EllipsoidDep {

CellGrid::CellGrid(const Eigen::Vector3d &lo_, const Eigen::Vector3d &hi_,
                   const std::array<bool, 3> &periodic_, double reach, std::size_t max_cells) :
    lo(lo_), periodic(periodic_)
{
  const Eigen::Vector3d extent = hi_ - lo_;
  const double magnitude = std::max(lo_.cwiseAbs().maxCoeff(), hi_.cwiseAbs().maxCoeff());
  double w = reach + 1e-9 * (reach + magnitude);
  const double cap = static_cast<double>(std::max<std::size_t>(max_cells, 1));
  std::array<double, 3> n;
  while (true) {
    for (int d = 0; d < 3; d++) n[d] = std::max(1.0, std::floor(extent[d] / w));
    const double cells = n[0] * n[1] * n[2];
    if (cells <= cap) break;
    w *= std::cbrt(cells / cap);
  }
  for (int d = 0; d < 3; d++) {
    count[d] = static_cast<int>(n[d]);
    // a periodic dimension holds a whole number of cells; a dimension narrower than one
    // cell has one of width w
    width[d] = std::max(extent[d] / n[d], w);
  }
  head.assign(static_cast<std::size_t>(count[0]) * count[1] * count[2], -1);
}

void CellGrid::insert(const Eigen::Vector3d &x)
{
  const int c = index(cell(0, x[0]), cell(1, x[1]), cell(2, x[2]));
  next.push_back(head[c]);
  head[c] = static_cast<int>(next.size()) - 1;
}

int CellGrid::cell(int dim, double value) const
{
  double c = std::floor((value - lo[dim]) / width[dim]);
  if (!std::isfinite(c)) return 0;    // a point nowhere (NaN, inf): any cell, but a defined one
  if (periodic[dim]) {
    c = std::fmod(c, count[dim]);    // exact for whole numbers
    if (c < 0.0) c += count[dim];
  } else {
    c = std::clamp(c, 0.0, count[dim] - 1.0);
  }
  return static_cast<int>(c);
}

// c and the cells next to it in one dimension, each once; c first, where a query's overlaps
// are likeliest, so that a caller stopping at the first one stops sooner
int CellGrid::neighbours(int dim, int c, int out[3]) const
{
  const int n = count[dim];
  int m = 0;
  out[m++] = c;
  for (int e : {c - 1, c + 1}) {
    if (periodic[dim])
      e = (e + n) % n;
    else if (e < 0 || e >= n)
      continue;
    if (e != out[0] && (m == 1 || e != out[1])) out[m++] = e;    // fewer than 3 cells
  }
  return m;
}

}    // namespace EllipsoidDep
