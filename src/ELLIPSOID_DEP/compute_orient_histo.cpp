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
------------------------------------------------------------------------- */

#include "compute_orient_histo.h"

#include "atom.h"
#include "atom_vec_ellipsoid.h"
#include "error.h"
#include "math_const.h"
#include "math_extra.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

#include <Eigen/Dense>

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using MathConst::MY_PI;

namespace {
const char *const COLNAMES[ComputeOrientHisto::NVALUES] = {"S", "nx", "ny", "nz", "Qzz",
                                                           "cos2", "N"};
}

/* ---------------------------------------------------------------------- */

ComputeOrientHisto::ComputeOrientHisto(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), which_axis(0), nbins(18), fold(false), have_zlo(false),
    have_zhi(false), zlo_user(0.0), zhi_user(0.0), slab_id(nullptr), slab_compute(nullptr),
    hist(nullptr), hist_all(nullptr)
{
  if (!atom->ellipsoid_flag) error->all(FLERR, "Compute orient/histo requires atom style ellipsoid");

  int iarg = 3;
  while (iarg < narg) {
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "compute orient/histo", error);
    if (strcmp(arg[iarg], "axis") == 0) {
      if (strcmp(arg[iarg + 1], "long") == 0)
        which_axis = 0;
      else if (strcmp(arg[iarg + 1], "middle") == 0)
        which_axis = 1;
      else if (strcmp(arg[iarg + 1], "short") == 0)
        which_axis = 2;
      else
        error->all(FLERR, "Compute orient/histo axis must be long, middle or short");
    } else if (strcmp(arg[iarg], "bins") == 0) {
      nbins = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (nbins < 1) error->all(FLERR, "Compute orient/histo bins must be >= 1");
    } else if (strcmp(arg[iarg], "fold") == 0) {
      fold = utils::logical(FLERR, arg[iarg + 1], false, lmp) == 1;
    } else if (strcmp(arg[iarg], "zlo") == 0) {
      have_zlo = true;
      zlo_user = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "zhi") == 0) {
      have_zhi = true;
      zhi_user = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "slab") == 0) {
      delete[] slab_id;
      slab_id = utils::strdup(arg[iarg + 1]);
    } else
      error->all(FLERR, "Unknown compute orient/histo keyword: {}", arg[iarg]);
    iarg += 2;
  }
  if (slab_id && (have_zlo || have_zhi))
    error->all(FLERR, "Compute orient/histo: use either 'slab' or 'zlo'/'zhi'");
  if (have_zlo && have_zhi && !(zhi_user > zlo_user))
    error->all(FLERR, "Compute orient/histo needs zhi > zlo");

  array_flag = 1;
  size_array_rows = nbins;
  size_array_cols = 3;
  extarray = 0;
  vector_flag = 1;
  size_vector = NVALUES;
  extvector = 0;
  thermo_modify_colname = 1;

  vector = new double[NVALUES];
  for (int k = 0; k < NVALUES; k++) vector[k] = 0.0;
  memory->create(array, nbins, 3, "orient/histo:array");
  hist = new double[nbins + 8];
  hist_all = new double[nbins + 8];
  const double dtheta = (fold ? 0.5 * MY_PI : MY_PI) / nbins;
  for (int k = 0; k < nbins; k++) {
    array[k][0] = (k + 0.5) * dtheta;
    array[k][1] = array[k][2] = 0.0;
  }
}

/* ---------------------------------------------------------------------- */

ComputeOrientHisto::~ComputeOrientHisto()
{
  delete[] vector;
  memory->destroy(array);
  delete[] hist;
  delete[] hist_all;
  delete[] slab_id;
}

/* ---------------------------------------------------------------------- */

void ComputeOrientHisto::init()
{
  if (!atom->style_match("ellipsoid"))
    error->all(FLERR, "Compute orient/histo requires atom style ellipsoid");
  if (slab_id) {
    slab_compute = modify->get_compute_by_id(slab_id);
    if (!slab_compute) error->all(FLERR, "Compute orient/histo: no compute with ID {}", slab_id);
    if (strcmp(slab_compute->style, "packing/ellipsoid") != 0)
      error->all(FLERR, "Compute orient/histo: slab compute {} is not packing/ellipsoid", slab_id);
  }
}

/* ---------------------------------------------------------------------- */

std::string ComputeOrientHisto::get_thermo_colname(int n)
{
  if (n >= 0 && n < NVALUES) return fmt::format("c_{}:{}", id, COLNAMES[n]);
  return {};
}

/* ---------------------------------------------------------------------- */

void ComputeOrientHisto::compute_vector()
{
  invoked_vector = update->ntimestep;
  tally();
}

void ComputeOrientHisto::compute_array()
{
  invoked_array = update->ntimestep;
  tally();
}

/* ---------------------------------------------------------------------- */

