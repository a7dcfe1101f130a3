/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix pour/ellipsoid (see doc/fix_pour_ellipsoid.rst)

   The insertion schedule follows LAMMPS's fix pour (a batch that fills the region at the
   requested volume fraction every time a particle needs to fall through the region), but
   the particles are general ellipsoids:
     size   r = (abc)^(1/3) drawn from the NUMBER distribution n(r) ~ V(r) / r^3, where
            V(r) ~ (r - rmin)^(alpha-1) (rmax - r)^(beta-1) is the volume distribution:
            x ~ Beta(alpha, beta), r = rmin + x (rmax - rmin), accepted with probability
            (rmin / r)^3 (exact rejection sampling);
     shape  a = eta b, b = zeta c, so c = r (eta zeta^2)^(-1/3), b = zeta c, a = eta b;
     orientation uniform on SO(3) (Shoemake's uniform unit quaternion).
   Every rank draws the same random numbers and makes the same decisions (the overlap
   check sees the same gathered particles on every rank), and keeps the particles in its
   sub-domain, so a pour is independent of the number of ranks.
------------------------------------------------------------------------- */

#include "fix_pour_ellipsoid.h"

#include "atom.h"
#include "atom_vec_ellipsoid.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "math_const.h"
#include "memory.h"
#include "modify.h"
#include "random_park.h"
#include "region.h"
#include "update.h"

#include "granular_ellipsoid_atoms.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
using namespace EllipsoidDep;
using MathConst::MY_2PI;
using MathConst::MY_4PI3;
using MathConst::MY_PI;

static constexpr double EPSILON = 0.001;
static constexpr double MIN_ACCEPTANCE = 1.0e-4;    // size sampler: refuse hopeless ranges
static constexpr int NEAR_SIZE = 10;                // x, semi-axes, quaternion

namespace {

// integral over [0, 1] of x^(a-1) (1-x)^(b-1) w(x), singular end points removed by
// x = u^(1/a) on [0, 1/2] and 1 - x = u^(1/b) on [1/2, 1]; Simpson's rule on each half
template <class F> double beta_weighted_integral(double a, double b, F w)
{
  const int n = 4000;    // even
  auto half = [&](double p, double q, bool left) {
    const double umax = std::pow(0.5, p);
    const double h = umax / n;
    double sum = 0.0;
    for (int k = 0; k <= n; k++) {
      const double u = k * h;
      const double y = std::pow(u, 1.0 / p);    // distance from the end point
      const double x = left ? y : 1.0 - y;
      const double f = std::pow(1.0 - y, q - 1.0) * w(x) / p;
      const double weight = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
      sum += weight * f;
    }
    return sum * h / 3.0;
  };
  return half(a, b, true) + half(b, a, false);
}

}    // namespace

/* ----------------------------------------------------------------------
   fix ID group pour/ellipsoid N type seed region R [keyword value ...]
------------------------------------------------------------------------- */

FixPourEllipsoid::FixPourEllipsoid(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), idregion(nullptr), region(nullptr), random(nullptr)
{
  if (narg < 6) utils::missing_cmd_args(FLERR, "fix pour/ellipsoid", error);
  if (lmp->kokkos) error->all(FLERR, "Cannot use fix pour/ellipsoid with the KOKKOS package");

  scalar_flag = 1;
  extscalar = 0;
  vector_flag = 1;
  size_vector = 3;
  extvector = 0;
  global_freq = 1;
  time_depend = 1;
  restart_global = 1;
  force_reneighbor = 1;
  next_reneighbor = -1;

  if (!atom->ellipsoid_flag) error->all(FLERR, "Fix pour/ellipsoid requires atom_style ellipsoid");
  if (!atom->rmass_flag || !atom->angmom_flag)
    error->all(FLERR, "Fix pour/ellipsoid requires per-atom mass and angular momentum");
  if (atom->tag_enable == 0) error->all(FLERR, "Fix pour/ellipsoid requires atom IDs");
  if (domain->dimension != 3) error->all(FLERR, "Fix pour/ellipsoid requires a 3d simulation");

  auto integer = [&](int i, const char *what) {
    if (!utils::is_integer(arg[i]))
      error->all(FLERR, i, "Fix pour/ellipsoid {}: expected an integer, got '{}'", what, arg[i]);
    return utils::inumeric(FLERR, arg[i], false, lmp);
  };
  ninsert = integer(3, "N");
  ntype = integer(4, "type");
  seed = integer(5, "seed");
  if (ninsert <= 0) error->all(FLERR, 3, "Fix pour/ellipsoid N must be > 0, got {}", ninsert);
  if (ntype <= 0 || ntype > atom->ntypes)
    error->all(FLERR, 4, "Fix pour/ellipsoid atom type {} is not in 1..{}", ntype, atom->ntypes);
  if (seed <= 0) error->all(FLERR, 5, "Fix pour/ellipsoid seed must be > 0, got {}", seed);

  options(narg, arg);

  // region: block or z-cylinder inside the box
  if (!region) error->all(FLERR, "Fix pour/ellipsoid requires the keyword 'region ID'");
  if (region->bboxflag == 0)
    error->all(FLERR, "Fix pour/ellipsoid region {} does not support a bounding box", idregion);
  if (region->dynamic_check())
    error->all(FLERR, "Fix pour/ellipsoid region {} cannot be dynamic", idregion);
  if (region->interior == 0)
    error->all(FLERR, "Fix pour/ellipsoid region {} must be an interior region (side in)",
               idregion);
  const double ex[2] = {region->extent_xlo, region->extent_xhi};
  const double ey[2] = {region->extent_ylo, region->extent_yhi};
  const double ez[2] = {region->extent_zlo, region->extent_zhi};
  if (strcmp(region->style, "block") == 0) {
    region_style = 1;
  } else if (strcmp(region->style, "cylinder") == 0) {
    region_style = 2;
    // a z-axis cylinder has a disk as xy section: the corner of its bounding square is
    // outside, the middle of its bounding square's edge (at any z) is inside
    const double f = 1.0e-3;
    const double dxr = f * (ex[1] - ex[0]), dyr = f * (ey[1] - ey[0]), dzr = f * (ez[1] - ez[0]);
    const double zmid = 0.5 * (ez[0] + ez[1]), ymid = 0.5 * (ey[0] + ey[1]);
    const bool corner_in = region->match(ex[0] + 10 * dxr, ey[0] + 10 * dyr, zmid) != 0;
    const bool edge_in = region->match(ex[0] + dxr, ymid, ez[0] + dzr) != 0;
    if (corner_in || !edge_in)
      error->all(FLERR, "Fix pour/ellipsoid region {} must be a z-axis cylinder", idregion);
  } else {
    error->all(FLERR, "Fix pour/ellipsoid region {} must be a block or a cylinder (style {})",
               idregion, region->style);
  }
  xlo = ex[0];
  xhi = ex[1];
  ylo = ey[0];
  yhi = ey[1];
  zlo = ez[0];
  zhi = ez[1];
  xc = 0.5 * (xlo + xhi);
  yc = 0.5 * (ylo + yhi);
  rc = 0.5 * (xhi - xlo);
  if (xlo < domain->boxlo[0] || xhi > domain->boxhi[0] || ylo < domain->boxlo[1] ||
      yhi > domain->boxhi[1] || zlo < domain->boxlo[2] || zhi > domain->boxhi[2])
    error->all(FLERR, "Fix pour/ellipsoid region {} extends outside the simulation box", idregion);
  if (!(xhi > xlo && yhi > ylo && zhi > zlo))
    error->all(FLERR, "Fix pour/ellipsoid region {} is empty", idregion);

  setup_size_statistics();
  // particles are inserted with their whole bounding sphere inside the region's z range
  if (zhi - zlo < 2.0 * bounding_max)
    error->all(FLERR,
               "Fix pour/ellipsoid region {} is {} high: too low for particles whose "
               "largest semi-axis is {} (their bounding spheres must fit in z)",
               idregion, zhi - zlo, bounding_max);

  // insertions per batch from the region volume and the mean particle volume
  const double volume = region_style == 1 ? (xhi - xlo) * (yhi - ylo) * (zhi - zlo)
                                          : MY_PI * rc * rc * (zhi - zlo);
  const double count = volfrac * volume / mean_volume;
  nper = count > 1.0e9 ? 1000000000 : static_cast<int>(count);
  if (nper <= 0)
    error->all(FLERR,
               "Fix pour/ellipsoid region {} is too small: volume {} holds no particle "
               "of mean volume {} at volume fraction {}",
               idregion, volume, mean_volume, volfrac);

  // same random numbers on every rank; warm up as fix pour does
  random = new RanPark(lmp, seed);
  for (int i = 0; i < 30; i++) random->uniform();

  contact_settings = ContactSettings();
  ninserted = nfailed = nrejected = 0;
  maxtag_all = 0;
  initialized = 0;
  nfreq = 0;
  nfirst = next_insert = 0;
  grav = 0.0;
  lo_current = zlo;
  hi_current = zhi;
  radius_one = 0.0;

  MPI_Comm_rank(world, &me);
  MPI_Comm_size(world, &nprocs);
}

/* ---------------------------------------------------------------------- */

FixPourEllipsoid::~FixPourEllipsoid()
{
  delete random;
  delete[] idregion;
}

/* ---------------------------------------------------------------------- */

int FixPourEllipsoid::setmask()
{
  int mask = 0;
  mask |= PRE_EXCHANGE;
  return mask;
}

/* ----------------------------------------------------------------------
   keywords; arg is the whole fix command (errors point at the bad word)
------------------------------------------------------------------------- */

void FixPourEllipsoid::options(int narg, char **arg)
{
  rmin = rmax = 0.5;
  alpha = beta = 3.0;
  eta = zeta = 1.0;
  delta_eta = delta_zeta = 0.0;
  density = 1.0;
  volfrac = 0.25;
  maxattempt = 50;
  rate = 0.0;
  vxlo = vxhi = vylo = vyhi = vz = 0.0;
  every = 0;

  auto number = [&](int i, const std::string &what) {
    if (i >= narg) utils::missing_cmd_args(FLERR, "fix pour/ellipsoid " + what, error);
    if (!utils::is_double(arg[i]))
      error->all(FLERR, i, "Fix pour/ellipsoid {}: expected a number, got '{}'", what, arg[i]);
    return utils::numeric(FLERR, arg[i], false, lmp);
  };
  auto integer = [&](int i, const std::string &what) {
    if (i >= narg) utils::missing_cmd_args(FLERR, "fix pour/ellipsoid " + what, error);
    if (!utils::is_integer(arg[i]))
      error->all(FLERR, i, "Fix pour/ellipsoid {}: expected an integer, got '{}'", what, arg[i]);
    return utils::inumeric(FLERR, arg[i], false, lmp);
  };

  int iarg = 6;
  while (iarg < narg) {
    const std::string word = arg[iarg];
    if (word == "region") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix pour/ellipsoid region", error);
      region = domain->get_region_by_id(arg[iarg + 1]);
      if (!region)
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid region {} does not exist", arg[iarg + 1]);
      delete[] idregion;
      idregion = utils::strdup(arg[iarg + 1]);
      iarg += 2;
    } else if (word == "size") {
      if (iarg + 3 > narg) utils::missing_cmd_args(FLERR, "fix pour/ellipsoid size", error);
      if (strcmp(arg[iarg + 1], "mean") == 0) {
        // size mean R delta_r D
        if (iarg + 5 > narg)
          utils::missing_cmd_args(FLERR, "fix pour/ellipsoid size mean R delta_r D", error);
        const double mean = number(iarg + 2, "size mean R");
        if (strcmp(arg[iarg + 3], "delta_r") != 0)
          error->all(FLERR, iarg + 3,
                     "Fix pour/ellipsoid size mean R: expected 'delta_r', got "
                     "'{}'",
                     arg[iarg + 3]);
        const double delta = number(iarg + 4, "size delta_r");
        if (!(mean > 0.0))
          error->all(FLERR, iarg + 2, "Fix pour/ellipsoid size mean R must be > 0, got {}", mean);
        if (!(delta >= 0.0 && delta < 1.0))
          error->all(FLERR, iarg + 4, "Fix pour/ellipsoid delta_r must be in [0, 1), got {}",
                     delta);
        rmin = mean * (1.0 - delta);
        rmax = mean * (1.0 + delta);
        iarg += 5;
      } else {
        rmin = number(iarg + 1, "size rmin");
        rmax = number(iarg + 2, "size rmax");
        if (!(rmin > 0.0))
          error->all(FLERR, iarg + 1, "Fix pour/ellipsoid size rmin must be > 0, got {}", rmin);
        if (!(rmax > 0.0))
          error->all(FLERR, iarg + 2, "Fix pour/ellipsoid size rmax must be > 0, got {}", rmax);
        if (rmin > rmax)
          error->all(FLERR, iarg + 1, "Fix pour/ellipsoid size rmin {} exceeds rmax {}", rmin,
                     rmax);
        iarg += 3;
      }
    } else if (word == "alpha") {
      alpha = number(iarg + 1, "alpha");
      if (!(alpha > 0.0))
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid alpha must be > 0, got {}", alpha);
      iarg += 2;
    } else if (word == "beta") {
      beta = number(iarg + 1, "beta");
      if (!(beta > 0.0))
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid beta must be > 0, got {}", beta);
      iarg += 2;
    } else if (word == "shape") {
      eta = number(iarg + 1, "shape eta");
      zeta = number(iarg + 2, "shape zeta");
      if (!(eta >= 1.0))
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid shape eta = a/b must be >= 1, got {}", eta);
      if (!(zeta >= 1.0))
        error->all(FLERR, iarg + 2, "Fix pour/ellipsoid shape zeta = b/c must be >= 1, got {}",
                   zeta);
      iarg += 3;
    } else if (word == "dshape") {
      delta_eta = number(iarg + 1, "dshape delta_eta");
      delta_zeta = number(iarg + 2, "dshape delta_zeta");
      if (!(delta_eta >= 0.0 && delta_eta < 1.0))
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid delta_eta must be in [0, 1), got {}",
                   delta_eta);
      if (!(delta_zeta >= 0.0 && delta_zeta < 1.0))
        error->all(FLERR, iarg + 2, "Fix pour/ellipsoid delta_zeta must be in [0, 1), got {}",
                   delta_zeta);
      iarg += 3;
    } else if (word == "density") {
      density = number(iarg + 1, "density");
      if (!(density > 0.0))
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid density must be > 0, got {}", density);
      iarg += 2;
    } else if (word == "vol") {
      volfrac = number(iarg + 1, "vol fraction");
      maxattempt = integer(iarg + 2, "vol maxattempt");
      if (!(volfrac > 0.0 && volfrac <= 1.0))
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid vol fraction must be in (0, 1], got {}",
                   volfrac);
      if (maxattempt <= 0)
        error->all(FLERR, iarg + 2, "Fix pour/ellipsoid vol maxattempt must be > 0, got {}",
                   maxattempt);
      iarg += 3;
    } else if (word == "rate") {
      rate = number(iarg + 1, "rate");
      iarg += 2;
    } else if (word == "vel") {
      vxlo = number(iarg + 1, "vel vxlo");
      vxhi = number(iarg + 2, "vel vxhi");
      vylo = number(iarg + 3, "vel vylo");
      vyhi = number(iarg + 4, "vel vyhi");
      vz = number(iarg + 5, "vel vz");
      if (vxlo > vxhi)
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid vel vxlo {} exceeds vxhi {}", vxlo, vxhi);
      if (vylo > vyhi)
        error->all(FLERR, iarg + 3, "Fix pour/ellipsoid vel vylo {} exceeds vyhi {}", vylo, vyhi);
      iarg += 6;
    } else if (word == "every") {
      every = integer(iarg + 1, "every");
      if (every <= 0)
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid every must be > 0, got {}", every);
      iarg += 2;
    } else {
      error->all(FLERR, iarg, "Unknown fix pour/ellipsoid keyword '{}'", word);
    }
  }

  const double eta_lo = eta * (1.0 - delta_eta), zeta_lo = zeta * (1.0 - delta_zeta);
  if (eta_lo < 1.0 - 1e-12)
    error->all(FLERR,
               "Fix pour/ellipsoid: eta (1 - delta_eta) = {} < 1 (a must stay the "
               "longest axis)",
               eta_lo);
  if (zeta_lo < 1.0 - 1e-12)
    error->all(FLERR,
               "Fix pour/ellipsoid: zeta (1 - delta_zeta) = {} < 1 (c must stay the "
               "shortest axis)",
               zeta_lo);
}

