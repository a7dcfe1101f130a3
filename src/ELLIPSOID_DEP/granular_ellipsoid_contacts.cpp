/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: the pair's contact list for the computes (see granular_ellipsoid_contacts.h)
------------------------------------------------------------------------- */

#include "granular_ellipsoid_contacts.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "update.h"

#include "pair_granular_ellipsoid.h"

using namespace LAMMPS_NS;

ContactList *ContactList::request(LAMMPS *lmp, const char *who)
{
  auto *pair =
      dynamic_cast<PairGranularEllipsoid *>(lmp->force->pair_match("granular/ellipsoid", 1));
  if (!pair) lmp->error->all(FLERR, "{} requires pair style granular/ellipsoid", who);
  ContactList &contacts = pair->contact_list();
  contacts.wanted = true;
  return &contacts;
}

const ContactList &ContactList::current(const ContactList *list, LAMMPS *lmp, const char *who)
{
  if (!list) lmp->error->all(FLERR, "{} used before initialisation (do a run)", who);
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
