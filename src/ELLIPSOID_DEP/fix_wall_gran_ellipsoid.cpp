/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/ellipsoid (see doc/fix_wall_gran_ellipsoid.rst)

   Each wall is a plane; the particle is body i and the wall body j at rest (v_j = omega_j
   = 0, effective mass m_i). The geometry comes from EllipsoidDep::ellipsoid_plane_contact
   and the force from ForceLaw::compute, the one definition the pair style uses too.
------------------------------------------------------------------------- */

#include "fix_wall_gran_ellipsoid.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "memory.h"
#include "update.h"

#include "granular_contact_time.h"
#include "granular_ellipsoid_atoms.h"
#include "granular_materials.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>

using namespace LAMMPS_NS;
using namespace FixConst;
using namespace EllipsoidDep;

/* ----------------------------------------------------------------------
   fix ID group wall/gran/ellipsoid <force-law words> zplane lo hi [xplane lo hi] ...
       [wall_material E nu | NAME | rigid] [impact_velocity v]
------------------------------------------------------------------------- */

FixWallGranEllipsoid::FixWallGranEllipsoid(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), size_history(0), history_one(nullptr), history_update(true),
    impact_velocity(0.0), force_flag(0)
{
  if (narg < 4) utils::missing_cmd_args(FLERR, "fix wall/gran/ellipsoid", error);
  EllipsoidAtoms::require_granular_style(lmp, "Fix wall/gran/ellipsoid");

  // the force law: exactly the words pair_coeff takes; by default the wall is of the
  // particles' material (as LAMMPS's fix wall/gran), wall_material gives it its own
  std::vector<std::string> words(arg + 3, arg + narg);
  std::optional<MaterialTable> materials;
  if (names_a_material(words)) materials.emplace(lmp);
  const MaterialLookup lookup = materials ? materials->lookup() : MaterialLookup();
  std::string message;
  const int used = parse_force_law(words, law, message, lookup);
  if (used < 0) error->all(FLERR, "Fix wall/gran/ellipsoid: {}", message);
  const ForceLaw particle_law = law;
  bool wall_material_given = false;

  // walls
  int iarg = 3 + used;
  if (iarg >= narg)
    error->all(FLERR,
               "Fix wall/gran/ellipsoid needs at least one wall (xplane, yplane or "
               "zplane lo hi) after the force law");
  bool seen[3] = {false, false, false};
  while (iarg < narg) {
    const std::string word = arg[iarg];
    if (word == "wall_material") {
      if (wall_material_given)
        error->all(FLERR, iarg, "Fix wall/gran/ellipsoid: {} given twice", word);
      wall_material_given = true;
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix wall/gran/ellipsoid " + word, error);
      if (!std::holds_alternative<HertzMaterialNormal>(particle_law.normal))
        error->all(FLERR, iarg, "Fix wall/gran/ellipsoid: wall_material needs hertz/material");
      ForceLaw wall_side = particle_law;
      auto &wall_normal = std::get<HertzMaterialNormal>(wall_side.normal);
      const std::string value = arg[iarg + 1];
      if (value == "rigid") {
        // an undeformable wall: no compliance, 1/E* = (1 - nu^2)/E of the particle
        wall_normal.youngs = HUGE_VAL;
        iarg += 2;
      } else if (utils::is_double(value)) {
        if (iarg + 3 > narg)
          utils::missing_cmd_args(FLERR, "fix wall/gran/ellipsoid wall_material E nu", error);
        wall_normal.youngs = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
        wall_normal.poisson = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        message = wall_side.validate();
        if (!message.empty())
          error->all(FLERR, iarg, "Fix wall/gran/ellipsoid wall_material: {}", message);
        iarg += 3;
      } else {
        Material material{};
        message = lookup(value, material);
        if (!message.empty())
          error->all(FLERR, iarg + 1, "Fix wall/gran/ellipsoid wall_material: {}", message);
        wall_normal.youngs = material.youngs;
        wall_normal.poisson = material.poisson;
        iarg += 2;
      }
      // the pair's mixing rule: the restitution stays the particle law's
      mix_laws(particle_law, wall_side, law);
      continue;
    }
    if (word == "impact_velocity") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix wall/gran/ellipsoid " + word, error);
      impact_velocity = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(impact_velocity > 0.0))
        error->all(FLERR, iarg + 1, "Fix wall/gran/ellipsoid impact_velocity must be > 0");
      iarg += 2;
      continue;
    }
    int dim = -1;
    if (word == "xplane")
      dim = 0;
    else if (word == "yplane")
      dim = 1;
    else if (word == "zplane")
      dim = 2;
    if (dim < 0)
      error->all(FLERR, iarg,
                 "Unknown fix wall/gran/ellipsoid keyword '{}' (expected xplane, "
                 "yplane, zplane, wall_material, impact_velocity, or a force-law word)",
                 word);
    if (seen[dim]) error->all(FLERR, iarg, "Fix wall/gran/ellipsoid: {} given twice", word);
    seen[dim] = true;
    if (iarg + 3 > narg) utils::missing_cmd_args(FLERR, "fix wall/gran/ellipsoid " + word, error);
    if (domain->periodicity[dim])
      error->all(FLERR, iarg, "Cannot use fix wall/gran/ellipsoid {} in a periodic dimension",
                 word);
    for (int k = 0; k < 2; k++) {
      const char *value = arg[iarg + 1 + k];
      if (strcmp(value, "NULL") == 0) continue;
      if (!utils::is_double(value))
        error->all(FLERR, iarg + 1 + k,
                   "Fix wall/gran/ellipsoid {} {}: expected a number or "
                   "NULL, got '{}'",
                   word, k == 0 ? "lo" : "hi", value);
      Wall w;
      w.dim = dim;
      w.side = k == 0 ? -1 : 1;
      w.coord = utils::numeric(FLERR, value, false, lmp);
      w.normal = Vec3::Zero();
      w.normal[dim] = k == 0 ? 1.0 : -1.0;
      w.offset = k == 0 ? w.coord : -w.coord;
      walls.push_back(w);
    }
    const char *lo = arg[iarg + 1], *hi = arg[iarg + 2];
    if (strcmp(lo, "NULL") != 0 && strcmp(hi, "NULL") != 0 &&
        !(utils::numeric(FLERR, lo, false, lmp) < utils::numeric(FLERR, hi, false, lmp)))
      error->all(FLERR, iarg + 1, "Fix wall/gran/ellipsoid {}: lo {} must be below hi {}", word, lo,
                 hi);
    iarg += 3;
  }
  if (walls.empty())
    error->all(FLERR, "Fix wall/gran/ellipsoid: every wall is NULL; nothing to do");

  const int nwalls = static_cast<int>(walls.size());
  vector_flag = 1;
  size_vector = 3 * nwalls;
  global_freq = 1;
  extvector = 1;
  create_attribute = 1;
  dynamic_group_allow = 1;

  wall_force.assign(3 * nwalls, 0.0);
  wall_force_all.assign(3 * nwalls, 0.0);

  size_history = law.history_size() * nwalls;
  restart_peratom = size_history > 0 ? 1 : 0;
  maxexchange = size_history;
  if (size_history) {
    grow_arrays(atom->nmax);
    atom->add_callback(Atom::GROW);
    atom->add_callback(Atom::RESTART);
    for (int i = 0; i < atom->nlocal; i++)
      for (int m = 0; m < size_history; m++) history_one[i][m] = 0.0;
  }
}