/* ----------------------------------------------------------------------
   acceptance of the size sampler, mean volume and largest semi-axis
------------------------------------------------------------------------- */

void FixPourEllipsoid::setup_size_statistics()
{
  if (rmax - rmin <= 1.0e-12 * rmax) {
    rmax = rmin;
    acceptance = 1.0;
    mean_volume = MY_4PI3 * rmin * rmin * rmin;
  } else {
    const double span = rmax - rmin;
    const double norm = beta_weighted_integral(alpha, beta, [](double) {
      return 1.0;
    });
    // E_V[(rmin/r)^3]: the acceptance; E_n[r^3] = 1 / E_V[r^-3]
    const double inv3 = beta_weighted_integral(alpha, beta,
                                               [&](double x) {
                                                 const double r = rmin + span * x;
                                                 return 1.0 / (r * r * r);
                                               }) /
        norm;
    acceptance = rmin * rmin * rmin * inv3;
    mean_volume = MY_4PI3 / inv3;
    if (acceptance < MIN_ACCEPTANCE)
      error->all(FLERR,
                 "Fix pour/ellipsoid size range rmin {} rmax {} is too wide for the exact "
                 "size sampler (acceptance {:.3g} < {}); raise rmin",
                 rmin, rmax, acceptance, MIN_ACCEPTANCE);
  }
  const double eta_max = eta * (1.0 + delta_eta), zeta_max = zeta * (1.0 + delta_zeta);
  // a = r eta^(2/3) zeta^(1/3) grows with r, eta and zeta
  bounding_max = rmax * std::cbrt(eta_max * eta_max * zeta_max);

  // masses and principal moments must be normal, finite numbers: sizes so small (or so
  // large) that rho 4/3 pi r^3 or m c^2 under- or overflows would give zero or infinite
  // masses and NaN velocities under fix nve/asphere
  const double c_min = rmin / std::cbrt(eta_max * zeta_max * zeta_max);
  const double mass_min = density * MY_4PI3 * rmin * rmin * rmin;
  const double mass_max = density * MY_4PI3 * rmax * rmax * rmax;
  if (!std::isnormal(mass_min) || !std::isnormal(mass_min * c_min * c_min) ||
      !std::isnormal(mean_volume) || !std::isfinite(mass_max * bounding_max * bounding_max))
    error->all(FLERR,
               "Fix pour/ellipsoid size and density give masses or moments of inertia "
               "that are not representable (rmin {} rmax {} density {}); use other units",
               rmin, rmax, density);
}

