/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/region/ellipsoid, the region against periodic boundaries

   The walls act on the particle centres in the box, not on their periodic images: a region
   whose walls reach across a periodic boundary would hold a particle on one side of it and
   let it go on the other. Along each periodic dimension the centres the walls can act on
   must lie in the box, or the walls must be the same at every shift along it (a face
   parallel to it, a cylinder along it) and cover the box. Checked where the region is: at
   setup and at every step it moves (see doc/fix_wall_gran_region_ellipsoid.rst).
------------------------------------------------------------------------- */

#include "fix_wall_gran_region_ellipsoid.h"

#include "domain.h"
#include "error.h"
#include "region.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <string>

using namespace LAMMPS_NS;
using namespace EllipsoidDep;

namespace {

// a direction cosine this close to 0 or 1 is one (a rotated region's faces carry round-off)
constexpr double ALIGNED = 1.0e-12;
bool across(double cosine) { return std::fabs(cosine) <= ALIGNED; }
bool along(double cosine) { return std::fabs(std::fabs(cosine) - 1.0) <= ALIGNED; }

// the centres a wall can act on along one dimension, and whether the wall is the same at
// every shift along it
struct Span {
  double lo = -INFINITY, hi = INFINITY;
  bool invariant = true;
  void cut(double a, double b)
  {
    lo = std::max(lo, a);
    hi = std::min(hi, b);
  }
};

// the particles' side of a plane; the inside of a curved face met from inside; a solid met
// from outside grown by the particles' reach
Span wall_span(const WallSurface &w, int d, double reach)
{
  Span s;
  switch (w.shape) {
    case WallShape::Plane:
      if (across(w.normal[d])) return s;
      s.invariant = false;
      if (along(w.normal[d])) {
        // the particle side x_d >= offset (normal +e_d) or x_d <= -offset (normal -e_d)
        if (w.normal[d] > 0.0) s.lo = w.offset;
        else s.hi = -w.offset;
      }
      return s;
    case WallShape::Sphere: {
      const double r = w.radius + (w.inside ? 0.0 : reach);
      s.invariant = false;
      s.cut(w.center[d] - r, w.center[d] + r);
      return s;
    }
    case WallShape::Cylinder: {
      // the caps' ends along the axis (infinite: none), widened by the circle's half-width
      const double u = w.axis[d], grow = w.inside ? 0.0 : reach;
      const double half = w.radius * std::sqrt(std::max(0.0, 1.0 - u * u)) + grow;
      s.invariant = along(u) && std::isinf(w.cap_lo) && std::isinf(w.cap_hi);
      if (s.invariant) return s;
      if (across(u)) {
        s.cut(w.center[d] - half, w.center[d] + half);
        return s;
      }
      const double a = w.center[d] + w.cap_lo * u, b = w.center[d] + w.cap_hi * u;
      s.cut(std::min(a, b) - half - grow, std::max(a, b) + half + grow);
      return s;
    }
    case WallShape::Cone:
      s.invariant = false;    // the region's bounding box bounds its side
      return s;
    case WallShape::Box: {
      double lo = w.center[d] - reach, hi = w.center[d] + reach;
      for (int k = 0; k < 3; k++) {
        const double f = w.frame(d, k);
        if (across(f)) continue;
        if (along(f) && std::isinf(w.lower[k]) && std::isinf(w.upper[k])) return s;
        lo += std::min(f * w.lower[k], f * w.upper[k]);
        hi += std::max(f * w.lower[k], f * w.upper[k]);
      }
      s.invariant = false;
      s.cut(lo, hi);
      return s;
    }
  }
  return s;
}

}    // namespace

void FixWallGranRegionEllipsoid::check_periodic_crossing()
{
  for (int d = 0; d < 3; d++) {
    if (!domain->periodicity[d]) continue;
    Span span;
    for (const WallSurface &w : walls) {
      const Span s = wall_span(w, d, reach);
      span.cut(s.lo, s.hi);
      span.invariant = span.invariant && s.invariant;
    }
    // a region met from inside is bounded by its open faces too: LAMMPS's bounding box of
    // the region where it is now (a sphere's ignores rotate; its face is exact)
    if (region->interior && region->bboxflag && std::string(region->style) != "sphere") {
      const double extent[3][2] = {{region->extent_xlo, region->extent_xhi},
                                   {region->extent_ylo, region->extent_yhi},
                                   {region->extent_zlo, region->extent_zhi}};
      span.cut(extent[d][0], extent[d][1]);
    }
    const double boxlo = domain->boxlo[d], boxhi = domain->boxhi[d];
    const bool within = span.lo >= boxlo && span.hi <= boxhi;
    const bool covers = span.invariant && span.lo <= boxlo && span.hi >= boxhi;
    if (within || covers) continue;
    std::string radius;
    for (const WallSurface &w : walls)
      if (w.shape == WallShape::Sphere || w.shape == WallShape::Cylinder)
        radius = fmt::format(" (radius {})", w.radius);
    error->all(FLERR,
               "Fix wall/gran/region/ellipsoid: region {}'s {}{} crosses the periodic boundary "
               "in {} at step {}: its walls act on particle centres from {} to {} along {}, "
               "the box is {} to {}; a wall across a periodic boundary would hold one image of "
               "a particle and not the other",
               region_id, region->style, radius, "xyz"[d], update->ntimestep, span.lo, span.hi,
               "xyz"[d], boxlo, boxhi);
  }
}
