/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix pour/ellipsoid (see doc/fix_pour_ellipsoid.rst): life cycle,
   schedule, restart and output.

   The insertion schedule follows LAMMPS's fix pour: a batch that fills the region at the
   requested volume fraction every time a particle needs to fall through the region. The
   particles are general ellipsoids drawn by the engine-free PourSampler from this fix's
   RanPark, so the generator and its restart state stay LAMMPS's.
   Every rank draws the same random numbers and makes the same decisions (the overlap
   check sees the same gathered particles on every rank), and keeps the particles in its
   sub-domain, so a pour is independent of the number of ranks.
------------------------------------------------------------------------- */

#include "fix_pour_ellipsoid.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_wall_gran_ellipsoid.h"
#include "force.h"
#include "math_const.h"
#include "modify.h"
#include "pair_granular_ellipsoid.h"
#include "random_park.h"
#include "region.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
using namespace EllipsoidDep;
using MathConst::MY_4PI3;
using MathConst::MY_PI;

static constexpr double EPSILON = 0.001;
static constexpr double MIN_ACCEPTANCE = 1.0e-4;    // size sampler: refuse hopeless ranges

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
  size_vector = 5;
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

  options(narg, arg);
  check_region();

  // same random numbers on every rank; warm up as fix pour does
  random = new RanPark(lmp, seed);
  for (int i = 0; i < 30; i++) random->uniform();
  sampler = std::make_unique<PourSampler>(distribution, [this] {
    return random->uniform();
  });
  distribution = sampler->distribution();    // a near-empty size range made one size
  if (sampler->acceptance() < MIN_ACCEPTANCE)
    error->all(FLERR,
               "Fix pour/ellipsoid size range rmin {} rmax {} is too wide for the exact "
               "size sampler (acceptance {:.3g} < {}); raise rmin",
               distribution.rmin, distribution.rmax, sampler->acceptance(), MIN_ACCEPTANCE);
  bounding_max = sampler->largest_semi_axis();
  check_representable();

  // particles are inserted with their whole bounding sphere inside the region's z range
  if (zhi - zlo < 2.0 * bounding_max)
    error->all(FLERR,
               "Fix pour/ellipsoid region {} is {} high: too low for particles whose "
               "largest semi-axis is {} (their bounding spheres must fit in z)",
               idregion, zhi - zlo, bounding_max);

  // insertions per batch from the region volume and the mean particle volume
  const double count = volfrac * region_volume() / sampler->mean_volume();
  nper = count > 1.0e9 ? 1000000000 : static_cast<int>(count);
  if (nper <= 0)
    error->all(FLERR,
               "Fix pour/ellipsoid region {} is too small: volume {} holds no particle "
               "of mean volume {} at volume fraction {}",
               idregion, region_volume(), sampler->mean_volume(), volfrac);

  contact_settings = ContactSettings();
  ninserted = nfailed = nrejected = nside = nwall = 0;
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

/* ---------------------------------------------------------------------- */

double FixPourEllipsoid::region_volume() const
{
  const double height = zhi - zlo;
  return region_style == 1 ? (xhi - xlo) * (yhi - ylo) * height : MY_PI * rc * rc * height;
}

/* ---------------------------------------------------------------------- */

void FixPourEllipsoid::init()
{
  if (domain->triclinic) error->all(FLERR, "Cannot use fix pour/ellipsoid with a triclinic box");
  recheck_region();
  find_walls();

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
    report_schedule();
  } else if (fabs(gnew - grav) > 1e-12 * MAX(1.0, fabs(grav)) && every == 0) {
    error->all(FLERR, "Gravity changed since fix pour/ellipsoid was created");
  }
  // the pair's run-start check sees only the atoms present: an empty box has none
  check_contact_times(true);
}

/* ----------------------------------------------------------------------
   the time-step check of the particles to come
------------------------------------------------------------------------- */

double FixPourEllipsoid::lightest_mass() const
{
  return density * MY_4PI3 * distribution.rmin * distribution.rmin * distribution.rmin;
}

// released at the top of the region (as it stands at the last batch) with the largest
// velocities the vel keyword allows, falling to the bottom of the box: the fastest a poured
// particle can hit the floor or a resting particle
double FixPourEllipsoid::impact_speed() const
{
  const double vx = MAX(fabs(vxlo), fabs(vxhi)), vy = MAX(fabs(vylo), fabs(vyhi));
  const double drop = hi_current - domain->boxlo[2];
  return sqrt(vx * vx + vy * vy + MAX(0.0, vz * vz - 2.0 * grav * drop));
}