/* ---------------------------------------------------------------------- */

void FixPourEllipsoid::init()
{
  if (domain->triclinic) error->all(FLERR, "Cannot use fix pour/ellipsoid with a triclinic box");
  region = domain->get_region_by_id(idregion);
  if (!region) error->all(FLERR, "Fix pour/ellipsoid region {} does not exist", idregion);

  // gravity: constant, along -z (its vector is set when the fix is created)
  auto fixlist = modify->get_fix_by_style("^gravity");
  if (fixlist.size() > 1) error->all(FLERR, "Fix pour/ellipsoid needs at most one fix gravity");
  if (fixlist.empty() && every == 0)
    error->all(FLERR,
               "Fix pour/ellipsoid needs a fix gravity to time its insertions, or the "
               "keyword 'every'");
  double gnew = 0.0;
  if (!fixlist.empty()) {
    int dim = 0;
    auto *gvec = static_cast<double *>(fixlist.front()->extract("gvec", dim));
    if (!gvec) error->all(FLERR, "Fix pour/ellipsoid cannot read the gravity vector");
    const double g = sqrt(gvec[0] * gvec[0] + gvec[1] * gvec[1] + gvec[2] * gvec[2]);
    if (g > 0.0 && (fabs(gvec[0]) > EPSILON * g || fabs(gvec[1]) > EPSILON * g || gvec[2] > 0.0))
      error->all(FLERR, "Gravity must point in -z to use with fix pour/ellipsoid");
    gnew = -g * force->ftm2v;
  }
  if (every == 0 && !(gnew < 0.0))
    error->all(FLERR,
               "Fix pour/ellipsoid needs a non-zero constant gravity, or the keyword "
               "'every'");

  if (!initialized) {
    initialized = 1;
    grav = gnew;
    if (every > 0) {
      nfreq = every;
    } else {
      // time to fall from the top of the (moving) region to its bottom, as in fix pour
      const double v_relative = vz - rate;
      const double delta = zhi - zlo;
      const double t = (-v_relative - sqrt(v_relative * v_relative - 2.0 * grav * delta)) / grav;
      nfreq = MAX(1, static_cast<int>(std::lround(t / update->dt)));
    }
    nfirst = update->ntimestep + 1;
    next_insert = nfirst;
    const bigint nfinal = nfirst + ((bigint) ninsert - 1) / nper * nfreq;
    if (me == 0)
      utils::logmesg(lmp,
                     "fix pour/ellipsoid: {} particles every {} steps, {} by step {}; r in "
                     "[{}, {}], largest semi-axis {}, mean volume {:.6g}\n",
                     nper, nfreq, ninsert, nfinal, rmin, rmax, bounding_max, mean_volume);
  } else if (fabs(gnew - grav) > 1e-12 * MAX(1.0, fabs(grav)) && every == 0) {
    error->all(FLERR, "Gravity changed since fix pour/ellipsoid was created");
  }
}

