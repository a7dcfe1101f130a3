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

/* ---------------------------------------------------------------------- */

FixWallGranEllipsoid::~FixWallGranEllipsoid()
{
  if (allocated && (size_history || peratom_flag)) atom->delete_callback(id, Atom::GROW);
  if (allocated && size_history) atom->delete_callback(id, Atom::RESTART);
  memory->destroy(history_one);
  memory->destroy(array_atom);
  delete[] extlist;
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
    error->all(FLERR, "Fix {} does not support run_style respa", style);
  update_contact_times();
}

/* ----------------------------------------------------------------------
   shortest Hertz contact and damping times against the walls: per type the lightest atom,
   the flattest surface and the largest rotational compliance, at the impact speed (keyword, or the fastest atom of the group)
------------------------------------------------------------------------- */

void FixWallGranEllipsoid::update_contact_times()
{
  const ContactScales scales = contact_scales(lmp, groupbit);
  const double speed = impact_velocity > 0.0 ? impact_velocity : scales.fastest_speed;
  ContactTimes times;
  for (int t = 1; t <= atom->ntypes; t++) {
    const double mass = scales.lightest_mass[t], radius = scales.flattest_radius[t];
    if (!(mass > 0.0 && speed > 0.0)) continue;
    times.add_contact(lmp, law, radius, mass, tangential_mass(mass, scales.compliance[t]), speed,
                      fmt::format("type {}", t));
  }
  report_contact_times(lmp, fmt::format("Fix {}", style), times, speed, times_reported);
}

/* ----------------------------------------------------------------------
   Planes: a wall cutting through a particle's centre is an error (the contact would be
   meaningless); an overlap deeper than half the smallest semi-axis is a warning. A region, at
   its first run: a warning with the number of particles the wall starts inside, of those
   whose centres lie outside it (left alone, as LAMMPS's fix wall/gran/region does) and of the
   deep overlaps.
------------------------------------------------------------------------- */

