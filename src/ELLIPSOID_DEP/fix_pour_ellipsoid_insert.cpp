/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix pour/ellipsoid, inserting one batch (see fix_pour_ellipsoid.h)

   Per particle, in this order of random numbers (which restarts rely on): the height
   deviate, the size, the shape, then per trial position its x, y and orientation, then
   the lateral velocity. A trial is rejected when the particle crosses a side of the region
   (its exact extent: whole particles are inserted), touches or lies beyond a wall acting on
   it, or overlaps (or touches) any particle near the region or of the same batch, each by the
   kernel's exact test. After maxattempt trials at one
   height the particle draws another height of the stream (one more deviate), up to
   MAX_HEIGHTS heights; then it is a failed insertion. A pour in which every particle fits
   at its first height draws exactly the numbers of a pour that tries one height only.
------------------------------------------------------------------------- */

#include "fix_pour_ellipsoid.h"

#include "atom.h"
#include "atom_vec_ellipsoid.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_wall_gran_ellipsoid.h"
#include "math_const.h"
#include "modify.h"
#include "random_park.h"
#include "update.h"

#include "granular_ellipsoid_atoms.h"

#include <algorithm>
#include <cmath>
#include <string>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;
using MathConst::MY_4PI3;

static constexpr int NEAR_SIZE = 10;      // x, semi-axes, quaternion
static constexpr int MAX_HEIGHTS = 10;    // heights tried per particle before it fails
// Domain::minimum_image takes the file name as a std::string: FLERR would build and free
// one per tested pair
static const std::string THIS_FILE = __FILE__;

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
   depth below the top of the batch (0 <= depth <= height) of a particle with uniform
   deviate rn. release cloud: uniform. release stream: a snapshot of a steady stream that
   enters the region's top at speed |vz| and falls under gravity, so the time since entry,
   not the depth, is uniform and the number density is ~ 1/speed. With vz = 0 this is
   LAMMPS fix pour's rn^2 law, whose density diverges at the top.
------------------------------------------------------------------------- */

double FixPourEllipsoid::batch_depth(double rn, double height) const
{
  if (cloud) return rn * height;
  const double v0 = fabs(vz), g = -grav;
  if (v0 == 0.0) return rn * rn * height;
  const double t = rn * 2.0 * height / (sqrt(v0 * v0 + 2.0 * g * height) + v0);
  return MIN(height, v0 * t + 0.5 * g * t * t);
}

/* ----------------------------------------------------------------------
   particles of all ranks whose bounding spheres can reach the region
------------------------------------------------------------------------- */

std::vector<Ellipsoid> FixPourEllipsoid::gather_near_region(int reserve)
{
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
  near.reserve(total / NEAR_SIZE + reserve);
  for (int k = 0; k < total; k += NEAR_SIZE)
    near.push_back(make_particle(Vec3(all[k], all[k + 1], all[k + 2]), &all[k + 6],
                                 Vec3(all[k + 3], all[k + 4], all[k + 5])));
  return near;
}

/* ----------------------------------------------------------------------
   cells of the near particles, as wide as two of the largest bounding radii: a particle
   they skip cannot pass the bounding-sphere test of overlaps(). Over the region (positions
   outside fall in its edge cells), over the box in periodic dimensions, where they wrap as
   in domain->minimum_image.
------------------------------------------------------------------------- */

CellGrid FixPourEllipsoid::near_cells(const std::vector<Ellipsoid> &near, int nnew) const
{
  // a drawn semi-axis may exceed largest_semi_axis() by a few ulp
  double radius = bounding_max * (1.0 + 1e-9);
  for (const Ellipsoid &e : near) radius = MAX(radius, e.bounding_radius);
  Vec3 lo(xlo, ylo, lo_current), hi(xhi, yhi, hi_current);    // the region's bounding box
  std::array<bool, 3> periodic;
  for (int d = 0; d < 3; d++) {
    periodic[d] = domain->periodicity[d];
    if (periodic[d]) {
      lo[d] = domain->boxlo[d];
      hi[d] = domain->boxhi[d];
    }
  }
  CellGrid cells(lo, hi, periodic, 2.0 * radius, near.size() + nnew);
  for (const Ellipsoid &e : near) cells.insert(e.center);
  return cells;
}

