/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: compute orient/histo (doc/compute_orient_histo.rst)

   u = unit vector along the chosen principal axis (longest / middle / shortest semi-axis).
   Global array, one row per bin of theta (angle between the axis line and +z):
     default: theta in [0, pi], each particle adds u and -u (symmetric about pi/2, directly
              comparable with contact/histo); P_k = c_k / (C dOmega_k), uniform = 1/(4 pi)
     fold yes: theta = acos|u_z| in [0, pi/2], each particle once; P_k = c_k / (C dOmega_k)
              over the upper hemisphere, uniform = 1/(2 pi)
     columns: theta_k, P_k, c_k / C
   Global vector (Q = <(3 u u^T - I)/2> over the particles):
     1 S = largest eigenvalue of Q   2-4 its eigenvector (director, n_z >= 0)
     5 Q_zz = <P2(cos theta)>   6 <cos^2 theta>   7 number of particles
   Per-atom vector: acos|u_z| in [0, pi/2] of every atom of the group, slab or not (0 for
   atoms outside the group), e.g. to colour a picture by the tilt of the long axis.

   Arguments, array and slab handling: ComputeAngleHisto (compute_angle_histo.cpp). The
   shapes and orientations come from EllipsoidAtoms (atom_style ellipsoid, with or without
   superellipsoid).
------------------------------------------------------------------------- */

#include "compute_orient_histo.h"

#include "atom.h"
#include "error.h"
#include "math_const.h"
#include "memory.h"
#include "update.h"

#include "granular_ellipsoid_atoms.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using MathConst::MY_PI;

namespace {
const char *const MISSING_SHAPE = "Compute orient/histo: every atom of the group must have a shape";
const char *const COLNAMES[ComputeOrientHisto::NVALUES] = {"S",   "nx",   "ny", "nz",
                                                           "Qzz", "cos2", "N"};
}    // namespace

/* ----------------------------------------------------------------------
   one extra sum: the atoms of the group without a shape
------------------------------------------------------------------------- */

ComputeOrientHisto::ComputeOrientHisto(LAMMPS *lmp, int narg, char **arg) :
    ComputeAngleHisto(lmp, narg, arg, "orient/histo", NVALUES, COLNAMES, 1), which_axis(0),
    fold(false), nmax(0), axis_angle(nullptr)
{
  parse_args(narg, arg);
  peratom_flag = 1;
  size_peratom_cols = 0;
}

/* ---------------------------------------------------------------------- */

ComputeOrientHisto::~ComputeOrientHisto()
{
  memory->destroy(axis_angle);
}

/* ---------------------------------------------------------------------- */

bool ComputeOrientHisto::parse_keyword(const char *key, const char *value)
{
  if (strcmp(key, "axis") == 0) {
    if (strcmp(value, "long") == 0)
      which_axis = 0;
    else if (strcmp(value, "middle") == 0)
      which_axis = 1;
    else if (strcmp(value, "short") == 0)
      which_axis = 2;
    else
      error->all(FLERR, "Compute orient/histo axis must be long, middle or short");
  } else if (strcmp(key, "fold") == 0) {
    fold = utils::logical(FLERR, value, false, lmp) == 1;
    theta_max = fold ? 0.5 * MY_PI : MY_PI;
  } else
    return false;
  return true;
}

/* ---------------------------------------------------------------------- */

void ComputeOrientHisto::init()
{
  if (!atom->style_match("ellipsoid"))
    error->all(FLERR, "Compute orient/histo requires atom style ellipsoid");
  ComputeAngleHisto::init();
}

/* ----------------------------------------------------------------------
   u = the chosen principal axis of atom i (which has a shape) in the box frame
------------------------------------------------------------------------- */

void ComputeOrientHisto::chosen_axis(const EllipsoidAtoms &ellipsoids, int i, double *u) const
{
  const double *shape = ellipsoids.shape(i);
  // rank the semi-axes, ties resolved by the lower body-axis index (stable order)
  int order[3] = {0, 1, 2};
  for (int p = 0; p < 3; p++)
    for (int q = p + 1; q < 3; q++)
      if (shape[order[q]] > shape[order[p]] ||
          (shape[order[q]] == shape[order[p]] && order[q] < order[p])) {
        const int t = order[p];
        order[p] = order[q];
        order[q] = t;
      }
  const int axis = order[which_axis];
  const EllipsoidDep::Mat3 rot = EllipsoidDep::quaternion_rotation(ellipsoids.quat(i));
  for (int d = 0; d < 3; d++) u[d] = rot(d, axis);
}

