/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/ellipsoid (see doc/fix_wall_gran_ellipsoid.rst)

   Each wall is a plane; the particle is body i and the wall body j at rest (v_j = omega_j
   = 0, effective mass m_i). The geometry comes from EllipsoidDep::wall_contact
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
    if (word == "wiggle" || word == "shear") {
      iarg += parse_motion(iarg, narg, arg);
      continue;
    }
    if (word == "servo") {
      iarg += parse_servo(iarg, narg, arg);
      continue;
    }
    if (word == "contacts") {    // fix wall/gran's per-atom contact array
      peratom_flag = 1;
      iarg += 1;
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
                 "yplane, zplane, wall_material, wiggle, shear, servo, contacts, "
                 "impact_velocity, or a force-law word)",
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
      // lo: solid below the plane, hi: solid above it
      const double coord = utils::numeric(FLERR, value, false, lmp);
      WallSurface w;
      w.shape = WallShape::Plane;
      w.normal = Vec3::Zero();
      w.normal[dim] = k == 0 ? 1.0 : -1.0;
      w.offset = k == 0 ? coord : -coord;
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
  if (motion.kind == Motion::Kind::Shear)
    for (const WallSurface &w : walls)
      if (w.normal[motion.dim] != 0.0)
        error->all(FLERR,
                   "Fix wall/gran/ellipsoid: shear along {} would move a wall normal to {} "
                   "into the particles (use wiggle)",
                   "xyz"[motion.dim], "xyz"[motion.dim]);
  if (motion.kind == Motion::Kind::Servo && walls.size() != 1)
    error->all(FLERR, "Fix wall/gran/ellipsoid servo moves one wall: give one lo or hi wall (the "
                      "other walls in a fix of their own)");
  for (const WallSurface &w : walls) rest_offset.push_back(w.offset);
  restart_global = motion.kind != Motion::Kind::None ? 1 : 0;
  motion.time_origin = update->ntimestep;
  wall_velocity = Vec3::Zero();

  const int nwalls = static_cast<int>(walls.size());
  vector_flag = 1;
  // a servo's wall also reports where it is (its coordinate along its normal's dimension)
  size_vector = 3 * nwalls + (motion.kind == Motion::Kind::Servo ? 1 : 0);
  global_freq = 1;
  extvector = 1;
  create_attribute = 1;
  dynamic_group_allow = 1;

  wall_force.assign(3 * nwalls, 0.0);
  wall_force_all.assign(3 * nwalls, 0.0);

  size_history = law.history_size() * nwalls;
  restart_peratom = size_history > 0 ? 1 : 0;
  maxexchange = size_history;
  if (peratom_flag) {
    size_peratom_cols = CONTACT_COLUMNS;
    peratom_freq = 1;
  }
  if (size_history || peratom_flag) {
    grow_arrays(atom->nmax);
    atom->add_callback(Atom::GROW);
  }
  if (size_history) {
    atom->add_callback(Atom::RESTART);
    for (int i = 0; i < atom->nlocal; i++)
      for (int m = 0; m < size_history; m++) history_one[i][m] = 0.0;
  }
}

/* ---------------------------------------------------------------------- */