/* ---------------------------------------------------------------------- */

FixWallGranEllipsoid::~FixWallGranEllipsoid()
{
  if (size_history) {
    atom->delete_callback(id, Atom::GROW);
    atom->delete_callback(id, Atom::RESTART);
  }
  memory->destroy(history_one);
}

/* ---------------------------------------------------------------------- */

int FixWallGranEllipsoid::setmask()
{
  int mask = 0;
  mask |= POST_FORCE;
  return mask;
}

/* ---------------------------------------------------------------------- */

void FixWallGranEllipsoid::init()
{
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix wall/gran/ellipsoid does not support run_style respa");
  update_contact_times();
}

/* ----------------------------------------------------------------------
   shortest Hertz contact and damping times against the walls: per type the lightest atom
   and the flattest surface, at the impact speed (keyword, or the fastest atom of the group)
------------------------------------------------------------------------- */

void FixWallGranEllipsoid::update_contact_times()
{
  const ContactScales scales = contact_scales(lmp, groupbit);
  const double speed = impact_velocity > 0.0 ? impact_velocity : scales.fastest_speed;
  ContactTimes times;
  for (int t = 1; t <= atom->ntypes; t++) {
    const double mass = scales.lightest_mass[t], radius = scales.flattest_radius[t];
    if (!(mass > 0.0 && speed > 0.0)) continue;
    times.add_contact(lmp, law, radius, mass, speed, fmt::format("type {}", t));
  }
  report_contact_times(lmp, "Fix wall/gran/ellipsoid", times, speed, times_reported);
}

