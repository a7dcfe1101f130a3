/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/ellipsoid and fix wall/gran/region/ellipsoid, the arguments:
   the force law's words, the walls (planes, or a region for the region style) and the
   keywords both styles share (see doc/fix_wall_gran_ellipsoid.rst and
   doc/fix_wall_gran_region_ellipsoid.rst)
------------------------------------------------------------------------- */

#include "fix_wall_gran_ellipsoid.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "update.h"

#include "granular_ellipsoid_atoms.h"
#include "granular_materials.h"

#include <cmath>
#include <cstring>
#include <optional>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

/* ----------------------------------------------------------------------
   fix ID group wall/gran/ellipsoid <force-law words> zplane lo hi [xplane lo hi] ...
       [wall_material E nu | NAME | rigid] [impact_velocity v] [contacts]
       [wiggle dim A period | shear dim v | servo ...]
   fix ID group wall/gran/region/ellipsoid <force-law words> region ID
       [wall_material ...] [impact_velocity v] [contacts]
------------------------------------------------------------------------- */

FixWallGranEllipsoid::FixWallGranEllipsoid(LAMMPS *lmp, int narg, char **arg) :
    FixWallGranEllipsoid(lmp, narg, arg, false)
{
}

FixWallGranEllipsoid::FixWallGranEllipsoid(LAMMPS *lmp, int narg, char **arg,
                                           bool region_walls) :
    Fix(lmp, narg, arg), region_style(region_walls), size_history(0), history_one(nullptr),
    history_update(true), impact_velocity(0.0), force_flag(0)
{
  const std::string label = fmt::format("Fix {}", style);
  const std::string command = fmt::format("fix {}", style);    // LAMMPS's "Illegal fix ..."
  if (narg < 4) utils::missing_cmd_args(FLERR, command, error);
  EllipsoidAtoms::require_granular_style(lmp, label.c_str());

  // the force law: exactly the words pair_coeff takes; by default the wall is of the
  // particles' material (as LAMMPS's fix wall/gran), wall_material gives it its own
  std::vector<std::string> words(arg + 3, arg + narg);
  std::optional<MaterialTable> materials;
  if (names_a_material(words)) materials.emplace(lmp);
  const MaterialLookup lookup = materials ? materials->lookup() : MaterialLookup();
  std::string message;
  const int used = parse_force_law(words, law, message, lookup);
  if (used < 0) error->all(FLERR, "{}: {}", label, message);
  const ForceLaw particle_law = law;

  int iarg = 3 + used;
  if (iarg >= narg)
    error->all(FLERR, "{} needs {} after the force law", label,
               region_style ? "region ID" : "at least one wall (xplane, yplane or zplane lo hi)");
  bool seen[3] = {false, false, false};
  bool wall_material_given = false;
  while (iarg < narg) {
    const std::string word = arg[iarg];
    if (word == "wall_material") {
      if (wall_material_given) error->all(FLERR, iarg, "{}: {} given twice", label, word);
      wall_material_given = true;
      iarg += parse_wall_material(iarg, narg, arg, particle_law, lookup);
    } else if (word == "contacts") {    // fix wall/gran's per-atom contact array
      peratom_flag = 1;
      iarg += 1;
    } else if (word == "impact_velocity") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, command + " " + word, error);
      impact_velocity = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(impact_velocity > 0.0))
        error->all(FLERR, iarg + 1, "{} impact_velocity must be > 0", label);
      iarg += 2;
    } else if (region_style && word == "region") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, command + " region", error);
      if (!region_id.empty()) error->all(FLERR, iarg, "{}: region given twice", label);
      region_id = arg[iarg + 1];
      iarg += 2;
    } else if (region_style && word == "servo") {
      error->all(FLERR, iarg,
                 "{}: servo is a keyword of fix wall/gran/ellipsoid's planes; a piston in this "
                 "region is a plane servo with 'area A' (its area) beside this fix",
                 label);
    } else if (region_style && (word == "wiggle" || word == "shear")) {
      error->all(FLERR, iarg,
                 "{}: {} is a keyword of fix wall/gran/ellipsoid's planes; a region wall moves "
                 "with its region (region keywords move and rotate)",
                 label, word);
    } else if (!region_style && (word == "wiggle" || word == "shear")) {
      iarg += parse_motion(iarg, narg, arg);
    } else if (!region_style && word == "servo") {
      iarg += parse_servo(iarg, narg, arg);
    } else if (!region_style && (word == "xplane" || word == "yplane" || word == "zplane")) {
      iarg += parse_plane(iarg, narg, arg, seen);
    } else if (region_style) {
      error->all(FLERR, iarg,
                 "Unknown {} keyword '{}' (expected region, wall_material, contacts, "
                 "impact_velocity, or a force-law word)",
                 command, word);
    } else {
      error->all(FLERR, iarg,
                 "Unknown {} keyword '{}' (expected xplane, yplane, zplane, wall_material, "
                 "wiggle, shear, servo, contacts, impact_velocity, or a force-law word)",
                 command, word);
    }
  }
  if (region_style) {
    if (region_id.empty()) error->all(FLERR, "{} needs region ID after the force law", label);
    return;    // the derived class builds the walls from the region
  }
  if (walls.empty()) error->all(FLERR, "{}: every wall is NULL; nothing to do", label);
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
  motion.time_origin = simulation_time();
  wall_velocity = Vec3::Zero();
  allocate_walls();
}

