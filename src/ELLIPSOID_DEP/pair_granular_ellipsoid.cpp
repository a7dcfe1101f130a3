/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: pair_style granular/ellipsoid (see doc/pair_granular_ellipsoid.rst)
------------------------------------------------------------------------- */

#include "pair_granular_ellipsoid.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "fix_dummy.h"
#include "fix_neigh_history.h"
#include "force.h"
#include "granular_ellipsoid_atoms.h"
#include "granular_materials.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstring>
#include <optional>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

static const char HISTORY_DUMMY_ID[] = "NEIGH_HISTORY_GRANULAR_ELLIPSOID_DUMMY";
// the fix that stores the contact rows back, before the history fix (granular_contact_rows.h)
static const char ROWS_DUMMY_ID[] = "STORE_CONTACT_ROWS_GRANULAR_ELLIPSOID_DUMMY";
static const char ROWS_ID[] = "STORE_CONTACT_ROWS_GRANULAR_ELLIPSOID";
// The history fix's ID names its values per pair: read_restart hands a fix the per-atom values
// of the fix of its ID in the file, and a fix of another size (another layout, or a tangential
// history added or removed by a pair_style given again after read_restart) would misread them.
// Under another ID they stay unused (LAMMPS logs "Unused restart file peratom fix info") and
// the contacts start afresh.
static std::string history_fix_id(int size)
{
  return fmt::format("NEIGH_HISTORY_GRANULAR_ELLIPSOID_V{}_{}", PairHistory::LAYOUT_VERSION, size);
}

/* ---------------------------------------------------------------------- */

PairGranularEllipsoid::PairGranularEllipsoid(LAMMPS *lmp) :
    Pair(lmp), law_index(nullptr), max_bounding_dynamic(nullptr), fix_dummy(nullptr),
    fix_store_rows(nullptr),
    fix_history(nullptr), size_history(PairHistory::size(0)), history_update(true),
    freeze_group_bit(0), respa_run(false), restart_history_layout(0), restart_history_size(0),
    impact_velocity(0.0), contact_time(0.0), damping_time(0.0)
{
  // the history fix's IDs are the style's: a second instance (pair_style hybrid listing it
  // twice) would replace the first one's fix and fail at init and at deletion
  if (modify->get_fix_by_id(HISTORY_DUMMY_ID))
    error->all(FLERR,
               "Pair granular/ellipsoid can be used only once (pair_style hybrid lists it "
               "more than once)");
  // Pair's defaults kept: single() and restart info enabled; fix NEIGH_HISTORY's default
  // transfer, which negates every value when i and j swap: PairHistory's swap rule.
  no_virial_fdotr_compute = 1;
  centroidstressflag = CENTROID_NOTAVAIL;
  finitecutflag = 1;
  // History of pairs that do not touch (their cached separating plane) must survive a
  // neighbour-list rebuild: the pair list is not a size list, so ask for every stored pair.
  beyond_contact = 1;

  single_extra = 10;
  svector = new double[single_extra];
  // the counters, for "compute ID all pair granular/ellipsoid" (which sums them over ranks),
  // then the contact and damping times (rank 0 holds them, the others 0, so that the sum is
  // their value)
  nextra = NUM_COUNTERS + 2;
  pvector = new double[nextra];
  local_counters(pvector);
  pvector[NUM_COUNTERS] = pvector[NUM_COUNTERS + 1] = 0.0;
  for (double &c : counters_extracted) c = 0.0;

  // placeholders so the history fix, and before it the fix that stores the contact rows,
  // keep their places in the fix list (as pair granular does)
  modify->add_fix(std::string(ROWS_DUMMY_ID) + " all DUMMY");
  fix_dummy =
      dynamic_cast<FixDummy *>(modify->add_fix(std::string(HISTORY_DUMMY_ID) + " all DUMMY"));
}

/* ---------------------------------------------------------------------- */

