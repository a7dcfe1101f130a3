/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/ellipsoid, the per-atom wall history (the force law's history
   of each atom against each wall, ForceLaw::history_size() doubles): growth, exchange between
   ranks and restart files, so that it travels with its atom
------------------------------------------------------------------------- */

#include "fix_wall_gran_ellipsoid.h"

#include "atom.h"
#include "error.h"
#include "memory.h"

using namespace LAMMPS_NS;

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
  // another tangential model or number of walls in the run that wrote the file
  if (static_cast<int>(extra[nlocal][m]) != size_history + 1)
    error->one(FLERR,
               "Fix {}: the restart file holds {} history values per atom, "
               "this fix needs {} (tangential model or walls changed)",
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