/* ---------------------------------------------------------------------- */

void FixPourEllipsoid::setup_pre_exchange()
{
  // keep the schedule (also across runs and restarts): next batch at next_insert
  if (ninserted < ninsert)
    next_reneighbor = MAX(next_insert, update->ntimestep + 1);
  else
    next_reneighbor = 0;
  next_insert = next_reneighbor;
}

/* ---------------------------------------------------------------------- */

void FixPourEllipsoid::find_maxid()
{
  tagint max = 0;
  for (int i = 0; i < atom->nlocal; i++) max = MAX(max, atom->tag[i]);
  MPI_Allreduce(&max, &maxtag_all, 1, MPI_LMP_TAGINT, MPI_MAX, world);
}

/* ----------------------------------------------------------------------
   value outside [lo, hi] in dimension dim, with periodic wrap-around of the range
------------------------------------------------------------------------- */

bool FixPourEllipsoid::outside(int dim, double value, double lo, double hi) const
{
  const bool outside_range = (value < lo || value > hi);
  if (!outside_range || !domain->periodicity[dim]) return outside_range;
  const double boxlo = domain->boxlo[dim], boxhi = domain->boxhi[dim], prd = domain->prd[dim];
  if ((lo < boxlo && hi > boxhi) || (hi - lo) > prd) return false;
  if (lo < boxlo) return (value > hi && value < lo + prd);
  if (hi > boxhi) return (value < lo && value > hi - prd);
  return true;
}

