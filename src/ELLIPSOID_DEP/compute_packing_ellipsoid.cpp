/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: compute packing/ellipsoid (doc/compute_packing_ellipsoid.rst)

   Global vector (1-based in input scripts):
     1 volume fraction of the slab [zlo, zhi]   (exact ellipsoid-slab volumes / Lx Ly (zhi-zlo))
     2 number of particles with centre in the slab
     3 mean coordination number Z of those particles
     4 Z without rattlers (iterative removal of particles with < rattler_min contacts)
     5 zlo used   6 zhi used
     7 number of rattlers with centre in the slab
     8 mean volume-equivalent diameter 2 (abc)^(1/3) of the group
     9 solid volume inside the slab
------------------------------------------------------------------------- */

#include "compute_packing_ellipsoid.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "update.h"

#include "granular_ellipsoid_atoms.h"
#include "granular_ellipsoid_contacts.h"

#include <cfloat>
#include <cmath>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;

namespace {
const char WHO[] = "Compute packing/ellipsoid";
const char *const COLNAMES[ComputePackingEllipsoid::NVALUES] = {
    "phi", "Nslab", "Z", "Z_norattler", "zlo", "zhi", "Nrattler", "dmean", "Vsolid"};
}    // namespace

/* ---------------------------------------------------------------------- */

ComputePackingEllipsoid::ComputePackingEllipsoid(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), contacts(nullptr), automatic(false), zlo_user(0.0), zhi_user(0.0),
    zlo_edge(0), zhi_edge(0), nbottom(0.0), ntop(0.0), floor_given(false), floor_z(0.0),
    surface_mode(0), rattler_min(2), nmax(0), ncontact(nullptr), active(nullptr)
{
  if (narg < 4) utils::missing_cmd_args(FLERR, "compute packing/ellipsoid", error);
  if (!atom->ellipsoid_flag)
    error->all(FLERR, "Compute packing/ellipsoid requires atom style ellipsoid");

  int iarg = 3;
  if (strcmp(arg[iarg], "auto") == 0) {
    automatic = true;
    iarg++;
    bool have_bottom = false, have_top = false;
    while (iarg < narg) {
      if (strcmp(arg[iarg], "bottom") == 0) {
        if (iarg + 2 > narg)
          utils::missing_cmd_args(FLERR, "compute packing/ellipsoid bottom", error);
        nbottom = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
        have_bottom = true;
        iarg += 2;
      } else if (strcmp(arg[iarg], "top") == 0) {
        if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "compute packing/ellipsoid top", error);
        ntop = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
        have_top = true;
        iarg += 2;
      } else
        break;
    }
    if (!have_bottom || !have_top)
      error->all(FLERR, "Compute packing/ellipsoid auto needs both 'bottom Nb' and 'top Nt'");
    if (nbottom < 0.0 || ntop < 0.0)
      error->all(FLERR, "Compute packing/ellipsoid auto: Nb and Nt must be >= 0");
  } else {
    if (narg < 5) utils::missing_cmd_args(FLERR, "compute packing/ellipsoid", error);
    if (strcmp(arg[3], "EDGE") == 0)
      zlo_edge = 1;
    else
      zlo_user = utils::numeric(FLERR, arg[3], false, lmp);
    if (strcmp(arg[4], "EDGE") == 0)
      zhi_edge = 1;
    else
      zhi_user = utils::numeric(FLERR, arg[4], false, lmp);
    if (!zlo_edge && !zhi_edge && !(zhi_user > zlo_user))
      error->all(FLERR, "Compute packing/ellipsoid needs zhi > zlo");
    iarg = 5;
  }

  while (iarg < narg) {
    if (strcmp(arg[iarg], "rattler") == 0) {
      if (iarg + 2 > narg)
        utils::missing_cmd_args(FLERR, "compute packing/ellipsoid rattler", error);
      rattler_min = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (rattler_min < 0) error->all(FLERR, "Compute packing/ellipsoid rattler must be >= 0");
      iarg += 2;
    } else if (strcmp(arg[iarg], "floor") == 0 && automatic) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "compute packing/ellipsoid floor", error);
      floor_given = true;
      floor_z = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      iarg += 2;
    } else if (strcmp(arg[iarg], "surface") == 0 && automatic) {
      if (iarg + 2 > narg)
        utils::missing_cmd_args(FLERR, "compute packing/ellipsoid surface", error);
      if (strcmp(arg[iarg + 1], "max") == 0)
        surface_mode = 0;
      else if (strcmp(arg[iarg + 1], "columns") == 0)
        surface_mode = 1;
      else
        error->all(FLERR, "Compute packing/ellipsoid surface must be 'max' or 'columns'");
      iarg += 2;
    } else
      error->all(FLERR, "Unknown compute packing/ellipsoid keyword: {}", arg[iarg]);
  }

  vector_flag = 1;
  size_vector = NVALUES;
  extvector = 0;
  thermo_modify_colname = 1;
  comm_forward = 1;
  comm_reverse = 1;
  vector = new double[NVALUES];
  for (int k = 0; k < NVALUES; k++) vector[k] = 0.0;
}

/* ---------------------------------------------------------------------- */

