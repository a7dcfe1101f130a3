/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: pair_style granular/ellipsoid, its restart records (see
   doc/pair_granular_ellipsoid.rst): the solver settings, the force laws as their models'
   rows pack them, the type-pair assignment and the history layout and size of the run that
   wrote the file (one int, history_record(): files of layouts 1 and 2 hold the bare size).
------------------------------------------------------------------------- */

#include "pair_granular_ellipsoid.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_neigh_history.h"

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

// the values the law record gained, newest first: tangential history's xt; rolling sds's
// k_r, gamma_r, mu_r. Each was appended, so the records of earlier versions are its prefixes.
static constexpr int APPENDED_LAW_VALUES[] = {1, 3};

// a law record of this size is this version's or an earlier one's
static bool known_law_record(int size)
{
  int known = packed_law_size();
  if (size == known) return true;
  for (int appended : APPENDED_LAW_VALUES)
    if (size == (known -= appended)) return true;
  return false;
}

void PairGranularEllipsoid::write_restart_settings(FILE *fp)
{
  fwrite(&pipeline.contact.tolerance, sizeof(double), 1, fp);
  fwrite(&pipeline.contact.max_iterations, sizeof(int), 1, fp);
  fwrite(&pipeline.contact.correction_angle, sizeof(double), 1, fp);
  fwrite(&pipeline.contact.wang_band, sizeof(double), 1, fp);
  const int planes = pipeline.use_planes ? 1 : 0, wang = pipeline.use_wang ? 1 : 0;
  fwrite(&planes, sizeof(int), 1, fp);
  fwrite(&wang, sizeof(int), 1, fp);
  fwrite(&impact_velocity, sizeof(double), 1, fp);
}

void PairGranularEllipsoid::read_restart_settings(FILE *fp)
{
  int me = comm->me, planes = 1, wang = 1;
  if (me == 0) {
    utils::sfread(FLERR, &pipeline.contact.tolerance, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &pipeline.contact.max_iterations, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &pipeline.contact.correction_angle, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &pipeline.contact.wang_band, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &planes, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &wang, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &impact_velocity, sizeof(double), 1, fp, nullptr, error);
  }
  MPI_Bcast(&pipeline.contact.tolerance, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&pipeline.contact.max_iterations, 1, MPI_INT, 0, world);
  MPI_Bcast(&pipeline.contact.correction_angle, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&pipeline.contact.wang_band, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&planes, 1, MPI_INT, 0, world);
  MPI_Bcast(&wang, 1, MPI_INT, 0, world);
  MPI_Bcast(&impact_velocity, 1, MPI_DOUBLE, 0, world);
  pipeline.use_planes = planes == 1;
  pipeline.use_wang = wang == 1;
}

/* ----------------------------------------------------------------------
   the laws as their models' rows lay them out (pack_law), after the record size so that a
   file of another layout is refused, then the per-pair history size of the run that wrote it
------------------------------------------------------------------------- */

void PairGranularEllipsoid::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  const int nlaws = static_cast<int>(laws.size()), record = packed_law_size();
  fwrite(&nlaws, sizeof(int), 1, fp);
  fwrite(&record, sizeof(int), 1, fp);
  for (const auto &law : laws) fwrite(pack_law(law).data(), sizeof(double), record, fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      fwrite(&law_index[i][j], sizeof(int), 1, fp);
    }
  const int history = history_record(fix_history ? fix_history->get_dnum() : 0);
  fwrite(&history, sizeof(int), 1, fp);
}

void PairGranularEllipsoid::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  const int me = comm->me;
  int sizes[2] = {0, 0};    // laws, doubles per law
  if (me == 0) utils::sfread(FLERR, sizes, sizeof(int), 2, fp, nullptr, error);
  MPI_Bcast(sizes, 2, MPI_INT, 0, world);
  // the record of an earlier version is the start of this one's: the parameters it lacks
  // keep their defaults
  if (!known_law_record(sizes[1]))
    error->all(FLERR,
               "Pair granular/ellipsoid: the restart file's force laws have {} values each, "
               "this version has {}: the file was written by another version",
               sizes[1], packed_law_size());
  laws.assign(sizes[0], ForceLaw());
  std::vector<double> values = pack_law(ForceLaw());
  for (auto &law : laws) {
    if (me == 0) utils::sfread(FLERR, values.data(), sizeof(double), sizes[1], fp, nullptr, error);
    MPI_Bcast(values.data(), sizes[1], MPI_DOUBLE, 0, world);
    if (!unpack_law(values.data(), law))
      error->all(FLERR, "Pair granular/ellipsoid: the restart file holds an unknown force model");
  }
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      int pair[2] = {0, -1};
      if (me == 0) utils::sfread(FLERR, pair, sizeof(int), 2, fp, nullptr, error);
      MPI_Bcast(pair, 2, MPI_INT, 0, world);
      setflag[i][j] = pair[0];
      law_index[i][j] = law_index[j][i] = pair[1];
    }
  int history = 0;
  if (me == 0) utils::sfread(FLERR, &history, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&history, 1, MPI_INT, 0, world);
  restart_history_layout = history / HISTORY_RECORD_BASE;
  restart_history_size = history % HISTORY_RECORD_BASE;
}