PairGranularEllipsoid::~PairGranularEllipsoid()
{
  delete[] svector;
  delete[] pvector;
  if (!fix_history)
    modify->delete_fix(HISTORY_DUMMY_ID);
  else
    modify->delete_fix(history_id);
  // (an input may have deleted it with unfix)
  const char *rows_id = fix_store_rows ? ROWS_ID : ROWS_DUMMY_ID;
  if (modify->get_fix_by_id(rows_id)) modify->delete_fix(rows_id);

  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(law_index);
    memory->destroy(max_bounding_dynamic);
  }
}

/* ---------------------------------------------------------------------- */

void PairGranularEllipsoid::allocate()
{
  allocated = 1;
  int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  memory->create(cutsq, n, n, "pair:cutsq");
  memory->create(law_index, n, n, "pair:law_index");
  memory->create(max_bounding_dynamic, n, "pair:max_bounding_dynamic");
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) {
      setflag[i][j] = 0;
      law_index[i][j] = -1;
    }
}

/* ----------------------------------------------------------------------
   pair_style granular/ellipsoid [tolerance t] [iterations n] [correction deg]
                                 [planes yes/no] [wang yes/no] [preset accurate|fast]
                                 [impact_velocity v]
------------------------------------------------------------------------- */

void PairGranularEllipsoid::settings(int narg, char **arg)
{
  PipelineSettings s;
  double impact = 0.0;
  int iarg = 0;
  while (iarg < narg) {
    const std::string word = arg[iarg];
    if (iarg + 1 >= narg)
      utils::missing_cmd_args(FLERR, "pair_style granular/ellipsoid " + word, error);
    if (word == "tolerance") {
      s.contact.tolerance = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(s.contact.tolerance > 0.0 && s.contact.tolerance < 1.0))
        error->all(FLERR, iarg + 1, "pair_style granular/ellipsoid tolerance must be in (0, 1)");
    } else if (word == "iterations") {
      s.contact.max_iterations = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (s.contact.max_iterations < 1)
        error->all(FLERR, iarg + 1, "pair_style granular/ellipsoid iterations must be >= 1");
    } else if (word == "correction") {
      const double degrees = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(degrees >= 0.0 && degrees <= 180.0))
        error->all(FLERR, iarg + 1,
                   "pair_style granular/ellipsoid correction angle must be in [0, 180] degrees");
      s.contact.correction_angle = degrees * M_PI / 180.0;
    } else if (word == "planes") {
      s.use_planes = utils::logical(FLERR, arg[iarg + 1], false, lmp) == 1;
    } else if (word == "wang") {
      s.use_wang = utils::logical(FLERR, arg[iarg + 1], false, lmp) == 1;
    } else if (word == "preset") {
      const std::string preset = arg[iarg + 1];
      if (preset == "accurate") {
        s.contact.tolerance = 1e-14;
        s.contact.max_iterations = 100;
        s.contact.correction_angle = 0.0;
      } else if (preset == "fast") {
        s.contact.tolerance = 1e-8;
        s.contact.max_iterations = 20;
      } else {
        error->all(FLERR, iarg + 1, "Unknown pair_style granular/ellipsoid preset '{}'", preset);
      }
    } else if (word == "impact_velocity") {
      impact = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(impact > 0.0))
        error->all(FLERR, iarg + 1, "pair_style granular/ellipsoid impact_velocity must be > 0");
    } else {
      error->all(FLERR, iarg, "Unknown pair_style granular/ellipsoid keyword '{}'", word);
    }
    iarg += 2;
  }
  pipeline = s;
  impact_velocity = impact;
}

/* ---------------------------------------------------------------------- */

int PairGranularEllipsoid::add_law(const ForceLaw &law)
{
  laws.push_back(law);
  return static_cast<int>(laws.size()) - 1;
}

/* ----------------------------------------------------------------------
   pair_coeff I J <force-law words> (see parse_force_law)
------------------------------------------------------------------------- */

