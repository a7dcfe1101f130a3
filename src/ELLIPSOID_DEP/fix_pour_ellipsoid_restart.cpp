/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix pour/ellipsoid, its restart record: the generator's state, the counters
   and schedule, and the arguments the pour was defined with, which a re-specified fix must
   repeat (see doc/fix_pour_ellipsoid.rst, "Restart")
------------------------------------------------------------------------- */

#include "fix_pour_ellipsoid.h"

#include "comm.h"
#include "error.h"
#include "random_park.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

/* ----------------------------------------------------------------------
   global state: RNG seed, counters and schedule, then the arguments the pour was defined
   with (its particles and schedule follow from them and the generator's state: a pour
   re-specified with others after read_restart would silently be another pour)
------------------------------------------------------------------------- */

// first value of a record that holds the arguments (records before 2 Dec 2026 start with
// the generator's state, which is > 0), and of one that also holds, after them, the counts
// of trial positions rejected at the region's side and at walls (older: 0)
static constexpr double RESTART_WITH_ARGUMENTS = -2.0;
static constexpr double RESTART_WITH_SIDE_COUNTS = -3.0;

std::vector<FixPourEllipsoid::Argument> FixPourEllipsoid::arguments() const
{
  const PourDistribution &d = distribution;
  return {{"seed", {double(seed)}},
          {"N", {double(ninsert)}},
          {"type", {double(ntype)}},
          {"size", {d.rmin, d.rmax}},
          {"alpha", {d.alpha}},
          {"beta", {d.beta}},
          {"shape", {d.eta, d.zeta}},
          {"dshape", {d.delta_eta, d.delta_zeta}},
          {"density", {density}},
          {"vol", {volfrac, double(maxattempt)}},
          {"rate", {rate}},
          {"vel", {vxlo, vxhi, vylo, vyhi, vz}},
          {"release", {cloud ? 1.0 : 0.0}},
          {"every", {double(every)}},
          {"region", region_values()}};
}

// an argument's values as the command gives them
std::string FixPourEllipsoid::argument_words(const std::string &keyword,
                                             const std::vector<double> &values)
{
  if (keyword == "release") return values[0] != 0.0 ? "cloud" : "stream";
  std::string words;
  for (std::size_t k = 0; k < values.size(); k++) {
    if (k > 0) words += " ";
    if (keyword == "region" && k == 0)
      words += values[0] == 1.0 ? "block" : "cylinder";
    else
      words += fmt::format("{}", values[k]);
  }
  return words;
}

void FixPourEllipsoid::write_restart(FILE *fp)
{
  std::vector<double> list;
  list.push_back(RESTART_WITH_SIDE_COUNTS);
  list.push_back(random->state());
  list.push_back(ubuf(ninserted).d);
  list.push_back(ubuf(nfailed).d);
  list.push_back(ubuf(nrejected).d);
  list.push_back(ubuf(nfirst).d);
  list.push_back(ubuf(next_insert).d);
  list.push_back(ubuf(update->ntimestep).d);
  list.push_back(nper);
  list.push_back(nfreq);
  list.push_back(grav);
  list.push_back(initialized);
  for (const Argument &argument : arguments())
    list.insert(list.end(), argument.values.begin(), argument.values.end());
  list.push_back(ubuf(nside).d);
  list.push_back(ubuf(nwall).d);
  if (comm->me == 0) {
    const int size = static_cast<int>(list.size() * sizeof(double));
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list.data(), sizeof(double), list.size(), fp);
  }
}

void FixPourEllipsoid::restart(char *buf)
{
  auto *list = (double *) buf;
  int n = 0;
  const bool with_side_counts = list[0] == RESTART_WITH_SIDE_COUNTS;
  const bool with_arguments = with_side_counts || list[0] == RESTART_WITH_ARGUMENTS;
  if (with_arguments) n++;
  const int state = static_cast<int>(list[n++]);
  ninserted = ubuf(list[n++]).i;
  nfailed = ubuf(list[n++]).i;
  nrejected = ubuf(list[n++]).i;
  nfirst = ubuf(list[n++]).i;
  next_insert = ubuf(list[n++]).i;
  const bigint step = ubuf(list[n++]).i;
  nper = static_cast<int>(list[n++]);
  nfreq = static_cast<int>(list[n++]);
  grav = list[n++];
  initialized = static_cast<int>(list[n++]);
  if (step != update->ntimestep)
    error->all(FLERR, "Must not reset the timestep when restarting fix pour/ellipsoid");

  // the command must be the one the pour was written with (to 1e-12 relative: a value
  // computed in another order is the same argument)
  std::vector<Argument> written;
  if (with_arguments) {
    for (Argument argument : arguments()) {
      for (double &value : argument.values) value = list[n++];
      written.push_back(argument);
    }
  } else {    // an older record holds N only
    written.push_back({"N", {list[n++]}});
  }
  nside = with_side_counts ? ubuf(list[n++]).i : 0;
  nwall = with_side_counts ? ubuf(list[n++]).i : 0;
  const std::vector<Argument> given = arguments();
  for (const Argument &old : written) {
    const Argument &now = *std::find_if(given.begin(), given.end(), [&](const Argument &a) {
      return a.keyword == old.keyword;
    });
    bool same = true;
    for (std::size_t k = 0; k < now.values.size(); k++)
      same &= fabs(now.values[k] - old.values[k]) <=
          1e-12 * MAX(fabs(now.values[k]), fabs(old.values[k]));
    if (!same)
      error->all(FLERR,
                 "Fix pour/ellipsoid {}: {} {} differs from the restart file's {} {}: a pour "
                 "continues only with the arguments it was written with (give a new fix ID "
                 "for another pour)",
                 id, now.keyword, argument_words(now.keyword, now.values), old.keyword,
                 argument_words(old.keyword, old.values));
  }
  random->reset(state);
}

