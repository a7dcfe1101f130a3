/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix pour/ellipsoid, the command's arguments, its region and the walls a new
   particle must be clear of (see fix_pour_ellipsoid.h)
------------------------------------------------------------------------- */

#include "fix_pour_ellipsoid.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "fix_wall_gran_ellipsoid.h"
#include "math_const.h"
#include "modify.h"
#include "region.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using EllipsoidDep::Ellipsoid;
using EllipsoidDep::WallSurface;
using MathConst::MY_4PI3;

/* ----------------------------------------------------------------------
   N type seed and the keywords; arg is the whole fix command (errors point at the bad
   word)
------------------------------------------------------------------------- */

void FixPourEllipsoid::options(int narg, char **arg)
{
  distribution = EllipsoidDep::PourDistribution();
  double &rmin = distribution.rmin, &rmax = distribution.rmax;
  double &alpha = distribution.alpha, &beta = distribution.beta;
  double &eta = distribution.eta, &zeta = distribution.zeta;
  double &delta_eta = distribution.delta_eta, &delta_zeta = distribution.delta_zeta;
  density = 1.0;
  volfrac = 0.25;
  maxattempt = 50;
  rate = 0.0;
  vxlo = vxhi = vylo = vyhi = vz = 0.0;
  every = 0;
  cloud = false;

  auto number = [&](int i, const std::string &what) {
    if (i >= narg) utils::missing_cmd_args(FLERR, "fix pour/ellipsoid " + what, error);
    if (!utils::is_double(arg[i]))
      error->all(FLERR, i, "Fix pour/ellipsoid {}: expected a number, got '{}'", what, arg[i]);
    return utils::numeric(FLERR, arg[i], false, lmp);
  };
  auto integer = [&](int i, const std::string &what) {
    if (i >= narg) utils::missing_cmd_args(FLERR, "fix pour/ellipsoid " + what, error);
    if (!utils::is_integer(arg[i]))
      error->all(FLERR, i, "Fix pour/ellipsoid {}: expected an integer, got '{}'", what, arg[i]);
    return utils::inumeric(FLERR, arg[i], false, lmp);
  };
  auto positive = [&](int i, const std::string &what) {
    const double value = number(i, what);
    if (!(value > 0.0))
      error->all(FLERR, i, "Fix pour/ellipsoid {} must be > 0, got {}", what, value);
    return value;
  };

  ninsert = integer(3, "N");
  ntype = integer(4, "type");
  seed = integer(5, "seed");
  if (ninsert <= 0) error->all(FLERR, 3, "Fix pour/ellipsoid N must be > 0, got {}", ninsert);
  if (ntype <= 0 || ntype > atom->ntypes)
    error->all(FLERR, 4, "Fix pour/ellipsoid atom type {} is not in 1..{}", ntype, atom->ntypes);
  if (seed <= 0) error->all(FLERR, 5, "Fix pour/ellipsoid seed must be > 0, got {}", seed);

  int iarg = 6;
  while (iarg < narg) {
    const std::string word = arg[iarg];
    if (word == "region") {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix pour/ellipsoid region", error);
      region = domain->get_region_by_id(arg[iarg + 1]);
      if (!region)
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid region {} does not exist", arg[iarg + 1]);
      delete[] idregion;
      idregion = utils::strdup(arg[iarg + 1]);
      iarg += 2;
    } else if (word == "size") {
      if (iarg + 3 > narg) utils::missing_cmd_args(FLERR, "fix pour/ellipsoid size", error);
      if (strcmp(arg[iarg + 1], "mean") == 0) {
        // size mean R delta_r D
        if (iarg + 5 > narg)
          utils::missing_cmd_args(FLERR, "fix pour/ellipsoid size mean R delta_r D", error);
        const double mean = positive(iarg + 2, "size mean R");
        if (strcmp(arg[iarg + 3], "delta_r") != 0)
          error->all(FLERR, iarg + 3,
                     "Fix pour/ellipsoid size mean R: expected 'delta_r', got "
                     "'{}'",
                     arg[iarg + 3]);
        const double delta = number(iarg + 4, "size delta_r");
        if (!(delta >= 0.0 && delta < 1.0))
          error->all(FLERR, iarg + 4, "Fix pour/ellipsoid delta_r must be in [0, 1), got {}",
                     delta);
        rmin = mean * (1.0 - delta);
        rmax = mean * (1.0 + delta);
        iarg += 5;
      } else {
        rmin = positive(iarg + 1, "size rmin");
        rmax = positive(iarg + 2, "size rmax");
        if (rmin > rmax)
          error->all(FLERR, iarg + 1, "Fix pour/ellipsoid size rmin {} exceeds rmax {}", rmin,
                     rmax);
        iarg += 3;
      }
    } else if (word == "alpha") {
      alpha = positive(iarg + 1, "alpha");
      iarg += 2;
    } else if (word == "beta") {
      beta = positive(iarg + 1, "beta");
      iarg += 2;
    } else if (word == "shape") {
      eta = number(iarg + 1, "shape eta");
      zeta = number(iarg + 2, "shape zeta");
      if (!(eta >= 1.0))
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid shape eta = a/b must be >= 1, got {}", eta);
      if (!(zeta >= 1.0))
        error->all(FLERR, iarg + 2, "Fix pour/ellipsoid shape zeta = b/c must be >= 1, got {}",
                   zeta);
      iarg += 3;
    } else if (word == "dshape") {
      delta_eta = number(iarg + 1, "dshape delta_eta");
      delta_zeta = number(iarg + 2, "dshape delta_zeta");
      if (!(delta_eta >= 0.0 && delta_eta < 1.0))
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid delta_eta must be in [0, 1), got {}",
                   delta_eta);
      if (!(delta_zeta >= 0.0 && delta_zeta < 1.0))
        error->all(FLERR, iarg + 2, "Fix pour/ellipsoid delta_zeta must be in [0, 1), got {}",
                   delta_zeta);
      iarg += 3;
    } else if (word == "density") {
      density = positive(iarg + 1, "density");
      iarg += 2;
    } else if (word == "vol") {
      volfrac = number(iarg + 1, "vol fraction");
      maxattempt = integer(iarg + 2, "vol maxattempt");
      if (!(volfrac > 0.0 && volfrac <= 1.0))
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid vol fraction must be in (0, 1], got {}",
                   volfrac);
      if (maxattempt <= 0)
        error->all(FLERR, iarg + 2, "Fix pour/ellipsoid vol maxattempt must be > 0, got {}",
                   maxattempt);
      iarg += 3;
    } else if (word == "rate") {
      rate = number(iarg + 1, "rate");
      iarg += 2;
    } else if (word == "vel") {
      vxlo = number(iarg + 1, "vel vxlo");
      vxhi = number(iarg + 2, "vel vxhi");
      vylo = number(iarg + 3, "vel vylo");
      vyhi = number(iarg + 4, "vel vyhi");
      vz = number(iarg + 5, "vel vz");
      if (vxlo > vxhi)
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid vel vxlo {} exceeds vxhi {}", vxlo, vxhi);
      if (vylo > vyhi)
        error->all(FLERR, iarg + 3, "Fix pour/ellipsoid vel vylo {} exceeds vyhi {}", vylo, vyhi);
      iarg += 6;
    } else if (word == "release") {
      if (iarg + 1 >= narg) utils::missing_cmd_args(FLERR, "fix pour/ellipsoid release", error);
      const std::string how = arg[iarg + 1];
      if (how != "stream" && how != "cloud")
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid release must be stream or cloud, got {}",
                   how);
      cloud = how == "cloud";
      iarg += 2;
    } else if (word == "every") {
      every = integer(iarg + 1, "every");
      if (every <= 0)
        error->all(FLERR, iarg + 1, "Fix pour/ellipsoid every must be > 0, got {}", every);
      iarg += 2;
    } else {
      error->all(FLERR, iarg, "Unknown fix pour/ellipsoid keyword '{}'", word);
    }
  }

  const double eta_lo = eta * (1.0 - delta_eta), zeta_lo = zeta * (1.0 - delta_zeta);
  if (eta_lo < 1.0 - 1e-12)
    error->all(FLERR,
               "Fix pour/ellipsoid: eta (1 - delta_eta) = {} < 1 (a must stay the "
               "longest axis)",
               eta_lo);
  if (zeta_lo < 1.0 - 1e-12)
    error->all(FLERR,
               "Fix pour/ellipsoid: zeta (1 - delta_zeta) = {} < 1 (c must stay the "
               "shortest axis)",
               zeta_lo);
}