// can a particle at x with bounding radius `bound` touch an inserted one?
bool FixPourEllipsoid::near_region(const double *x, double bound) const
{
  const double delta = bound + bounding_max;
  if (region_style == 1) {
    if (outside(0, x[0], xlo - delta, xhi + delta)) return false;
    if (outside(1, x[1], ylo - delta, yhi + delta)) return false;
  } else {
    double dx = x[0] - xc, dy = x[1] - yc, dz = 0.0;
    domain->minimum_image(FLERR, dx, dy, dz);
    const double r = rc + delta;
    if (dx * dx + dy * dy > r * r) return false;
  }
  return !outside(2, x[2], lo_current - delta, hi_current + delta);
}

/* ---------------------------------------------------------------------- */

void FixPourEllipsoid::xyz_random(double h, double *coord)
{
  if (region_style == 1) {
    coord[0] = xlo + random->uniform() * (xhi - xlo);
    coord[1] = ylo + random->uniform() * (yhi - ylo);
  } else {
    double r1, r2;
    while (true) {
      r1 = random->uniform() - 0.5;
      r2 = random->uniform() - 0.5;
      if (r1 * r1 + r2 * r2 < 0.25) break;
    }
    coord[0] = xc + 2.0 * r1 * rc;
    coord[1] = yc + 2.0 * r2 * rc;
  }
  coord[2] = h;
}

