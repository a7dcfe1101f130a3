/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: the contacts of the last force evaluation of pair granular/ellipsoid, for the
   computes that need real contacts (never a radius-sum guess). The pair owns the list and
   fills it only while some compute asked for it.

   Owned sides: a contact (i, j) is in the list of the rank that evaluated the pair; i is
   always owned there. Side j is counted there when j is owned or newton_pair is on (the pair
   is then on this rank only; a count on a ghost j must be sent back to its owner). With
   newton_pair off a contact with a ghost j is also in the list of j's owner, which counts
   that side.
------------------------------------------------------------------------- */

#ifndef LMP_GRANULAR_ELLIPSOID_CONTACTS_H
#define LMP_GRANULAR_ELLIPSOID_CONTACTS_H

#include "lmptype.h"

#include <vector>

namespace LAMMPS_NS {
class LAMMPS;

class ContactList {
 public:
  struct Contact {
    int i, j;            // local indices (j may be a ghost)
    double normal[3];    // unit, from i to j
    double point[3];     // contact point, box coordinates
    double overlap;
    double force[3];    // total force on i
  };

  // For a compute's init(): the list of the pair style in use (ERROR naming who, e.g.
  // "Compute contact/histo", when there is none, or when pair_style hybrid has another
  // sub-style than zero, whose contacts the list would miss), which records from now on.
  static ContactList *request(LAMMPS *lmp, const char *who);
  // the name under which the pair's Pair::extract returns its list
  static constexpr const char *EXTRACT_NAME = "contact_list";
  // For a compute's evaluation: the list, after an ERROR naming who unless it was requested
  // (init ran) and holds the contacts of the current step.
  static const ContactList &current(const ContactList *list, LAMMPS *lmp, const char *who);

  // f(contact, count_j) for every contact; count_j: side j is counted on this rank (see the
  // rule above). ERROR naming who when an index does not match the atoms of this rank.
  template <class F> void for_each_owned_side(LAMMPS *lmp, const char *who, F f) const
  {
    int nlocal, nall, newton;
    sizes(lmp, nlocal, nall, newton);
    for (const Contact &c : list) {
      if (c.i < 0 || c.i >= nlocal || c.j < 0 || c.j >= nall) mismatch(lmp, who);
      f(c, c.j < nlocal || newton);
    }
  }

  // the pair's side
  bool recording() const { return wanted; }
  void start(bigint timestep)
  {
    list.clear();
    step = timestep;
  }
  void add(const Contact &c) { list.push_back(c); }
  double memory_usage() const { return static_cast<double>(list.capacity() * sizeof(Contact)); }

 private:
  bool wanted = false;
  bigint step = -1;    // timestep of the evaluation that filled the list (-1: never)
  std::vector<Contact> list;

  static void sizes(LAMMPS *lmp, int &nlocal, int &nall, int &newton);
  [[noreturn]] static void mismatch(LAMMPS *lmp, const char *who);
};

}    // namespace LAMMPS_NS

#endif