/* ----------------------------------------------------------------------
   the region: a block or a z-axis cylinder, static, side in, inside the box (when the fix is
   defined: a box shrunk later, as the default deposit's picture does, is no error)
------------------------------------------------------------------------- */

void FixPourEllipsoid::check_region()
{
  if (!region) error->all(FLERR, "Fix pour/ellipsoid requires the keyword 'region ID'");
  read_region();
  if (xlo < domain->boxlo[0] || xhi > domain->boxhi[0] || ylo < domain->boxlo[1] ||
      yhi > domain->boxhi[1] || zlo < domain->boxlo[2] || zhi > domain->boxhi[2])
    error->all(FLERR, "Fix pour/ellipsoid region {} extends outside the simulation box", idregion);
  if (!(xhi > xlo && yhi > ylo && zhi > zlo))
    error->all(FLERR, "Fix pour/ellipsoid region {} is empty", idregion);
}

// the region's style and extent, and its lateral sides as kernel wall surfaces (whole
// particles stay within them)
void FixPourEllipsoid::read_region()
{
  if (region->bboxflag == 0)
    error->all(FLERR, "Fix pour/ellipsoid region {} does not support a bounding box", idregion);
  if (region->dynamic_check())
    error->all(FLERR, "Fix pour/ellipsoid region {} cannot be dynamic", idregion);
  if (region->interior == 0)
    error->all(FLERR, "Fix pour/ellipsoid region {} must be an interior region (side in)",
               idregion);
  const double ex[2] = {region->extent_xlo, region->extent_xhi};
  const double ey[2] = {region->extent_ylo, region->extent_yhi};
  const double ez[2] = {region->extent_zlo, region->extent_zhi};
  if (strcmp(region->style, "block") == 0) {
    region_style = 1;
  } else if (strcmp(region->style, "cylinder") == 0) {
    region_style = 2;
    // a z-axis cylinder has a disk as xy section: the corner of its bounding square is
    // outside, the middle of its bounding square's edge (at any z) is inside
    const double f = 1.0e-3;
    const double dxr = f * (ex[1] - ex[0]), dyr = f * (ey[1] - ey[0]), dzr = f * (ez[1] - ez[0]);
    const double zmid = 0.5 * (ez[0] + ez[1]), ymid = 0.5 * (ey[0] + ey[1]);
    const bool corner_in = region->match(ex[0] + 10 * dxr, ey[0] + 10 * dyr, zmid) != 0;
    const bool edge_in = region->match(ex[0] + dxr, ymid, ez[0] + dzr) != 0;
    if (corner_in || !edge_in)
      error->all(FLERR, "Fix pour/ellipsoid region {} must be a z-axis cylinder", idregion);
  } else {
    error->all(FLERR, "Fix pour/ellipsoid region {} must be a block or a cylinder (style {})",
               idregion, region->style);
  }
  xlo = ex[0];
  xhi = ex[1];
  ylo = ey[0];
  yhi = ey[1];
  zlo = ez[0];
  zhi = ez[1];
  xc = 0.5 * (xlo + xhi);
  yc = 0.5 * (ylo + yhi);
  rc = 0.5 * (xhi - xlo);

  region_sides.clear();
  if (region_style == 2) {
    WallSurface side;
    side.shape = EllipsoidDep::WallShape::Cylinder;
    side.center = EllipsoidDep::Vec3(xc, yc, 0.0);
    side.radius = rc;
    region_sides.push_back(side);
    return;
  }
  // a block that spans a periodic box in x or y has no side there: particles cross the
  // periodic boundary
  const double lo[2] = {xlo, ylo}, hi[2] = {xhi, yhi};
  for (int d = 0; d < 2; d++) {
    if (domain->periodicity[d] && lo[d] <= domain->boxlo[d] && hi[d] >= domain->boxhi[d]) continue;
    WallSurface face;    // the particle side: lo <= x_d <= hi
    face.normal = EllipsoidDep::Vec3::Unit(d);
    face.offset = lo[d];
    region_sides.push_back(face);
    face.normal = -EllipsoidDep::Vec3::Unit(d);
    face.offset = -hi[d];
    region_sides.push_back(face);
  }
}