void PairGranularEllipsoid::coeff(int narg, char **arg)
{
  if (narg < 3) utils::missing_cmd_args(FLERR, "pair_coeff", error);
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);

  std::vector<std::string> words(arg + 2, arg + narg);
  ForceLaw law;
  std::string message;
  std::optional<MaterialTable> materials;
  if (names_a_material(words)) materials.emplace(lmp);
  const int used =
      parse_force_law(words, law, message, materials ? materials->lookup() : MaterialLookup());
  if (used < 0) error->all(FLERR, "pair_coeff granular/ellipsoid: {}", message);
  if (used != static_cast<int>(words.size()))
    error->all(FLERR, used + 2, "Unknown pair_coeff granular/ellipsoid keyword '{}'", words[used]);

  const int index = add_law(law);
  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = MAX(jlo, i); j <= jhi; j++) {
      law_index[i][j] = law_index[j][i] = index;
      setflag[i][j] = 1;
      count++;
    }
  if (count == 0) error->all(FLERR, "Incorrect args for pair coefficients");
}

/* ---------------------------------------------------------------------- */

void PairGranularEllipsoid::init_style()
{
  EllipsoidAtoms::require_granular_style(lmp, "Pair granular/ellipsoid");
  if (comm->ghost_velocity == 0)
    error->all(FLERR,
               "Pair granular/ellipsoid requires ghost atoms store velocity: "
               "use comm_modify vel yes");
  EllipsoidAtoms(atom).require_shapes(lmp, "Pair granular/ellipsoid", atom->nlocal);

  // A plain half list with the bounding-sphere cutoff (atom_style ellipsoid has no radius).
  neighbor->add_request(this, NeighConst::REQ_HISTORY);
  respa_run = utils::strmatch(update->integrate_style, "^respa");

  // every pair's row holds the history of the law that keeps the most
  int law_history = 0;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      ForceLaw law;
      std::string refusal;
      if (law_of_pair(i, j, law, refusal)) law_history = MAX(law_history, law.history_size());
    }
  size_history = PairHistory::size(law_history);
  pipeline.law_slots = law_history;
  // the history fix reads its restart values with its own size: a different size would
  // misread every pair
  const bool restart_layout_differs =
      restart_history_size > 0 && restart_history_layout != PairHistory::LAYOUT_VERSION;
  if (!fix_history && restart_layout_differs)
    error->all(FLERR,
               "Pair granular/ellipsoid: the restart file holds {} history values per pair, a "
               "layout of another version of ELLIPSOID_DEP (this one keeps {} or {}, layout "
               "{}); continue from write_data/read_data (which starts every contact afresh)",
               restart_history_size, PairHistory::size(0),
               PairHistory::size(ForceLaw::MAX_HISTORY_SIZE),
               PairHistory::LAYOUT_VERSION);
  if (!fix_history && restart_history_size > 0 && restart_history_size != size_history)
    error->all(FLERR,
               "Pair granular/ellipsoid: the restart file holds {} history values per pair, "
               "the force laws now need {}: a tangential model with history ({}) cannot be "
               "added or removed across a restart; keep the restart's tangential models, or "
               "continue from write_data/read_data (which starts every contact afresh)",
               restart_history_size, size_history,
               restart_history_size > size_history ? "removed" : "added");

  if (!fix_store_rows)
    fix_store_rows = dynamic_cast<FixStoreContactRows *>(modify->replace_fix(
        ROWS_DUMMY_ID, fmt::format("{} all STORE_CONTACT_ROWS/ELLIPSOID_DEP", ROWS_ID), 1));
  if (!fix_store_rows) error->all(FLERR, "Could not create pair granular/ellipsoid's rows fix");
  fix_store_rows->pair = this;

  if (!fix_history) {
    history_id = history_fix_id(size_history);
    fix_history = dynamic_cast<FixNeighHistory *>(modify->replace_fix(
        HISTORY_DUMMY_ID, fmt::format("{} all NEIGH_HISTORY {}", history_id, size_history), 1));
    fix_history->pair = this;
    fix_dummy = nullptr;
  } else {
    fix_history = dynamic_cast<FixNeighHistory *>(modify->get_fix_by_id(history_id));
    if (!fix_history) error->all(FLERR, "Could not find pair granular/ellipsoid history fix");
    if (fix_history->get_dnum() != size_history)
      error->all(FLERR,
                 "Pair granular/ellipsoid: the tangential models changed between runs; "
                 "history size {} != {}",
                 fix_history->get_dnum(), size_history);
  }

  auto frozen = modify->get_fix_by_style("^freeze");
  if (frozen.size() > 1) error->all(FLERR, "Only one fix freeze command at a time allowed");
  freeze_group_bit = frozen.empty() ? 0 : frozen.front()->groupbit;

  // largest bounding radius per type: atoms present plus what any fix may insert (every
  // inserting fix answers extract("radius", type), as LAMMPS's fix pour and fix deposit do)
  const int ntypes = atom->ntypes;
  std::vector<double> local(ntypes + 1, 0.0);
  for (const auto &ifix : modify->get_fix_list()) {
    for (int t = 1; t <= ntypes; t++) {
      int dim = t;
      auto *radius = static_cast<double *>(ifix->extract("radius", dim));
      if (radius && dim == 0) local[t] = MAX(local[t], *radius);
    }
  }
  const EllipsoidAtoms atoms(atom);
  for (int i = 0; i < atom->nlocal; i++)
    local[atom->type[i]] = MAX(local[atom->type[i]], atoms.bounding_radius(i));
  MPI_Allreduce(local.data(), max_bounding_dynamic, ntypes + 1, MPI_DOUBLE, MPI_MAX, world);

  update_contact_times();
}