/* ----------------------------------------------------------------------
   random variates from RanPark::uniform() only, so the generator's whole state is its
   seed (RanPark::state()) and a restart continues the exact sequence
------------------------------------------------------------------------- */

double FixPourEllipsoid::normal_variate()
{
  const double u1 = random->uniform(), u2 = random->uniform();
  return sqrt(-2.0 * log(u1)) * cos(MY_2PI * u2);
}

// Marsaglia & Tsang (2000); shape < 1 through Gamma(a+1) U^(1/a)
double FixPourEllipsoid::gamma_variate(double a)
{
  if (a < 1.0) {
    const double g = gamma_variate(a + 1.0);
    return g * pow(random->uniform(), 1.0 / a);
  }
  const double d = a - 1.0 / 3.0, c = 1.0 / sqrt(9.0 * d);
  while (true) {
    double x, v;
    do {
      x = normal_variate();
      v = 1.0 + c * x;
    } while (v <= 0.0);
    v = v * v * v;
    const double u = random->uniform();
    if (u < 1.0 - 0.0331 * x * x * x * x) return d * v;
    if (log(u) < 0.5 * x * x + d * (1.0 - v + log(v))) return d * v;
  }
}

double FixPourEllipsoid::beta_variate(double a, double b)
{
  const double x = gamma_variate(a), y = gamma_variate(b);
  const double s = x + y;
  return s > 0.0 ? x / s : 0.5;
}

double FixPourEllipsoid::sample_size()
{
  if (rmax == rmin) return rmin;
  const double span = rmax - rmin;
  while (true) {
    const double r = rmin + span * beta_variate(alpha, beta);
    const double w = rmin / r;
    if (random->uniform() < w * w * w) return r;
  }
}

// uniform on [mean (1 - delta), mean (1 + delta)]; no draw when mono-shaped
double FixPourEllipsoid::shape_value(double mean, double delta)
{
  if (delta <= 0.0) return mean;
  return mean * (1.0 - delta + 2.0 * delta * random->uniform());
}

void FixPourEllipsoid::sample_shape(double r, double *semi_axes)
{
  const double e = shape_value(eta, delta_eta);
  const double z = shape_value(zeta, delta_zeta);
  // r^3 = abc = (e z c)(z c) c = e z^2 c^3
  const double c = r / std::cbrt(e * z * z);
  semi_axes[2] = c;
  semi_axes[1] = z * c;
  semi_axes[0] = e * semi_axes[1];
}

// Shoemake (1992): uniform unit quaternion (w, x, y, z)
void FixPourEllipsoid::sample_quat(double *quat)
{
  const double u1 = random->uniform(), u2 = random->uniform(), u3 = random->uniform();
  const double s1 = sqrt(1.0 - u1), s2 = sqrt(u1);
  quat[0] = s2 * cos(MY_2PI * u3);
  quat[1] = s1 * sin(MY_2PI * u2);
  quat[2] = s1 * cos(MY_2PI * u2);
  quat[3] = s2 * sin(MY_2PI * u3);
  const double norm =
      sqrt(quat[0] * quat[0] + quat[1] * quat[1] + quat[2] * quat[2] + quat[3] * quat[3]);
  for (int k = 0; k < 4; k++) quat[k] /= norm;
}

/* ----------------------------------------------------------------------
   insert one batch
------------------------------------------------------------------------- */