// the region as the pour uses it: style (1 block, 2 cylinder) and extent
std::vector<double> FixPourEllipsoid::region_values() const
{
  return {double(region_style), xlo, xhi, ylo, yhi, zlo, zhi};
}

/* ----------------------------------------------------------------------
   at every run start, the region found by its ID again: one deleted and defined again with
   another style or extent would be poured into with the old one's numbers and schedule
------------------------------------------------------------------------- */

void FixPourEllipsoid::recheck_region()
{
  region = domain->get_region_by_id(idregion);
  if (!region) error->all(FLERR, "Fix pour/ellipsoid region {} does not exist", idregion);
  const std::vector<double> before = region_values();
  read_region();
  const std::vector<double> now = region_values();
  if (now == before) return;
  error->all(FLERR,
             "Fix pour/ellipsoid {}: region {} changed since the fix was defined (was {}, now "
             "{}: style and extent); define the pour again with a new fix ID",
             id, idregion, argument_words("region", before), argument_words("region", now));
}

/* ----------------------------------------------------------------------
   masses and principal moments must be normal, finite numbers: sizes so small (or so
   large) that rho 4/3 pi r^3 or m c^2 under- or overflows would give zero or infinite
   masses and NaN velocities under fix nve/asphere
------------------------------------------------------------------------- */