// does the candidate overlap (or touch) a near particle? exact test of the kernel on those of
// its cells, against every periodic image of it within the bounding spheres' reach (in a box
// narrower than twice the reach, more than the nearest one); the answer does not depend on
// the order (wang_classify has no side effect)
bool FixPourEllipsoid::overlaps(const Ellipsoid &cand, const std::vector<Ellipsoid> &near,
                                const CellGrid &cells) const
{
  return cells.any_near(cand.center, [&](int i) {
    const Ellipsoid &other = near[i];
    double d[3] = {cand.center[0] - other.center[0], cand.center[1] - other.center[1],
                   cand.center[2] - other.center[2]};
    domain->minimum_image(THIS_FILE, __LINE__, d);
    const double reach = cand.bounding_radius + other.bounding_radius;
    // the image shifts (in periods) that keep each component within reach
    int first[3], last[3];
    for (int dim = 0; dim < 3; dim++) {
      first[dim] = last[dim] = 0;
      if (!domain->periodicity[dim]) continue;
      const double period = domain->prd[dim];
      first[dim] = static_cast<int>(std::ceil((-reach - d[dim]) / period));
      last[dim] = static_cast<int>(std::floor((reach - d[dim]) / period));
    }
    Ellipsoid image = other;
    for (int sx = first[0]; sx <= last[0]; sx++)
      for (int sy = first[1]; sy <= last[1]; sy++)
        for (int sz = first[2]; sz <= last[2]; sz++) {
          const Vec3 shifted(d[0] + sx * domain->prd[0], d[1] + sy * domain->prd[1],
                             d[2] + sz * domain->prd[2]);
          if (shifted.squaredNorm() > reach * reach) continue;
          image.center = cand.center - shifted;    // this image of the near particle
          if (wang_classify(image, cand, contact_settings) != Status::Separated) return true;
        }
    return false;
  });
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
  check_contact_times(false);    // a rising region drops its particles from higher up

  std::vector<Ellipsoid> near = gather_near_region(nnew);
  CellGrid cells = near_cells(near, nnew);
  int nsuccess = 0;
  bigint batch_failed = 0, batch_overlaps = 0, batch_side = 0, batch_wall = 0;
  std::vector<std::string> walls_touched;    // the walls that rejected trials of this batch

  for (int k = 0; k < nnew; k++) {
    const double rn = random->uniform();
    const Vec3 axes = sampler->semi_axes(sampler->size());
    // the whole bounding sphere stays inside the region in z, so that no particle is
    // inserted through a floor (or wall) at the region's bottom
    const double bound = axes.maxCoeff();
    const double span = hi_current - lo_current - 2.0 * bound;
    double h = (hi_current - bound) - batch_depth(rn, span);

    // maxattempt trial positions at one height; where that height of the batch is full,
    // the particle takes another height (a fresh deviate)
    bool success = false;
    double quat[4], coord[3];
    Ellipsoid cand;
    for (int height = 0; height < MAX_HEIGHTS && !success; height++) {
      if (height > 0) h = (hi_current - bound) - batch_depth(random->uniform(), span);
      for (int attempt = 0; attempt < maxattempt; attempt++) {
        xyz_random(h, coord);
        sampler->orientation(quat);
        cand = make_particle(Vec3(coord[0], coord[1], coord[2]), quat, axes);
        if (!inside_region(cand)) {
          batch_side++;
          continue;
        }
        if (const FixWallGranEllipsoid *wall = touched_wall(cand)) {
          batch_wall++;
          if (std::find(walls_touched.begin(), walls_touched.end(), wall->id) ==
              walls_touched.end())
            walls_touched.emplace_back(wall->id);
          continue;
        }
        if (!overlaps(cand, near, cells)) {
          success = true;
          break;
        }
        batch_overlaps++;
      }
    }
    if (!success) {
      batch_failed++;
      continue;
    }
    near.push_back(cand);
    cells.insert(cand.center);
    nsuccess++;

    // velocity: a stream's as if fallen from the top of the region (fix pour); a cloud is
    // released as one body
    double vnew[3];
    vnew[0] = vxlo + random->uniform() * (vxhi - vxlo);
    vnew[1] = vylo + random->uniform() * (vyhi - vylo);
    if (grav < 0.0 && !cloud)
      vnew[2] = -sqrt(MAX(0.0, vz * vz + 2.0 * grav * (coord[2] - hi_current)));
    else
      vnew[2] = vz;

    const tagint tag = ++maxtag_all;
    if (owns(coord)) create_particle(coord, vnew, tag, axes, quat);
  }

  ninserted += nsuccess;
  nfailed += batch_failed;
  nrejected += batch_overlaps;
  nside += batch_side;
  nwall += batch_wall;
  // what could not be inserted, and why: the particles wait for the next batch
  if (batch_failed && me == 0)
    error->warning(FLERR,
                   "Fix pour/ellipsoid: {} of {} insertions failed at step {} (no free "
                   "place in {} attempts at each of up to {} heights; the batch's rejected trial "
                   "positions: {} overlapping particles, {} crossing region {}'s side, {} "
                   "touching a wall{}); they are tried again at the next batch",
                   batch_failed, nnew, update->ntimestep, maxattempt, MAX_HEIGHTS, batch_overlaps,
                   batch_side, idregion, batch_wall,
                   walls_touched.empty() ? ""
                                         : " of fix " + utils::join_words(walls_touched, ", "));

  if (nsuccess) {
    atom->natoms += nsuccess;
    if (atom->natoms < 0) error->all(FLERR, "Too many total atoms");
    if (maxtag_all >= MAXTAGINT) error->all(FLERR, "New atom IDs exceed maximum allowed ID");
  }
  // the global ellipsoid count (the 'ellipsoids' header of write_data), as the set command
  // keeps it; without it read_data rejects the data file of a pour
  bigint nlocal_bonus = EllipsoidAtoms(atom).avec->nlocal_bonus;
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

/* ----------------------------------------------------------------------
   mine if in my sub-domain, or above the box and I am in the top layer
------------------------------------------------------------------------- */

bool FixPourEllipsoid::owns(const double *coord) const
{
  const double *sublo = domain->sublo, *subhi = domain->subhi;
  const bool lateral =
      coord[0] >= sublo[0] && coord[0] < subhi[0] && coord[1] >= sublo[1] && coord[1] < subhi[1];
  if (!lateral) return false;
  if (coord[2] >= sublo[2] && coord[2] < subhi[2]) return true;
  if (coord[2] < domain->boxhi[2]) return false;
  if (comm->layout != Comm::LAYOUT_TILED) return comm->myloc[2] == comm->procgrid[2] - 1;
  return comm->mysplit[2][1] == 1.0;
}

void FixPourEllipsoid::create_particle(double *coord, const double *vnew, tagint tag,
                                       const Vec3 &axes, const double *quat)
{
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
  EllipsoidAtomsWriter(atom).set_ellipsoid(n, axes.data(), quat);
  modify->create_attribute(n);
}