ComputePackingEllipsoid::~ComputePackingEllipsoid()
{
  delete[] vector;
  memory->destroy(ncontact);
  memory->destroy(active);
}

/* ---------------------------------------------------------------------- */

void ComputePackingEllipsoid::init()
{
  contacts = ContactList::request(lmp, WHO);
  if (domain->triclinic)
    error->all(FLERR, "Compute packing/ellipsoid requires an orthogonal simulation box");
  if (domain->dimension != 3) error->all(FLERR, "Compute packing/ellipsoid requires 3d");
}

/* ---------------------------------------------------------------------- */

std::string ComputePackingEllipsoid::get_thermo_colname(int n)
{
  if (n >= 0 && n < NVALUES) return fmt::format("c_{}:{}", id, COLNAMES[n]);
  return {};
}

/* ---------------------------------------------------------------------- */

void ComputePackingEllipsoid::grow()
{
  if (atom->nmax > nmax) {
    nmax = atom->nmax;
    memory->destroy(ncontact);
    memory->destroy(active);
    memory->create(ncontact, nmax, "packing/ellipsoid:ncontact");
    memory->create(active, nmax, "packing/ellipsoid:active");
  }
}

/* ----------------------------------------------------------------------
   ncontact[i] for owned i = number of recorded contacts with both partners active, counted
   once per owned side (ContactList); with newton_pair on the ghosts' counts go back to their
   owners.
------------------------------------------------------------------------- */

void ComputePackingEllipsoid::count_contacts(int nall)
{
  for (int i = 0; i < nall; i++) ncontact[i] = 0.0;
  contacts->for_each_owned_side(lmp, WHO, [&](const ContactList::Contact &c, bool count_j) {
    if (active[c.i] == 0.0 || active[c.j] == 0.0) return;
    ncontact[c.i] += 1.0;
    if (count_j) ncontact[c.j] += 1.0;
  });
  if (force->newton_pair) { comm->reverse_comm(this); }
}

/* ----------------------------------------------------------------------
   the slab: user bounds, or from the deposit's extent in auto mode
------------------------------------------------------------------------- */

void ComputePackingEllipsoid::slab_bounds(double &zlo, double &zhi, double &dmean)
{
  const int nlocal = atom->nlocal;
  int *mask = atom->mask;

  const EllipsoidAtoms atoms(atom);
  double local[2] = {0.0, 0.0};    // sum of diameters, count
  double zbot = DBL_MAX, ztop = -DBL_MAX;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const EllipsoidDep::Ellipsoid e = atoms.ellipsoid(i);
    const double d = 2.0 * std::cbrt(e.semi_axes[0] * e.semi_axes[1] * e.semi_axes[2]);
    local[0] += d;
    local[1] += 1.0;
    const double h = std::sqrt(e.inverse_form(2, 2));
    zbot = MIN(zbot, e.center[2] - h);
    ztop = MAX(ztop, e.center[2] + h);
  }
  double global[2];
  MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_SUM, world);
  dmean = global[1] > 0.0 ? global[0] / global[1] : 0.0;

  if (!automatic) {
    zlo = zlo_edge ? domain->boxlo[2] : zlo_user;
    zhi = zhi_edge ? domain->boxhi[2] : zhi_user;
    return;
  }
  if (global[1] == 0.0) {
    zlo = zhi = domain->boxlo[2];
    return;
  }

  double zbot_all, ztop_all;
  MPI_Allreduce(&zbot, &zbot_all, 1, MPI_DOUBLE, MPI_MIN, world);
  MPI_Allreduce(&ztop, &ztop_all, 1, MPI_DOUBLE, MPI_MAX, world);
  if (floor_given) zbot_all = floor_z;

  if (surface_mode == 1) {
    // mean over a grid of columns (edge ~ one mean diameter) of the highest particle top in
    // each column; a column is the one holding the particle's centre; empty columns skipped
    const int nx = MAX(1, MIN(1000, static_cast<int>(domain->xprd / dmean)));
    const int ny = MAX(1, MIN(1000, static_cast<int>(domain->yprd / dmean)));
    std::vector<double> top(static_cast<size_t>(nx) * ny, -DBL_MAX), top_all(top.size());
    const EllipsoidAtoms atoms(atom);
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      const EllipsoidDep::Ellipsoid e = atoms.ellipsoid(i);
      const double h = std::sqrt(e.inverse_form(2, 2));
      int ix = static_cast<int>((atom->x[i][0] - domain->boxlo[0]) / domain->xprd * nx);
      int iy = static_cast<int>((atom->x[i][1] - domain->boxlo[1]) / domain->yprd * ny);
      ix = MAX(0, MIN(nx - 1, ix));
      iy = MAX(0, MIN(ny - 1, iy));
      double &t = top[static_cast<size_t>(iy) * nx + ix];
      t = MAX(t, e.center[2] + h);
    }
    MPI_Allreduce(top.data(), top_all.data(), static_cast<int>(top.size()), MPI_DOUBLE, MPI_MAX,
                  world);
    double sum = 0.0;
    int n = 0;
    for (double t : top_all)
      if (t > -DBL_MAX) {
        sum += t;
        n++;
      }
    ztop_all = sum / n;
  }

  zlo = zbot_all + nbottom * dmean;
  zhi = ztop_all - ntop * dmean;
  if (zhi < zlo) zhi = zlo;    // empty slab: volume fraction 0, no particles
}