void FixPourEllipsoid::check_representable() const
{
  const double rmin = distribution.rmin, rmax = distribution.rmax;
  const double c_min = sampler->smallest_semi_axis();
  const double mass_min = lightest_mass();
  const double mass_max = density * MY_4PI3 * rmax * rmax * rmax;
  if (!std::isnormal(mass_min) || !std::isnormal(mass_min * c_min * c_min) ||
      !std::isnormal(sampler->mean_volume()) ||
      !std::isfinite(mass_max * bounding_max * bounding_max))
    error->all(FLERR,
               "Fix pour/ellipsoid size and density give masses or moments of inertia "
               "that are not representable (rmin {} rmax {} density {}); use other units",
               rmin, rmax, density);
}

/* ----------------------------------------------------------------------
   the walls a new particle must be clear of: the region's sides and the walls acting on it
------------------------------------------------------------------------- */

// the walls acting on the poured particles (their mask: all and this group), of both wall
// styles (by type: LAMMPS's style patterns have no groups, so "(region/)?" matches nothing)
void FixPourEllipsoid::find_walls()
{
  walls.clear();
  for (auto *fix : modify->get_fix_list()) {
    const auto *wall = dynamic_cast<const FixWallGranEllipsoid *>(fix);
    if (wall && (fix->groupbit & (1 | groupbit))) walls.push_back(wall);
  }
}

// does the whole particle lie within the region's lateral sides? (its bounding sphere lies
// within the region's z range by its height)
bool FixPourEllipsoid::inside_region(const Ellipsoid &cand) const
{
  for (const WallSurface &side : region_sides)
    if (!wall_clear(cand, side)) return false;
  return true;
}

// the first wall acting on the poured particles that the candidate touches or lies beyond,
// where the last step placed it (moving walls move on by one step's travel at most before
// they act); null when it is clear of all
const FixWallGranEllipsoid *FixPourEllipsoid::touched_wall(const Ellipsoid &cand) const
{
  for (const FixWallGranEllipsoid *wall : walls)
    for (const WallSurface &w : wall->surfaces())
      if (!wall_clear(cand, w)) return wall;
  return nullptr;
}