void FixPourEllipsoid::check_contact_times(bool run_start)
{
  const double speed = impact_speed();
  if (!(speed > 0.0)) return;
  const double mass = lightest_mass(), radius = sampler->flattest_radius();
  const double compliance = sampler->largest_rotational_compliance();
  ContactTimes times;
  // two of the lightest particles with the flattest surfaces, as the pair's check pairs types
  auto *pair = dynamic_cast<PairGranularEllipsoid *>(force->pair_match("granular/ellipsoid", 1));
  EllipsoidDep::ForceLaw law;
  std::string refusal;
  if (pair && pair->law_of_pair(ntype, ntype, law, refusal))
    times.add_contact(lmp, law, effective_radius(radius, radius), mass * mass / (mass + mass),
                      tangential_mass(mass, compliance, mass, compliance), speed,
                      fmt::format("types {} {}", ntype, ntype));
  for (const FixWallGranEllipsoid *wall : walls)
    times.add_contact(lmp, wall->force_law(), radius, mass, tangential_mass(mass, compliance),
                      speed, fmt::format("type {} on fix {}", ntype, wall->id));
  const bool shorter = times.contact_time < 0.9 * checked.contact_time ||
      times.damping_time < 0.9 * checked.damping_time;
  if (!run_start && !shorter && update->dt == checked.timestep) return;
  checked = times;
  checked.timestep = update->dt;
  report_contact_times(lmp, "Fix pour/ellipsoid", times, speed, times_reported);
}

/* ----------------------------------------------------------------------
   the schedule, and how full a batch is: the mean volume fraction of the region, the
   fraction at its top (a stream's density is ~ 1/speed, highest where it enters; a cloud
   is uniform), and
   the region height that would take all N particles in one batch
------------------------------------------------------------------------- */

void FixPourEllipsoid::report_schedule() const
{
  if (me != 0) return;
  const bigint nfinal = nfirst + ((bigint) ninsert - 1) / nper * nfreq;
  const int nbatch = MIN(nper, ninsert);
  const double height = zhi - zlo, volume = region_volume();
  const double fill = nbatch * sampler->mean_volume() / volume;
  const double v_top = fabs(vz), v_bottom = sqrt(vz * vz - 2.0 * grav * height);
  std::string top = "unbounded: vz = 0";
  if (cloud)
    top = fmt::format("{:.3g}", fill);
  else if (v_top > 0.0)
    top = fmt::format("{:.3g}", fill * 0.5 * (1.0 + v_bottom / v_top));
  utils::logmesg(lmp,
                 "fix pour/ellipsoid: {} particles every {} steps, {} by step {}; r in [{}, {}], "
                 "largest semi-axis {}, mean volume {:.6g}\n"
                 "  a batch of {} fills the region to volume fraction {:.3g} ({} at its top)\n",
                 nper, nfreq, ninsert, nfinal, distribution.rmin, distribution.rmax, bounding_max,
                 sampler->mean_volume(), nbatch, fill, top);
  if (ninsert > nper)
    utils::logmesg(lmp,
                   "  one batch of all {} at volume fraction {} needs the region {:.6g} high "
                   "(it is {:.6g})\n",
                   ninsert, volfrac, ninsert * sampler->mean_volume() / (volfrac * volume) * height,
                   height);
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

void FixPourEllipsoid::post_run()
{
  if (me == 0)
    utils::logmesg(lmp,
                   "fix pour/ellipsoid {}: {} of {} particles inserted, {} insertions failed; "
                   "trial positions rejected: {} overlapping particles, {} crossing the "
                   "region's side, {} touching a wall\n",
                   id, ninserted, ninsert, nfailed, nrejected, nside, nwall);
}

void FixPourEllipsoid::reset_dt()
{
  if (every == 0) error->all(FLERR, "Cannot change the timestep with fix pour/ellipsoid");
}

double FixPourEllipsoid::compute_scalar()
{
  return static_cast<double>(ninserted);
}

// 1 inserted, 2 failed insertions, trial positions rejected: 3 overlapping particles, 4
// crossing the region's side, 5 touching a wall
double FixPourEllipsoid::compute_vector(int n)
{
  const bigint counts[5] = {ninserted, nfailed, nrejected, nside, nwall};
  return static_cast<double>(counts[n]);
}

/* ----------------------------------------------------------------------
   largest bounding radius (semi-axis) this fix may insert for atom type itype; as
   LAMMPS's fix pour, the answer is a scalar (itype is set to 0)
------------------------------------------------------------------------- */

void *FixPourEllipsoid::extract(const char *str, int &itype)
{
  if (strcmp(str, "radius") == 0) {
    radius_one = (itype == ntype) ? bounding_max : 0.0;
    itype = 0;
    return &radius_one;
  }
  return nullptr;
}
