/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: cells that find the stored points near a query point, with periodic
   wrap-around in any dimension (the overlap search of fix pour/ellipsoid).

   Engine independent: C++17 + Eigen only. No LAMMPS header, no MPI, no I/O, no exceptions.

   The promise: any_near(x, visit) visits every stored point whose nearest periodic image is
   within `reach` of x, and may visit others; each point at most once, those of x's own cell
   first (where a caller that stops at the first hit is likeliest to stop). The nearest image is
   taken per dimension, as LAMMPS's Domain::minimum_image does in an orthogonal box. Cells are
   at least `reach` wide (plus a slack for rounding), so such a point lies in x's cell or in a
   neighbouring one.
   - A periodic dimension wraps with the period hi - lo; with fewer than 3 cells in it, every
     cell of that dimension is a neighbour.
   - In a dimension that is not periodic, positions outside [lo, hi] fall in the edge cells.
   - At most max_cells cells (cells are widened): memory stays in proportion to the points.
   - Points are numbered from 0 in the order of insert(). A non-finite position (NaN, inf) is
     put in some cell, so that nothing is undefined; it is within reach of no point.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_CELL_GRID_H
#define ELLIPSOID_DEP_ELLIPSOID_CELL_GRID_H

#include <Eigen/Dense>

#include <array>
#include <cstddef>
#include <vector>

namespace EllipsoidDep {

class CellGrid {
 public:
  CellGrid(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi,
           const std::array<bool, 3> &periodic, double reach, std::size_t max_cells);

  void insert(const Eigen::Vector3d &x);    // the next point, numbered size() before the call
  std::size_t size() const { return next.size(); }

  // calls visit(index) on the points near x until one returns true; whether one did
  template <class Visit> bool any_near(const Eigen::Vector3d &x, Visit visit) const;

 private:
  Eigen::Vector3d lo, width;
  std::array<int, 3> count;
  std::array<bool, 3> periodic;
  std::vector<int> head;    // per cell: its last point, -1 when empty
  std::vector<int> next;    // per point: the point inserted before it in its cell, or -1

  int cell(int dim, double value) const;
  int neighbours(int dim, int c, int out[3]) const;
  int index(int cx, int cy, int cz) const { return (cz * count[1] + cy) * count[0] + cx; }
};

template <class Visit> bool CellGrid::any_near(const Eigen::Vector3d &x, Visit visit) const
{
  int cells[3][3], n[3];
  for (int d = 0; d < 3; d++) n[d] = neighbours(d, cell(d, x[d]), cells[d]);
  for (int k = 0; k < n[2]; k++)
    for (int j = 0; j < n[1]; j++)
      for (int i = 0; i < n[0]; i++)
        for (int p = head[index(cells[0][i], cells[1][j], cells[2][k])]; p >= 0; p = next[p])
          if (visit(p)) return true;
  return false;
}

}    // namespace EllipsoidDep

#endif