/* ---------------------------------------------------------------------- */

void ComputeOrientHisto::accumulate(const SlabOption::Bounds &slab)
{
  const EllipsoidAtoms ellipsoids(atom);
  if (!ellipsoids.avec) error->all(FLERR, "Compute orient/histo requires atom style ellipsoid");
  const int nlocal = atom->nlocal;
  int *mask = atom->mask;
  double **x = atom->x;
  double *no_shape = extra_sums();

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    if (!(x[i][2] >= slab.zlo && x[i][2] < slab.zhi)) continue;
    if (!ellipsoids.has_shape(i)) {
      no_shape[0] += 1.0;
      continue;
    }
    double u[3];
    chosen_axis(ellipsoids, i, u);
    if (fold) {
      bin(std::fabs(u[2]));
    } else {
      bin(u[2]);
      bin(-u[2]);
    }
    add_moment(u);
  }
}

/* ---------------------------------------------------------------------- */

void ComputeOrientHisto::finish_vector(const double *moments, double, double npart,
                                       const double *extra)
{
  if (extra[0] > 0.0) error->all(FLERR, MISSING_SHAPE);

  for (int k = 0; k < NVALUES; k++) vector[k] = 0.0;
  vector[PARTICLES] = npart;
  if (npart > 0.0) {
    double m[6];
    for (int k = 0; k < 6; k++) m[k] = moments[k] / npart;
    Eigen::Matrix3d Q;
    Q << 1.5 * m[0] - 0.5, 1.5 * m[3], 1.5 * m[4],    //
        1.5 * m[3], 1.5 * m[1] - 0.5, 1.5 * m[5],     //
        1.5 * m[4], 1.5 * m[5], 1.5 * m[2] - 0.5;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(Q);
    const Eigen::Vector3d evals = solver.eigenvalues();    // increasing
    Eigen::Vector3d dir = solver.eigenvectors().col(2);
    if (dir[2] < 0.0 || (dir[2] == 0.0 && (dir[0] < 0.0 || (dir[0] == 0.0 && dir[1] < 0.0))))
      dir = -dir;
    vector[S] = evals[2];
    for (int d = 0; d < 3; d++) vector[DIRECTOR + d] = dir[d];
    vector[QZZ] = Q(2, 2);
    vector[COS2] = m[2];
  }
}

/* ----------------------------------------------------------------------
   per-atom angle of the chosen axis to the vertical, acos|u_z|
------------------------------------------------------------------------- */

void ComputeOrientHisto::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  if (atom->nmax > nmax) {
    memory->destroy(axis_angle);
    nmax = atom->nmax;
    memory->create(axis_angle, nmax, "orient/histo:axis_angle");
    vector_atom = axis_angle;
  }
  const EllipsoidAtoms ellipsoids(atom);
  if (!ellipsoids.avec) error->all(FLERR, "Compute orient/histo requires atom style ellipsoid");
  const int nlocal = atom->nlocal;
  int *mask = atom->mask;
  int missing = 0;
  for (int i = 0; i < nlocal; i++) {
    axis_angle[i] = 0.0;
    if (!(mask[i] & groupbit)) continue;
    if (!ellipsoids.has_shape(i)) {
      missing = 1;
      continue;
    }
    double u[3];
    chosen_axis(ellipsoids, i, u);
    axis_angle[i] = std::acos(std::min(1.0, std::fabs(u[2])));
  }
  int any_missing = 0;
  MPI_Allreduce(&missing, &any_missing, 1, MPI_INT, MPI_MAX, world);
  if (any_missing) error->all(FLERR, MISSING_SHAPE);
}

/* ---------------------------------------------------------------------- */

double ComputeOrientHisto::memory_usage()
{
  return (double) nmax * sizeof(double);
}
