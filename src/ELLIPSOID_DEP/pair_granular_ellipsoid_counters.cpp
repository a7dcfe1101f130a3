/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: pair_style granular/ellipsoid, its counters (see doc/pair_granular_ellipsoid.rst):
   the vector of compute pair, Pair::extract and the end-of-run report, all in the order and
   with the names of EllipsoidDep::PIPELINE_COUNTERS.
------------------------------------------------------------------------- */

#include "pair_granular_ellipsoid.h"

#include "comm.h"
#include "error.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

void PairGranularEllipsoid::local_counters(double *out) const
{
  for (int k = 0; k < NUM_COUNTERS; k++)
    out[k] = static_cast<double>(counters.*PIPELINE_COUNTERS[k].member);
}

void PairGranularEllipsoid::global_counters(double *out) const
{
  double local[NUM_COUNTERS];
  local_counters(local);
  MPI_Allreduce(local, out, NUM_COUNTERS, MPI_DOUBLE, MPI_SUM, world);
}

/* ----------------------------------------------------------------------
   Pair::extract of the counters: "counters": this rank's counters (dim 1, table order);
   "counters/NAME": one of them (dim 0). Not collective, so a library caller may ask on one
   rank alone; compute pair and the end-of-run report give the sums over ranks.
------------------------------------------------------------------------- */

void *PairGranularEllipsoid::extract_counters(const char *name, int &dim)
{
  static const char prefix[] = "counters/";
  if (std::strcmp(name, "counters") == 0) {
    dim = 1;
    local_counters(counters_extracted);
    return (void *) counters_extracted;
  }
  if (std::strncmp(name, prefix, sizeof(prefix) - 1) == 0)
    for (int k = 0; k < NUM_COUNTERS; k++)
      if (std::strcmp(name + sizeof(prefix) - 1, PIPELINE_COUNTERS[k].name) == 0) {
        dim = 0;
        local_counters(counters_extracted);
        return (void *) &counters_extracted[k];
      }
  return nullptr;
}

/* ----------------------------------------------------------------------
   end of run: the counters once for people and once as JSON for programs
------------------------------------------------------------------------- */

void PairGranularEllipsoid::finish()
{
  double c[NUM_COUNTERS];
  global_counters(c);
  if (comm->me != 0) return;
  std::string line = "granular/ellipsoid:", json;
  for (int k = 0; k < NUM_COUNTERS; k++) {
    line += fmt::format("{} {:.0f} {}", k ? "," : "", c[k], PIPELINE_COUNTERS[k].label);
    json += fmt::format("{}\"{}\": {:.0f}", k ? ", " : "", PIPELINE_COUNTERS[k].name, c[k]);
  }
  const double contacts_made = c[counter_index(&PipelineCounters::contacts)];
  const double iterations = c[counter_index(&PipelineCounters::iterations)];
  line += fmt::format(", {:.2f} mean iterations",
                      contacts_made > 0.0 ? iterations / contacts_made : 0.0);
  utils::logmesg(lmp, "{}\ngranular/ellipsoid counters: {{{}}}\n", line, json);
  const double not_converged = c[counter_index(&PipelineCounters::not_converged)];
  const double degenerate = c[counter_index(&PipelineCounters::degenerate)];
  if (not_converged > 0.0)
    error->warning(FLERR,
                   "granular/ellipsoid: {:.0f} contact evaluations did not converge "
                   "within {} iterations (used with their last iterate)",
                   not_converged, pipeline.contact.max_iterations);
  if (degenerate > 0.0)
    error->warning(FLERR,
                   "granular/ellipsoid: {:.0f} pair evaluations had degenerate input "
                   "(non-finite positions or shapes) and gave no force",
                   degenerate);
}

/* ----------------------------------------------------------------------
   the counters (extract_counters), "contact_time": the shortest Hertz contact time of the
   last run start, or "damping_time": its shortest damping time (dim 0; 0: no moving atoms
   to judge by, or for the damping time an undamped law)
------------------------------------------------------------------------- */

void *PairGranularEllipsoid::extract(const char *name, int &dim)
{
  if (void *counter = extract_counters(name, dim)) return counter;
  // the contacts of the last force evaluation, recorded once a compute requested them
  // (ContactList::request)
  if (std::strcmp(name, ContactList::EXTRACT_NAME) == 0) {
    dim = 0;
    return &contacts;
  }
  if (std::strcmp(name, "contact_time") == 0) {
    dim = 0;
    return (void *) &contact_time;
  }
  if (std::strcmp(name, "damping_time") == 0) {
    dim = 0;
    return (void *) &damping_time;
  }
  return nullptr;
}
