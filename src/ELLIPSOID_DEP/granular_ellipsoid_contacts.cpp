/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: the pair's contact list for the computes (see granular_ellipsoid_contacts.h)
------------------------------------------------------------------------- */

#include "granular_ellipsoid_contacts.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "update.h"

#include "pair.h"

using namespace LAMMPS_NS;

namespace {
// The list holds granular/ellipsoid's contacts only. Under pair_style hybrid (any variant)
// another sub-style that can make contacts would have its contacts silently left out: ERROR.
// zero makes none; "none" is no sub-style. PairHybrid keeps its sub-styles protected, so
// every registered style name is asked for with pair_match.
void refuse_other_sub_styles(LAMMPS *lmp, const char *who)
{
  Force *force = lmp->force;
  if (!utils::strmatch(force->pair_style, "^hybrid")) return;
  for (const auto &style : *force->pair_map) {
    const std::string &name = style.first;
    if (name == "granular/ellipsoid" || name == "zero" || utils::strmatch(name, "^hybrid"))
      continue;
    if (force->pair_match(name, 1, 1))    // a sub-style (one or more times)
      lmp->error->all(FLERR,
                      "{} counts the contacts of pair granular/ellipsoid only, but pair_style {} "
                      "also has sub-style {}, whose contacts it would miss (only zero may join "
                      "granular/ellipsoid)",
                      who, force->pair_style, name);
  }
}
}    // namespace

namespace {
// the pair hands out its list through Pair::extract: this file does not know the pair
ContactList *pair_list(LAMMPS *lmp)
{
  Pair *pair = lmp->force->pair_match("granular/ellipsoid", 1);
  int dim = 0;
  return pair ? static_cast<ContactList *>(pair->extract(ContactList::EXTRACT_NAME, dim))
              : nullptr;
}
}    // namespace

ContactList *ContactList::request(LAMMPS *lmp, const char *who)
{
  auto *contacts = pair_list(lmp);
  if (!contacts) lmp->error->all(FLERR, "{} requires pair style granular/ellipsoid", who);
  refuse_other_sub_styles(lmp, who);
  contacts->wanted = true;
  return contacts;
}

const ContactList &ContactList::current(const ContactList *list, LAMMPS *lmp, const char *who)
{
  if (!list) lmp->error->all(FLERR, "{} used before initialisation (do a run)", who);
  // the pair of init() may have been replaced since (pair_style of another style between
  // runs): compare the addresses only, the old list may be freed
  if (pair_list(lmp) != list)
    lmp->error->all(FLERR, "{}: the pair style changed since the last run (do a run)", who);
  if (list->step != lmp->update->ntimestep)
    lmp->error->all(FLERR,
                    "{}: the pair's contacts are not from the current step (invoke it on a step "
                    "where forces were computed; 'run 0' after defining it)",
                    who);
  return *list;
}

void ContactList::sizes(LAMMPS *lmp, int &nlocal, int &nall, int &newton)
{
  nlocal = lmp->atom->nlocal;
  nall = nlocal + lmp->atom->nghost;
  newton = lmp->force->newton_pair;
}

void ContactList::mismatch(LAMMPS *lmp, const char *who)
{
  lmp->error->one(FLERR, "{}: contact list does not match the atoms", who);
}