FixWallGranEllipsoid::~FixWallGranEllipsoid()
{
  if (size_history || peratom_flag) atom->delete_callback(id, Atom::GROW);
  if (size_history) atom->delete_callback(id, Atom::RESTART);
  memory->destroy(history_one);
  memory->destroy(array_atom);
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
  if (motion.kind != Motion::Kind::Servo) move_walls();
  const EllipsoidAtoms atoms(atom);
  const int nlocal = atom->nlocal;
  double counts[2] = {0.0, 0.0};
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    if (!atoms.has_shape(i)) atoms.missing_shape(lmp, "Fix wall/gran/ellipsoid", i, groupbit);
    const Ellipsoid e = atoms.ellipsoid(i);
    const double thin = e.semi_axes.minCoeff();
    for (const WallSurface &w : walls) {
      if (wall_clearance(w, e.center) <= 0.0) {
        counts[0] += 1.0;
      } else {
        const ContactGeometry g = wall_contact(e, w);
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
  // a servo moves at time steps only (setup forces look without moving anything)
  if (history_update || motion.kind != Motion::Kind::Servo) move_walls();
  std::fill(wall_force.begin(), wall_force.end(), 0.0);

  const EllipsoidAtoms atoms(atom);
  double **x = atom->x;
  double **f = atom->f;
  double **torque = atom->torque;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double dt = update->dt;
  const int nwalls = static_cast<int>(walls.size());

  if (peratom_flag)
    for (int i = 0; i < nlocal; i++)
      for (int m = 0; m < CONTACT_COLUMNS; m++) array_atom[i][m] = 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    // an atom inserted during the run without a shape (fix deposit): the walls would let it go
    if (!atoms.has_shape(i)) atoms.missing_shape(lmp, "Fix wall/gran/ellipsoid", i, groupbit);
    const double bound = atoms.bounding_radius(i);
    bool built = false, moving = false;
    EllipsoidState state;

    for (int k = 0; k < nwalls; k++) {
      const WallSurface &w = walls[k];
      double *history = wall_history(i, k);
      // bounding sphere clear of the wall: no contact
      ContactGeometry g;
      if (wall_clearance(w, Vec3(x[i][0], x[i][1], x[i][2])) < bound) {
        if (!built) {
          state.shape = atoms.ellipsoid(i);
          built = true;
        }
        g = wall_contact(state.shape, w);
      }
      if (g.status != Status::Overlapping) {
        if (history && history_update) std::fill_n(history, law.history_size(), 0.0);
        continue;
      }
      if (!moving) {
        atoms.add_motion(i, state);
        moving = true;
      }
      // setup forces look at the stored history without advancing it (on a copy, dt 0), as
      // the pair's do: a step's displacement there would push the particle once, unrecorded
      const LawHistory law_history(history, law.history_size(), history_update);
      const ContactForce result = law.compute(g, wall_motion(state, g.point, wall_velocity),
                                              history_update ? dt : 0.0, law_history.get());
      for (int d = 0; d < 3; d++) {
        f[i][d] += result.force_i[d];
        torque[i][d] += result.torque_i[d];
        wall_force[3 * k + d] -= result.force_i[d];
      }
      if (peratom_flag) record_contact(i, result, g);
    }
  }
  // the servo's measure for the next step: the particles' push on its wall, along -n
  if (motion.kind == Motion::Kind::Servo) {
    MPI_Allreduce(wall_force.data(), wall_force_all.data(), static_cast<int>(wall_force.size()),
                  MPI_DOUBLE, MPI_SUM, world);
    force_flag = 1;
    motion.force = -Vec3(wall_force_all[0], wall_force_all[1], wall_force_all[2])
                        .dot(walls[0].normal);
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
  if (n == 3 * static_cast<int>(walls.size())) {    // the servo's wall coordinate
    const Vec3 &normal = walls[0].normal;
    for (int d = 0; d < 3; d++)
      if (normal[d] != 0.0) return walls[0].offset / normal[d];
  }
  return wall_force_all[n];
}

/* ---------------------------------------------------------------------- */

double FixWallGranEllipsoid::memory_usage()
{
  return static_cast<double>(atom->nmax) * (size_history + (peratom_flag ? CONTACT_COLUMNS : 0)) *
      sizeof(double);
}

// the contacts array of fix wall/gran: walls touching (count), the force the walls exert,
// the point on the (last) wall, the contact's R* (an ellipsoid has no one radius)
void FixWallGranEllipsoid::record_contact(int i, const ContactForce &result,
                                          const ContactGeometry &g)
{
  double *row = array_atom[i];
  row[0] += 1.0;
  for (int d = 0; d < 3; d++) {
    row[1 + d] += result.force_i[d];
    row[4 + d] = g.point_b[d];
  }
  row[7] = g.effective_radius;
}