void FixWallGranEllipsoid::setup(int vflag)
{
  const std::string label = fmt::format("Fix {}", style);
  if (motion.kind != Motion::Kind::Servo) update_walls();
  const EllipsoidAtoms atoms(atom);
  const int nlocal = atom->nlocal;
  double counts[3] = {0.0, 0.0, 0.0};    // centres beyond a wall, deep overlaps, any overlap
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    if (!atoms.has_shape(i)) atoms.missing_shape(lmp, label.c_str(), i, groupbit);
    const Ellipsoid e = atoms.ellipsoid(i);
    const double thin = e.semi_axes.minCoeff();
    if (!reaches_walls(i)) {
      counts[0] += 1.0;
      continue;
    }
    bool overlapping = false;
    for (const WallSurface &w : walls) {
      if (wall_clearance(w, e.center) <= 0.0) {
        counts[0] += 1.0;
        overlapping = false;
        break;
      }
      const ContactGeometry g = wall_contact(e, w);
      if (g.overlap > 0.5 * thin) counts[1] += 1.0;
      if (g.overlap > 0.0) overlapping = true;
    }
    if (overlapping) counts[2] += 1.0;
  }
  double all[3];
  MPI_Allreduce(counts, all, 3, MPI_DOUBLE, MPI_SUM, world);
  // before the first run a centre beyond a wall is bad input; after a run, impacts drove it
  // through (soft contacts: a heavy particle landing on a thin one on the ground), and the
  // plane's half-space contact pushes it back
  if (all[0] > 0.0 && !region_style && !setup_reported)
    error->all(FLERR, "{}: {:.0f} particle centre(s) lie on the solid side of a wall", label,
               all[0]);
  if (all[0] > 0.0 && !region_style && setup_reported && comm->me == 0)
    error->warning(FLERR,
                   "{}: {:.0f} particle centre(s) were driven through a flat wall during the "
                   "last run (contacts too soft for the impacts: a larger kn or a lower drop); "
                   "the wall pushes them back",
                   label, all[0]);
  // a region wall's warnings at its first run only: later runs continue resting contacts
  if (comm->me == 0 && !(region_style && setup_reported)) {
    if (all[0] > 0.0 && region_style)
      error->warning(FLERR,
                     "{}: {:.0f} particle centre(s) lie outside region {}; the wall leaves them "
                     "alone until they are back inside",
                     label, all[0], region_id);
    if (all[2] > 0.0 && region_style)
      error->warning(FLERR, "{}: the wall starts inside {:.0f} particle(s)", label, all[2]);
    if (all[1] > 0.0)
      error->warning(FLERR,
                     "{}: {:.0f} particle(s) overlap a wall by more than half their smallest "
                     "semi-axis at setup",
                     label, all[1]);
  }

  setup_reported = true;

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
  if (history_update || motion.kind != Motion::Kind::Servo) update_walls();
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
    if (!atoms.has_shape(i))
      atoms.missing_shape(lmp, fmt::format("Fix {}", style).c_str(), i, groupbit);
    if (!reaches_walls(i)) continue;
    const double bound = atoms.bounding_radius(i);
    bool built = false, moving = false;
    EllipsoidState state;

    for (int k = 0; k < nwalls; k++) {
      const WallSurface &w = walls[k];
      // bounding sphere clear of the wall (most atoms): no contact, its history forgotten
      // (what match_history does with no contact, without building one)
      if (!(wall_clearance(w, Vec3(x[i][0], x[i][1], x[i][2])) < bound)) {
        if (size_history && history_update)
          std::fill(&history_one[i][history_offset[k]], &history_one[i][history_offset[k + 1]],
                    0.0);
        continue;
      }
      if (!built) {
        state.shape = atoms.ellipsoid(i);
        built = true;
      }
      FaceContacts found = wall_contacts(state.shape, w);
      for (int c = 0; c < found.count; c++) {
        ContactGeometry &g = found.contact[c];
        // a curved wall's iteration cap: the last iterate is used, and counted
        if (g.status == Status::NotConverged) {
          unconverged++;
          if (g.overlap > 0.0) g.status = Status::Overlapping;
        } else if (g.status == Status::Degenerate) {
          degenerate++;
        }
      }
      // each contact region's history slot (a new one's cleared; setup: zeros)
      double *slot[MAX_FACE_CONTACTS];
      match_history(i, k, found, slot);
      for (int c = 0; c < found.count; c++) {
        const ContactGeometry &g = found.contact[c];
        if (g.status != Status::Overlapping) continue;
        if (!moving) {
          atoms.add_motion(i, state);
          moving = true;
        }
        // setup forces look at the stored history without advancing it (on a copy, dt 0), as
        // the pair's do: a step's displacement there would push the particle once, unrecorded
        const LawHistory law_history(slot[c], law.history_size(), history_update);
        const ContactForce result =
            law.compute(g, wall_motion(state, g.point, velocity_at(k, g.point_b)),
                        history_update ? dt : 0.0, law_history.get());
        for (int d = 0; d < 3; d++) {
          f[i][d] += result.force_i[d];
          torque[i][d] += result.torque_i[d];
          wall_force[3 * k + d] -= result.force_i[d];
        }
        if (peratom_flag) record_contact(i, result, g);
      }
    }
  }
  if (motion.kind == Motion::Kind::Servo) {
    MPI_Allreduce(wall_force.data(), wall_force_all.data(), static_cast<int>(wall_force.size()),
                  MPI_DOUBLE, MPI_SUM, world);
    force_flag = 1;
    measure_servo_force();
  }
}

/* ----------------------------------------------------------------------
   the curved walls' contacts the kernel could not settle in this run, counted over ranks
------------------------------------------------------------------------- */

void FixWallGranEllipsoid::post_run()
{
  const double local[2] = {static_cast<double>(unconverged), static_cast<double>(degenerate)};
  double all[2];
  MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_SUM, world);
  if ((all[0] > 0.0 || all[1] > 0.0) && comm->me == 0)
    error->warning(FLERR,
                   "Fix {}: {:.0f} wall contact(s) reached the iteration cap (the last iterate "
                   "was used), {:.0f} were degenerate (no force: a particle swallowed the "
                   "axis or centre of a wall)",
                   style, all[0], all[1]);
  unconverged = degenerate = 0;
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