/* ---------------------------------------------------------------------- */

void ComputePackingEllipsoid::compute_vector()
{
  invoked_vector = update->ntimestep;
  ContactList::current(contacts, lmp, WHO);

  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  int *mask = atom->mask;
  int *ellipsoid = atom->ellipsoid;

  int bad = 0;
  for (int i = 0; i < nlocal; i++)
    if ((mask[i] & groupbit) && ellipsoid[i] < 0) bad = 1;
  int bad_all;
  MPI_Allreduce(&bad, &bad_all, 1, MPI_INT, MPI_MAX, world);
  if (bad_all)
    error->all(FLERR, "Compute packing/ellipsoid: every atom of the group must have a shape");

  double zlo, zhi, dmean;
  slab_bounds(zlo, zhi, dmean);

  // solid volume in the slab (with the images across a periodic z boundary)
  const EllipsoidAtoms atoms(atom);
  double vsolid = 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    EllipsoidDep::Ellipsoid e = atoms.ellipsoid(i);
    vsolid += EllipsoidDep::ellipsoid_slab_volume(e, zlo, zhi);
    if (domain->zperiodic) {
      const double z0 = e.center[2];
      for (int s = -1; s <= 1; s += 2) {
        e.center[2] = z0 + s * domain->zprd;
        vsolid += EllipsoidDep::ellipsoid_slab_volume(e, zlo, zhi);
      }
    }
  }

  // coordination: contacts with any particle (group or not); first pass with every atom
  // active, then peel off rattlers on the whole packing; averages over the group in the slab
  grow();
  for (int i = 0; i < nall; i++) active[i] = 1.0;
  count_contacts(nall);

  double **x = atom->x;
  auto in_slab = [&](int i) {
    return x[i][2] >= zlo && x[i][2] < zhi;
  };

  // sums over the group in the slab, reduced together
  enum { N, SUM_Z, N_ACTIVE, SUM_Z_ACTIVE, SOLID, NSUMS };
  double sums[NSUMS] = {0.0, 0.0, 0.0, 0.0, 0.0};
  for (int i = 0; i < nlocal; i++)
    if ((mask[i] & groupbit) && in_slab(i)) {
      sums[N] += 1.0;
      sums[SUM_Z] += ncontact[i];
    }

  if (rattler_min > 0) {
    while (true) {
      int changed = 0;
      for (int i = 0; i < nlocal; i++)
        if (active[i] != 0.0 && ncontact[i] < rattler_min) {
          active[i] = 0.0;
          changed = 1;
        }
      int changed_all;
      MPI_Allreduce(&changed, &changed_all, 1, MPI_INT, MPI_MAX, world);
      if (!changed_all) break;
      comm->forward_comm(this);
      count_contacts(nall);
    }
  }
  for (int i = 0; i < nlocal; i++)
    if ((mask[i] & groupbit) && active[i] != 0.0 && in_slab(i)) {
      sums[N_ACTIVE] += 1.0;
      sums[SUM_Z_ACTIVE] += ncontact[i];
    }
  sums[SOLID] = vsolid;

  double all[NSUMS];
  MPI_Allreduce(sums, all, NSUMS, MPI_DOUBLE, MPI_SUM, world);

  const double vslab = domain->xprd * domain->yprd * (zhi - zlo);
  vector[PHI] = vslab > 0.0 ? all[SOLID] / vslab : 0.0;
  vector[NSLAB] = all[N];
  vector[Z] = all[N] > 0.0 ? all[SUM_Z] / all[N] : 0.0;
  vector[Z_NORATTLER] = all[N_ACTIVE] > 0.0 ? all[SUM_Z_ACTIVE] / all[N_ACTIVE] : 0.0;
  vector[ZLO] = zlo;
  vector[ZHI] = zhi;
  vector[NRATTLER] = all[N] - all[N_ACTIVE];
  vector[DMEAN] = dmean;
  vector[VSOLID] = all[SOLID];
}

/* ---------------------------------------------------------------------- */

int ComputePackingEllipsoid::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/,
                                               int * /*pbc*/)
{
  for (int k = 0; k < n; k++) buf[k] = active[list[k]];
  return n;
}

void ComputePackingEllipsoid::unpack_forward_comm(int n, int first, double *buf)
{
  for (int k = 0; k < n; k++) active[first + k] = buf[k];
}

int ComputePackingEllipsoid::pack_reverse_comm(int n, int first, double *buf)
{
  for (int k = 0; k < n; k++) buf[k] = ncontact[first + k];
  return n;
}

void ComputePackingEllipsoid::unpack_reverse_comm(int n, int *list, double *buf)
{
  for (int k = 0; k < n; k++) ncontact[list[k]] += buf[k];
}

/* ---------------------------------------------------------------------- */

double ComputePackingEllipsoid::memory_usage()
{
  return 2.0 * nmax * sizeof(double);
}