/* ----------------------------------------------------------------------
   A wall cutting through a particle's centre is an error (the contact would be
   meaningless); an overlap deeper than half the smallest semi-axis is a warning.
------------------------------------------------------------------------- */

void FixWallGranEllipsoid::setup(int vflag)
{
  const EllipsoidAtoms atoms(atom);
  const int nlocal = atom->nlocal;
  double counts[2] = {0.0, 0.0};
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    if (!atoms.has_shape(i)) atoms.missing_shape(lmp, "Fix wall/gran/ellipsoid", i, groupbit);
    const Ellipsoid e = atoms.ellipsoid(i);
    const double thin = e.semi_axes.minCoeff();
    for (const Wall &w : walls) {
      if (w.normal.dot(e.center) - w.offset <= 0.0) {
        counts[0] += 1.0;
      } else {
        const ContactGeometry g = ellipsoid_plane_contact(e, w.normal, w.offset);
        if (g.overlap > 0.5 * thin) counts[1] += 1.0;
      }
    }
  }
  double all[2];
  MPI_Allreduce(counts, all, 2, MPI_DOUBLE, MPI_SUM, world);
  if (all[0] > 0.0)
    error->all(FLERR,
               "Fix wall/gran/ellipsoid: {:.0f} particle centre(s) lie on the solid side "
               "of a wall",
               all[0]);
  if (all[1] > 0.0 && comm->me == 0)
    error->warning(FLERR,
                   "Fix wall/gran/ellipsoid: {:.0f} particle(s) overlap a wall by more "
                   "than half their smallest semi-axis at setup",
                   all[1]);

  // setup forces must not advance the law's history
  history_update = false;
  post_force(vflag);
  history_update = true;
}

/* ---------------------------------------------------------------------- */

void FixWallGranEllipsoid::post_force(int /*vflag*/)
{
  wall_forces();
}