/* ----------------------------------------------------------------------
   wall_material E nu | NAME | rigid: the wall's own material under hertz/material, mixed with
   the particles' by the pair's rule; the words used
------------------------------------------------------------------------- */

int FixWallGranEllipsoid::parse_wall_material(int iarg, int narg, char **arg,
                                              const ForceLaw &particle_law,
                                              const MaterialLookup &lookup)
{
  const std::string label = fmt::format("Fix {}", style);
  const std::string command = fmt::format("fix {}", style);
  if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, command + " wall_material", error);
  if (!std::holds_alternative<HertzMaterialNormal>(particle_law.normal))
    error->all(FLERR, iarg, "{}: wall_material needs hertz/material", label);
  ForceLaw wall_side = particle_law;
  auto &wall_normal = std::get<HertzMaterialNormal>(wall_side.normal);
  const std::string value = arg[iarg + 1];
  int nused = 2;
  if (value == "rigid") {
    // an undeformable wall: no compliance, 1/E* = (1 - nu^2)/E of the particle
    wall_normal.youngs = HUGE_VAL;
  } else if (utils::is_double(value)) {
    if (iarg + 3 > narg) utils::missing_cmd_args(FLERR, command + " wall_material E nu", error);
    wall_normal.youngs = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    wall_normal.poisson = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
    const std::string message = wall_side.validate();
    if (!message.empty()) error->all(FLERR, iarg, "{} wall_material: {}", label, message);
    nused = 3;
  } else {
    Material material{};
    const std::string message = lookup(value, material);
    if (!message.empty()) error->all(FLERR, iarg + 1, "{} wall_material: {}", label, message);
    wall_normal.youngs = material.youngs;
    wall_normal.poisson = material.poisson;
  }
  // the pair's mixing rule: the restitution stays the particle law's
  mix_laws(particle_law, wall_side, law);
  return nused;
}

/* ----------------------------------------------------------------------
   xplane|yplane|zplane lo hi (each a number or NULL): lo has the solid below it, hi above
------------------------------------------------------------------------- */

int FixWallGranEllipsoid::parse_plane(int iarg, int narg, char **arg, bool seen[3])
{
  const std::string word = arg[iarg];
  const int dim = word[0] - 'x';
  if (seen[dim]) error->all(FLERR, iarg, "Fix wall/gran/ellipsoid: {} given twice", word);
  seen[dim] = true;
  if (iarg + 3 > narg) utils::missing_cmd_args(FLERR, "fix wall/gran/ellipsoid " + word, error);
  if (domain->periodicity[dim])
    error->all(FLERR, iarg, "Cannot use fix wall/gran/ellipsoid {} in a periodic dimension", word);
  for (int k = 0; k < 2; k++) {
    const char *value = arg[iarg + 1 + k];
    if (strcmp(value, "NULL") == 0) continue;
    if (!utils::is_double(value))
      error->all(FLERR, iarg + 1 + k,
                 "Fix wall/gran/ellipsoid {} {}: expected a number or NULL, got '{}'", word,
                 k == 0 ? "lo" : "hi", value);
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
  return 3;
}

/* ----------------------------------------------------------------------
   the storage that depends on the number of walls: the global vector (the force on each
   wall), the per-atom history per wall and the contacts array
------------------------------------------------------------------------- */

void FixWallGranEllipsoid::allocate_walls()
{
  const int nwalls = static_cast<int>(walls.size());
  vector_flag = 1;
  // a servo's wall also reports where it is (its coordinate along its normal's dimension)
  size_vector = 3 * nwalls + (motion.kind == Motion::Kind::Servo ? 1 : 0);
  global_freq = 1;
  // LAMMPS's extlist: the forces are extensive (thermo_modify norm divides them by the atom
  // count), the servo's coordinate is not
  extvector = -1;
  extlist = new int[size_vector];
  for (int n = 0; n < size_vector; n++) extlist[n] = n < 3 * nwalls ? 1 : 0;
  create_attribute = 1;
  dynamic_group_allow = 1;

  wall_force.assign(3 * nwalls, 0.0);
  wall_force_all.assign(3 * nwalls, 0.0);

  size_history = history_layout();
  restart_peratom = size_history > 0 ? 1 : 0;
  maxexchange = size_history;
  if (peratom_flag) {
    size_peratom_cols = CONTACT_COLUMNS;
    peratom_freq = 1;
  }
  allocated = true;
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