/* ----------------------------------------------------------------------
   the law of type pair (i, j): its own, or mixed from those of i i and j j (init_one stores
   it; init_style needs it earlier). false with a reason when there is none.
------------------------------------------------------------------------- */

bool PairGranularEllipsoid::law_of_pair(int i, int j, ForceLaw &law, std::string &refusal) const
{
  if (setflag[i][j]) {
    law = laws[law_index[i][j]];
    return true;
  }
  if (law_index[i][i] < 0 || law_index[j][j] < 0) {
    refusal = fmt::format("coefficients for types {} {} are not set", i, j);
    return false;
  }
  refusal = mix_laws(laws[law_index[i][i]], laws[law_index[j][j]], law);
  if (refusal.empty()) return true;
  refusal = fmt::format("types {} and {} use different models: {}; set pair_coeff {} {} explicitly",
                        i, j, refusal, i, j);
  return false;
}

/* ---------------------------------------------------------------------- */

double PairGranularEllipsoid::init_one(int i, int j)
{
  if (setflag[i][j] == 0) {
    ForceLaw mixed;
    std::string refusal;
    if (!law_of_pair(i, j, mixed, refusal))
      error->all(FLERR, "Pair granular/ellipsoid: {}", refusal);
    // mixed laws are recomputed at every init: reuse their slot
    if (law_index[i][j] >= 0)
      laws[law_index[i][j]] = mixed;
    else
      law_index[i][j] = law_index[j][i] = add_law(mixed);
  }

  // two bounding spheres; when no atom of a type exists yet, fall back to the largest known
  double ri = max_bounding_dynamic[i], rj = max_bounding_dynamic[j];
  double largest = 0.0;
  for (int t = 1; t <= atom->ntypes; t++) largest = MAX(largest, max_bounding_dynamic[t]);
  if (ri <= 0.0) ri = largest;
  if (rj <= 0.0) rj = largest;
  double cut = ri + rj;
  if (cut <= 0.0)
    error->all(FLERR,
               "Pair granular/ellipsoid cannot size its cutoff: no ellipsoid exists and "
               "no fix pour/ellipsoid announces one");
  return cut;
}

/* ---------------------------------------------------------------------- */

double PairGranularEllipsoid::memory_usage()
{
  return static_cast<double>(states.capacity() * sizeof(EllipsoidState) +
                             state_keys.capacity() * sizeof(ShapeKey) + omega_known.capacity() +
                             ghost_owner.capacity() * sizeof(int) +
                             candidates.memory_usage() + contact_rows.memory_usage()) +
      contacts.memory_usage();
}
