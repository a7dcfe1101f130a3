/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/ellipsoid, the per-atom wall history (the force law's history
   of each atom against each wall, ForceLaw::history_size() doubles, per contact region of a
   wall that may have several): its layout, the contact regions' slots from step to step,
   growth, exchange between ranks and restart files, so that it travels with its atom
------------------------------------------------------------------------- */

#include "fix_wall_gran_ellipsoid.h"

#include "atom.h"
#include "error.h"
#include "memory.h"

#include <algorithm>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

namespace {
constexpr int NORMAL = 3;    // a slot's contact normal, before the law's history
}

// per wall: the law's history, or for a wall with several contact regions one slot each,
// its contact's normal and the law's history; nothing without a law history
int FixWallGranEllipsoid::history_layout()
{
  const int law_size = law.history_size();
  history_offset.assign(walls.size() + 1, 0);
  for (std::size_t k = 0; k < walls.size(); k++) {
    const int size = several_contacts(walls[k]) ? MAX_FACE_CONTACTS * (NORMAL + law_size) : law_size;
    history_offset[k + 1] = history_offset[k] + (law_size > 0 ? size : 0);
  }
  return history_offset.back();
}

/* ----------------------------------------------------------------------
   the law's history of each contact of atom i with wall k (null: none). A contact region
   keeps its slot from step to step: the contacts take the slots whose stored normals are
   nearest (the pairing with the larger sum of dot products); one that turned by more than 90
   degrees from its slot's (or found it empty) is a new region, its history cleared; a slot
   no contact took is cleared. Setup forces change nothing: a new region reads zeros.
------------------------------------------------------------------------- */

void FixWallGranEllipsoid::match_history(int i, int k, const FaceContacts &found, double *slot[])
{
  static std::array<double, ForceLaw::MAX_HISTORY_SIZE> zeros{};    // read, never written
  const int law_size = law.history_size();
  for (int c = 0; c < MAX_FACE_CONTACTS; c++) slot[c] = nullptr;
  if (!size_history) return;
  double *row = &history_one[i][history_offset[k]];
  auto touching = [&](int c) {
    return c < found.count && found.contact[c].status == Status::Overlapping;
  };
  if (!several_contacts(walls[k])) {
    if (touching(0))
      slot[0] = row;
    else if (history_update)
      std::fill_n(row, law_size, 0.0);
    return;
  }
  const int stride = NORMAL + law_size;
  auto stored = [&](int j) { return Eigen::Map<const Vec3>(row + j * stride); };
  auto dot = [&](int c, int j) { return touching(c) ? stored(j).dot(found.contact[c].normal) : 0.0; };
  const bool swap = dot(0, 1) + dot(1, 0) > dot(0, 0) + dot(1, 1);
  bool taken[MAX_FACE_CONTACTS] = {false, false};
  for (int c = 0; c < found.count; c++) {
    if (!touching(c)) continue;
    const int j = swap ? 1 - c : c;
    double *s = row + j * stride;
    taken[j] = true;
    const bool fresh = !(stored(j).dot(found.contact[c].normal) > 0.0);
    if (!history_update) {
      slot[c] = fresh ? zeros.data() : s + NORMAL;
      continue;
    }
    if (fresh) std::fill_n(s, stride, 0.0);
    Eigen::Map<Vec3> normal(s);
    normal = found.contact[c].normal;
    slot[c] = s + NORMAL;
  }
  if (history_update)
    for (int j = 0; j < MAX_FACE_CONTACTS; j++)
      if (!taken[j]) std::fill_n(row + j * stride, stride, 0.0);
}

/* ---------------------------------------------------------------------- */

void FixWallGranEllipsoid::grow_arrays(int nmax)
{
  if (size_history) memory->grow(history_one, nmax, size_history, "wall/gran/ellipsoid:history");
  if (peratom_flag) {
    memory->grow(array_atom, nmax, CONTACT_COLUMNS, "wall/gran/ellipsoid:contacts");
    // the rows are filled at every step (post_force, before any output reads them); until
    // then they hold no contact
    for (int i = 0; i < nmax; i++)
      for (int m = 0; m < CONTACT_COLUMNS; m++) array_atom[i][m] = 0.0;
  }
}

void FixWallGranEllipsoid::copy_arrays(int i, int j, int /*delflag*/)
{
  for (int m = 0; m < size_history; m++) history_one[j][m] = history_one[i][m];
  if (peratom_flag)
    for (int m = 0; m < CONTACT_COLUMNS; m++) array_atom[j][m] = array_atom[i][m];
}

void FixWallGranEllipsoid::set_arrays(int i)
{
  for (int m = 0; m < size_history; m++) history_one[i][m] = 0.0;
  if (peratom_flag)
    for (int m = 0; m < CONTACT_COLUMNS; m++) array_atom[i][m] = 0.0;
}

int FixWallGranEllipsoid::pack_exchange(int i, double *buf)
{
  for (int m = 0; m < size_history; m++) buf[m] = history_one[i][m];
  return size_history;
}

int FixWallGranEllipsoid::unpack_exchange(int nlocal, double *buf)
{
  for (int m = 0; m < size_history; m++) history_one[nlocal][m] = buf[m];
  return size_history;
}

int FixWallGranEllipsoid::pack_restart(int i, double *buf)
{
  if (!size_history) return 0;
  // buf[0] = count including itself, the convention other fixes unpack by
  buf[0] = size_history + 1;
  for (int m = 0; m < size_history; m++) buf[m + 1] = history_one[i][m];
  return size_history + 1;
}

void FixWallGranEllipsoid::unpack_restart(int nlocal, int nth)
{
  if (!size_history) return;
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  // another tangential model, number of walls or layout in the run that wrote the file
  if (static_cast<int>(extra[nlocal][m]) != size_history + 1)
    error->one(FLERR,
               "Fix {}: the restart file holds {} history values per atom, "
               "this fix needs {} (tangential model, walls or the layout changed: a curved "
               "region face now keeps a slot per contact region)",
               style, static_cast<int>(extra[nlocal][m]) - 1, size_history);
  m++;
  for (int k = 0; k < size_history; k++) history_one[nlocal][k] = extra[nlocal][m++];
}

int FixWallGranEllipsoid::size_restart(int /*nlocal*/)
{
  return size_history ? size_history + 1 : 0;
}

int FixWallGranEllipsoid::maxsize_restart()
{
  return size_history ? size_history + 1 : 0;
}