void FixPourEllipsoid::pre_exchange()
{
  if (next_reneighbor != update->ntimestep) return;

  // inserting atoms overwrites ghosts: clear them (and the ghost bonus data) first, as
  // Comm::exchange() would
  if (atom->map_style != Atom::MAP_NONE) atom->map_clear();
  atom->nghost = 0;
  atom->avec->clear_bonus();

  find_maxid();

  int nnew = nper;
  if (ninserted + nnew > ninsert) nnew = static_cast<int>(ninsert - ninserted);

  lo_current = zlo + (update->ntimestep - nfirst) * update->dt * rate;
  hi_current = zhi + (update->ntimestep - nfirst) * update->dt * rate;

  // particles of all ranks that may touch the region: x, semi-axes, quaternion
  auto *avec = dynamic_cast<AtomVecEllipsoid *>(atom->style_match("ellipsoid"));
  const EllipsoidAtoms atoms(atom);
  std::vector<double> mine;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!atoms.has_shape(i)) continue;
    const double *s = atoms.shape(i);
    const double bound = MAX(s[0], MAX(s[1], s[2]));
    if (!near_region(atom->x[i], bound)) continue;
    const double *q = atoms.quat(i);
    const double row[NEAR_SIZE] = {atom->x[i][0], atom->x[i][1], atom->x[i][2], s[0], s[1],
                                   s[2],          q[0],          q[1],          q[2], q[3]};
    mine.insert(mine.end(), row, row + NEAR_SIZE);
  }
  int nmine = static_cast<int>(mine.size());
  std::vector<int> counts(nprocs), displs(nprocs);
  MPI_Allgather(&nmine, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  int total = 0;
  for (int p = 0; p < nprocs; p++) {
    displs[p] = total;
    total += counts[p];
  }
  std::vector<double> all(MAX(total, 1));
  MPI_Allgatherv(mine.data(), nmine, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, world);

  std::vector<Ellipsoid> near;
  near.reserve(total / NEAR_SIZE + nnew);
  for (int k = 0; k < total; k += NEAR_SIZE)
    near.push_back(make_ellipsoid(Vec3(all[k], all[k + 1], all[k + 2]), &all[k + 6],
                                  Vec3(all[k + 3], all[k + 4], all[k + 5])));

  // does the candidate overlap (or touch) any near particle? exact test of the kernel
  auto overlaps = [&](const Ellipsoid &cand) {
    for (const Ellipsoid &other : near) {
      double d[3] = {cand.center[0] - other.center[0], cand.center[1] - other.center[1],
                     cand.center[2] - other.center[2]};
      domain->minimum_image(FLERR, d);
      const double reach = cand.bounding_radius + other.bounding_radius;
      if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > reach * reach) continue;
      Ellipsoid image = other;    // the periodic image next to the candidate
      image.center = cand.center - Vec3(d[0], d[1], d[2]);
      if (wang_classify(image, cand, contact_settings) != Status::Separated) return true;
    }
    return false;
  };

  const double *sublo = domain->sublo, *subhi = domain->subhi;
  int nsuccess = 0;
  bigint batch_failed = 0;

  for (int k = 0; k < nnew; k++) {
    const double rn = random->uniform();
    const double r = sample_size();
    double axes[3], quat[4], coord[3];
    sample_shape(r, axes);
    // the whole bounding sphere stays inside the region in z, so that no particle is
    // inserted through a floor (or wall) at the region's bottom
    const double bound = MAX(axes[0], MAX(axes[1], axes[2]));
    const double h = (hi_current - bound) - rn * rn * (hi_current - lo_current - 2.0 * bound);

    bool success = false;
    Ellipsoid cand;
    for (int attempt = 0; attempt < maxattempt; attempt++) {
      xyz_random(h, coord);
      sample_quat(quat);
      cand =
          make_ellipsoid(Vec3(coord[0], coord[1], coord[2]), quat, Vec3(axes[0], axes[1], axes[2]));
      if (!overlaps(cand)) {
        success = true;
        break;
      }
      nrejected++;
    }
    if (!success) {
      batch_failed++;
      continue;
    }
    near.push_back(cand);
    nsuccess++;

    // velocity: as if fallen from the top of the region (continuous stream, fix pour)
    double vnew[3];
    vnew[0] = vxlo + random->uniform() * (vxhi - vxlo);
    vnew[1] = vylo + random->uniform() * (vyhi - vylo);
    if (grav < 0.0)
      vnew[2] = -sqrt(MAX(0.0, vz * vz + 2.0 * grav * (coord[2] - hi_current)));
    else
      vnew[2] = vz;

    const tagint tag = ++maxtag_all;

    // mine if in my sub-domain, or above the box and I am in the top layer
    bool flag = false;
    if (coord[0] >= sublo[0] && coord[0] < subhi[0] && coord[1] >= sublo[1] &&
        coord[1] < subhi[1] && coord[2] >= sublo[2] && coord[2] < subhi[2])
      flag = true;
    else if (coord[2] >= domain->boxhi[2] && coord[0] >= sublo[0] && coord[0] < subhi[0] &&
             coord[1] >= sublo[1] && coord[1] < subhi[1]) {
      if (comm->layout != Comm::LAYOUT_TILED)
        flag = comm->myloc[2] == comm->procgrid[2] - 1;
      else
        flag = comm->mysplit[2][1] == 1.0;
    }
    if (!flag) continue;

    atom->avec->create_atom(ntype, coord);
    const int n = atom->nlocal - 1;
    atom->tag[n] = tag;
    atom->mask[n] = 1 | groupbit;
    atom->v[n][0] = vnew[0];
    atom->v[n][1] = vnew[1];
    atom->v[n][2] = vnew[2];
    atom->angmom[n][0] = atom->angmom[n][1] = atom->angmom[n][2] = 0.0;
    // mass first: the superellipsoid variant stores the inertia computed from it
    atom->rmass[n] = density * MY_4PI3 * axes[0] * axes[1] * axes[2];
    avec->set_shape(n, axes[0], axes[1], axes[2]);
    double *q = const_cast<double *>(atoms.quat(n));
    for (int m = 0; m < 4; m++) q[m] = quat[m];
    modify->create_attribute(n);
  }

  ninserted += nsuccess;
  nfailed += batch_failed;
  if (batch_failed && me == 0)
    error->warning(FLERR,
                   "Fix pour/ellipsoid: {} of {} insertions failed at step {} (no free "
                   "place in {} attempts)",
                   batch_failed, nnew, update->ntimestep, maxattempt);

  if (nsuccess) {
    atom->natoms += nsuccess;
    if (atom->natoms < 0) error->all(FLERR, "Too many total atoms");
    if (maxtag_all >= MAXTAGINT) error->all(FLERR, "New atom IDs exceed maximum allowed ID");
  }
  // the global ellipsoid count (the 'ellipsoids' header of write_data), as the set command
  // keeps it; without it read_data rejects the data file of a pour
  bigint nlocal_bonus = avec->nlocal_bonus;
  MPI_Allreduce(&nlocal_bonus, &atom->nellipsoids, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (atom->map_style != Atom::MAP_NONE) {
    atom->map_init();
    atom->map_set();
  }

  if (ninserted < ninsert) {
    next_insert = update->ntimestep + nfreq;
    next_reneighbor = next_insert;
  } else {
    next_reneighbor = 0;
  }
}

