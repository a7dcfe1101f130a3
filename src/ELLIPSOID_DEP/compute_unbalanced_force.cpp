/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: compute unbalanced/force (doc/compute_unbalanced_force.rst)

   ratio = <|F_i|>_i / <|f_c|>_c: F_i the net force on particle i of the group (atom->f at the
   end of the step: pair, walls, gravity and every other fix's force), f_c the total force of a
   contact, the pair's (each contact once) and, with the wall keyword, that of each wall fix's
   contacts array (a particle touching n walls of one fix counts n contacts of |sum| / n).
   Without contacts it is infinite (the particles are not held), with no particle 0.
------------------------------------------------------------------------- */

#include "compute_unbalanced_force.h"

#include "atom.h"
#include "error.h"
#include "fix.h"
#include "modify.h"
#include "update.h"

#include "fix_wall_gran_ellipsoid.h"
#include "granular_ellipsoid_contacts.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace {
const char WHO[] = "Compute unbalanced/force";
const char *const COLNAMES[ComputeUnbalancedForce::NVALUES] = {"unbalanced", "Fnet", "Fcontact",
                                                               "Ncontacts"};
// the wall fixes' contacts array: column 1 the walls touched, 2-4 their force on the particle
constexpr int WALL_COLUMNS = 8;

double length(const double *v)
{
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
}    // namespace

/* ---------------------------------------------------------------------- */

ComputeUnbalancedForce::ComputeUnbalancedForce(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), contacts(nullptr)
{
  if (!atom->ellipsoid_flag)
    error->all(FLERR, "Compute unbalanced/force requires atom style ellipsoid");
  int iarg = 3;
  if (iarg < narg) {
    if (strcmp(arg[iarg], "wall") != 0)
      error->all(FLERR, iarg, "Unknown compute unbalanced/force keyword: {}", arg[iarg]);
    if (++iarg == narg) utils::missing_cmd_args(FLERR, "compute unbalanced/force wall", error);
    for (; iarg < narg; iarg++) wall_ids.emplace_back(arg[iarg]);
  }

  scalar_flag = vector_flag = 1;
  size_vector = NVALUES;
  extscalar = extvector = 0;
  thermo_modify_colname = 1;
  vector = new double[NVALUES];
  for (int k = 0; k < NVALUES; k++) vector[k] = 0.0;
}

ComputeUnbalancedForce::~ComputeUnbalancedForce()
{
  delete[] vector;
}

/* ---------------------------------------------------------------------- */

void ComputeUnbalancedForce::init()
{
  contacts = ContactList::request(lmp, WHO);
  find_walls();
}

/* ----------------------------------------------------------------------
   the wall fixes by their IDs, at init and again at every tally: a fix deleted or defined
   again since the run (unfix, then a library call between runs) is found anew or refused,
   never read through a pointer kept from init()
------------------------------------------------------------------------- */

void ComputeUnbalancedForce::find_walls()
{
  walls.clear();
  for (const auto &wall_id : wall_ids) {
    Fix *fix = modify->get_fix_by_id(wall_id);
    if (!fix) error->all(FLERR, "{}: fix ID {} does not exist", WHO, wall_id);
    if (!dynamic_cast<FixWallGranEllipsoid *>(fix))
      error->all(FLERR, "{}: fix {} is {}, not a granular ellipsoid wall (wall/gran/ellipsoid, "
                 "wall/gran/region/ellipsoid)", WHO, wall_id, fix->style);
    if (!fix->peratom_flag || fix->size_peratom_cols != WALL_COLUMNS)
      error->all(FLERR, "{}: fix {} has no contacts array: add its contacts keyword", WHO,
                 wall_id);
    walls.push_back(fix);
  }
}

std::string ComputeUnbalancedForce::get_thermo_colname(int n)
{
  if (n >= 0 && n < NVALUES) return fmt::format("c_{}:{}", id, COLNAMES[n]);
  return {};
}

double ComputeUnbalancedForce::compute_scalar()
{
  invoked_scalar = update->ntimestep;
  tally();
  scalar = vector[RATIO];
  return scalar;
}

void ComputeUnbalancedForce::compute_vector()
{
  invoked_vector = update->ntimestep;
  tally();
}

/* ----------------------------------------------------------------------
   sums over ranks: |F_i| and particles; |f_c| and contacts. A pair contact is in the list of
   the rank that evaluated it, or of both ranks with newton_pair off and a ghost j: half of it
   per counted side (ContactList::for_each_owned_side) counts it once.
------------------------------------------------------------------------- */

void ComputeUnbalancedForce::tally()
{
  const ContactList &list = ContactList::current(contacts, lmp, WHO);
  find_walls();
  double sums[4] = {0.0, 0.0, 0.0, 0.0};    // |F_i|, particles, |f_c|, contacts
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double **f = atom->f;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    sums[0] += length(f[i]);
    sums[1] += 1.0;
    for (Fix *wall : walls) {
      const double *row = wall->array_atom[i];
      if (row[0] > 0.0) {
        sums[2] += length(row + 1);
        sums[3] += row[0];
      }
    }
  }
  list.for_each_owned_side(lmp, WHO, [&](const ContactList::Contact &c, bool count_j) {
    const double share = count_j ? 1.0 : 0.5;
    sums[2] += share * length(c.force);
    sums[3] += share;
  });
  double all[4];
  MPI_Allreduce(sums, all, 4, MPI_DOUBLE, MPI_SUM, world);

  vector[NET] = all[1] > 0.0 ? all[0] / all[1] : 0.0;
  vector[CONTACT] = all[3] > 0.0 ? all[2] / all[3] : 0.0;
  vector[CONTACTS] = all[3];
  if (all[1] == 0.0) vector[RATIO] = 0.0;
  else vector[RATIO] = vector[CONTACT] > 0.0 ? vector[NET] / vector[CONTACT] : HUGE_VAL;
}