void FixWallGranEllipsoid::wall_forces()
{
  force_flag = 0;
  std::fill(wall_force.begin(), wall_force.end(), 0.0);

  const EllipsoidAtoms atoms(atom);
  double **x = atom->x;
  double **f = atom->f;
  double **torque = atom->torque;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double dt = update->dt;
  const int nwalls = static_cast<int>(walls.size());

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    // an atom inserted during the run without a shape (fix deposit): the walls would let it go
    if (!atoms.has_shape(i)) atoms.missing_shape(lmp, "Fix wall/gran/ellipsoid", i, groupbit);
    const double bound = atoms.bounding_radius(i);
    bool built = false, moving = false;
    EllipsoidState state;

    for (int k = 0; k < nwalls; k++) {
      const Wall &w = walls[k];
      double *history = wall_history(i, k);
      // bounding sphere clear of the plane: no contact
      const double height = w.normal[w.dim] * x[i][w.dim] - w.offset;
      ContactGeometry g;
      if (height < bound) {
        if (!built) {
          state.shape = atoms.ellipsoid(i);
          built = true;
        }
        g = ellipsoid_plane_contact(state.shape, w.normal, w.offset);
      }
      if (g.status != Status::Overlapping) {
        if (history && history_update) std::fill_n(history, law.history_size(), 0.0);
        continue;
      }
      if (!moving) {
        atoms.add_motion(i, state);
        moving = true;
      }
      const LawHistory law_history(history, law.history_size(), history_update);
      const ContactForce result = law.compute(g, wall_motion(state, g.point), dt, law_history.get());
      for (int d = 0; d < 3; d++) {
        f[i][d] += result.force_i[d];
        torque[i][d] += result.torque_i[d];
        wall_force[3 * k + d] -= result.force_i[d];
      }
    }
  }
}

/* ----------------------------------------------------------------------
   total force on wall n/3 (in the order the walls were given, lo before hi),
   component n%3
------------------------------------------------------------------------- */

double FixWallGranEllipsoid::compute_vector(int n)
{
  if (force_flag == 0) {
    MPI_Allreduce(wall_force.data(), wall_force_all.data(), static_cast<int>(wall_force.size()),
                  MPI_DOUBLE, MPI_SUM, world);
    force_flag = 1;
  }
  return wall_force_all[n];
}

/* ---------------------------------------------------------------------- */

double FixWallGranEllipsoid::memory_usage()
{
  return static_cast<double>(atom->nmax) * size_history * sizeof(double);
}

/* ---------------------------------------------------------------------- */

void FixWallGranEllipsoid::grow_arrays(int nmax)
{
  if (size_history) memory->grow(history_one, nmax, size_history, "wall/gran/ellipsoid:history");
}

void FixWallGranEllipsoid::copy_arrays(int i, int j, int /*delflag*/)
{
  for (int m = 0; m < size_history; m++) history_one[j][m] = history_one[i][m];
}

void FixWallGranEllipsoid::set_arrays(int i)
{
  for (int m = 0; m < size_history; m++) history_one[i][m] = 0.0;
}

int FixWallGranEllipsoid::pack_exchange(int i, double *buf)
{
  for (int m = 0; m < size_history; m++) buf[m] = history_one[i][m];
  return size_history;
}

int FixWallGranEllipsoid::unpack_exchange(int nlocal, double *buf)
{
  for (int m = 0; m < size_history; m++) history_one[nlocal][m] = buf[m];
  return size_history;
}

int FixWallGranEllipsoid::pack_restart(int i, double *buf)
{
  if (!size_history) return 0;
  // buf[0] = count including itself, the convention other fixes unpack by
  buf[0] = size_history + 1;
  for (int m = 0; m < size_history; m++) buf[m + 1] = history_one[i][m];
  return size_history + 1;
}

void FixWallGranEllipsoid::unpack_restart(int nlocal, int nth)
{
  if (!size_history) return;
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  // another tangential model or number of walls in the run that wrote the file
  if (static_cast<int>(extra[nlocal][m]) != size_history + 1)
    error->one(FLERR,
               "Fix wall/gran/ellipsoid: the restart file holds {} history values per atom, "
               "this fix needs {} (tangential model or walls changed)",
               static_cast<int>(extra[nlocal][m]) - 1, size_history);
  m++;
  for (int k = 0; k < size_history; k++) history_one[nlocal][k] = extra[nlocal][m++];
}

int FixWallGranEllipsoid::size_restart(int /*nlocal*/)
{
  return size_history ? size_history + 1 : 0;
}

int FixWallGranEllipsoid::maxsize_restart()
{
  return size_history ? size_history + 1 : 0;
}