void ComputeOrientHisto::tally()
{
  double zlo = -HUGE_VAL, zhi = HUGE_VAL;
  if (have_zlo) zlo = zlo_user;
  if (have_zhi) zhi = zhi_user;
  if (slab_compute) {
    if (!(slab_compute->invoked_flag & Compute::INVOKED_VECTOR) ||
        slab_compute->invoked_vector != update->ntimestep) {
      slab_compute->compute_vector();
      slab_compute->invoked_flag |= Compute::INVOKED_VECTOR;
    }
    zlo = slab_compute->vector[4];
    zhi = slab_compute->vector[5];
  }

  auto *avec = dynamic_cast<AtomVecEllipsoid *>(atom->style_match("ellipsoid"));
  if (!avec) error->all(FLERR, "Compute orient/histo requires atom style ellipsoid");
  const int nlocal = atom->nlocal;
  int *mask = atom->mask;
  int *ellipsoid = atom->ellipsoid;
  double **x = atom->x;
  const double range = fold ? 0.5 * MY_PI : MY_PI;
  const double dtheta = range / nbins;

  // hist[0..nbins): counts; then Q sums (uu: xx yy zz xy xz yz), the particle count, bad shapes
  double *acc = hist + nbins;
  for (int k = 0; k < nbins + 8; k++) hist[k] = 0.0;

  auto bin_of = [&](double cz) {
    cz = cz > 1.0 ? 1.0 : (cz < -1.0 ? -1.0 : cz);
    int k = static_cast<int>(std::acos(cz) / dtheta);
    return k >= nbins ? nbins - 1 : (k < 0 ? 0 : k);
  };

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    if (!(x[i][2] >= zlo && x[i][2] < zhi)) continue;
    if (ellipsoid[i] < 0) {
      acc[7] += 1.0;
      continue;
    }
    const int b = ellipsoid[i];
    const double *shape = atom->superellipsoid_flag ? avec->bonus_super[b].shape : avec->bonus[b].shape;
    const double *quat = atom->superellipsoid_flag ? avec->bonus_super[b].quat : avec->bonus[b].quat;
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
    double rot[3][3];
    double qn[4] = {quat[0], quat[1], quat[2], quat[3]};
    MathExtra::qnormalize(qn);
    MathExtra::quat_to_mat(qn, rot);
    const double u[3] = {rot[0][axis], rot[1][axis], rot[2][axis]};    // body axis in box frame

    if (fold) {
      hist[bin_of(std::fabs(u[2]))] += 1.0;
    } else {
      hist[bin_of(u[2])] += 1.0;
      hist[bin_of(-u[2])] += 1.0;
    }
    acc[0] += u[0] * u[0];
    acc[1] += u[1] * u[1];
    acc[2] += u[2] * u[2];
    acc[3] += u[0] * u[1];
    acc[4] += u[0] * u[2];
    acc[5] += u[1] * u[2];
    acc[6] += 1.0;
  }

  MPI_Allreduce(hist, hist_all, nbins + 8, MPI_DOUBLE, MPI_SUM, world);
  if (hist_all[nbins + 7] > 0.0)
    error->all(FLERR, "Compute orient/histo: every atom of the group must have a shape");

  const double npart = hist_all[nbins + 6];
  double total = 0.0;
  for (int k = 0; k < nbins; k++) total += hist_all[k];
  for (int k = 0; k < nbins; k++) {
    const double domega = 2.0 * MY_PI * (std::cos(k * dtheta) - std::cos((k + 1) * dtheta));
    array[k][0] = (k + 0.5) * dtheta;
    array[k][1] = total > 0.0 ? hist_all[k] / (total * domega) : 0.0;
    array[k][2] = total > 0.0 ? hist_all[k] / total : 0.0;
  }

  for (int k = 0; k < NVALUES; k++) vector[k] = 0.0;
  vector[6] = npart;
  if (npart > 0.0) {
    double m[6];
    for (int k = 0; k < 6; k++) m[k] = hist_all[nbins + k] / npart;
    Eigen::Matrix3d Q;
    Q << 1.5 * m[0] - 0.5, 1.5 * m[3], 1.5 * m[4],    //
        1.5 * m[3], 1.5 * m[1] - 0.5, 1.5 * m[5],     //
        1.5 * m[4], 1.5 * m[5], 1.5 * m[2] - 0.5;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(Q);
    const Eigen::Vector3d evals = solver.eigenvalues();    // increasing
    Eigen::Vector3d dir = solver.eigenvectors().col(2);
    if (dir[2] < 0.0 || (dir[2] == 0.0 && (dir[0] < 0.0 || (dir[0] == 0.0 && dir[1] < 0.0))))
      dir = -dir;
    vector[0] = evals[2];
    vector[1] = dir[0];
    vector[2] = dir[1];
    vector[3] = dir[2];
    vector[4] = Q(2, 2);
    vector[5] = m[2];
  }
}