/* ---------------------------------------------------------------------- */

void FixPourEllipsoid::post_run()
{
  if (me == 0)
    utils::logmesg(lmp,
                   "fix pour/ellipsoid {}: {} of {} particles inserted, {} insertions failed, "
                   "{} overlapping trial positions rejected\n",
                   id, ninserted, ninsert, nfailed, nrejected);
}

void FixPourEllipsoid::reset_dt()
{
  if (every == 0) error->all(FLERR, "Cannot change the timestep with fix pour/ellipsoid");
}

double FixPourEllipsoid::compute_scalar()
{
  return static_cast<double>(ninserted);
}

// 1 inserted, 2 failed insertions, 3 rejected overlapping trial positions
double FixPourEllipsoid::compute_vector(int n)
{
  if (n == 0) return static_cast<double>(ninserted);
  if (n == 1) return static_cast<double>(nfailed);
  return static_cast<double>(nrejected);
}

/* ----------------------------------------------------------------------
   global state: RNG seed, counters and schedule
------------------------------------------------------------------------- */

void FixPourEllipsoid::write_restart(FILE *fp)
{
  double list[12];
  int n = 0;
  list[n++] = random->state();
  list[n++] = ubuf(ninserted).d;
  list[n++] = ubuf(nfailed).d;
  list[n++] = ubuf(nrejected).d;
  list[n++] = ubuf(nfirst).d;
  list[n++] = ubuf(next_insert).d;
  list[n++] = ubuf(update->ntimestep).d;
  list[n++] = nper;
  list[n++] = nfreq;
  list[n++] = grav;
  list[n++] = initialized;
  list[n++] = ninsert;
  if (comm->me == 0) {
    const int size = n * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), n, fp);
  }
}

void FixPourEllipsoid::restart(char *buf)
{
  auto *list = (double *) buf;
  int n = 0;
  seed = static_cast<int>(list[n++]);
  ninserted = ubuf(list[n++]).i;
  nfailed = ubuf(list[n++]).i;
  nrejected = ubuf(list[n++]).i;
  nfirst = ubuf(list[n++]).i;
  next_insert = ubuf(list[n++]).i;
  const bigint step = ubuf(list[n++]).i;
  nper = static_cast<int>(list[n++]);
  nfreq = static_cast<int>(list[n++]);
  grav = list[n++];
  initialized = static_cast<int>(list[n++]);
  const int ninsert_old = static_cast<int>(list[n++]);
  if (step != update->ntimestep)
    error->all(FLERR, "Must not reset the timestep when restarting fix pour/ellipsoid");
  if (ninsert_old != ninsert && comm->me == 0)
    error->warning(FLERR, "Fix pour/ellipsoid N changed from {} to {} across the restart",
                   ninsert_old, ninsert);
  random->reset(seed);
}

/* ----------------------------------------------------------------------
   largest bounding radius (semi-axis) inserted for atom type itype
------------------------------------------------------------------------- */

void *FixPourEllipsoid::extract(const char *str, int &itype)
{
  if (strcmp(str, "radius") == 0) {
    radius_one = (itype == ntype) ? bounding_max : 0.0;
    return &radius_one;
  }
  return nullptr;
}
