/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: the per-pair pipeline (see ellipsoid_pipeline.h).
------------------------------------------------------------------------- */

#include "ellipsoid_pipeline.h"

#include "ellipsoid_pair_history.h"
#include "ellipsoid_wang.h"

namespace EllipsoidDep {

void PipelineCounters::add(const PipelineCounters &o)
{
  for (const CounterField &c : PIPELINE_COUNTERS) this->*c.member += o.*c.member;
}

namespace {
  // The result of a shortcut that decides the pair without the iteration.
  ContactGeometry decided(Status status, const Vec3 &normal = Vec3::Zero(), double overlap = 0.0)
  {
    ContactGeometry g;
    g.status = status;
    g.normal = normal;
    g.overlap = overlap;
    return g;
  }

}    // namespace

ContactGeometry evaluate_pair(const Ellipsoid &a, const Ellipsoid &b,
                              const PipelineSettings &settings, double *cache,
                              PipelineCounters &counters)
{
  const BoundingTest bounds = bounding_test(a, b);
  // the overlap of a bounding reject is minus a lower bound of the distance
  if (reject_apart(bounds, cache, counters))
    return decided(Status::Separated, bounds.dc / bounds.dist, bounds.reach - bounds.dist);
  return evaluate_near_pair(a, b, bounds, settings, cache, counters);
}

ContactGeometry evaluate_near_pair(const Ellipsoid &a, const Ellipsoid &b,
                                   const BoundingTest &bounds, const PipelineSettings &settings,
                                   double *cache, PipelineCounters &counters)
{
  const Vec3 &dc = bounds.dc;
  const double dist = bounds.dist;
  // Each shortcut returns its own result; the iteration's is built in the caller's place (the
  // one named result below, returned on every path after it) instead of copied there.
  // Non-finite input falls through to the validity check.
  ++counters.pairs;
  PairHistory history(cache);
  PairHistory::State state = history.state();
  // a contact row of another pair or image (IDs renumbered, two images of one partner) is
  // not this pair's: it is forgotten and the pair evaluated as new. A plane needs no such
  // check: it is tested, and a plane that separates proves it whatever pair it was made for.
  if (state == PairHistory::State::Contact &&
      !history.belongs_to(dc, PairHistory::identity_tolerance(a, b))) {
    ++counters.foreign_histories;
    history.clear_row(settings.law_slots);
    state = PairHistory::State::Empty;
  }
  Vec3 cached_n;
  const bool have_n = history.usable_normal(cached_n);
  if (state == PairHistory::State::Plane && have_n && settings.use_planes) {
    // any NaN or an infinite n.dc makes the test false, so invalid input cannot hit here
    if (history.plane_separates(a, b, dc)) {
      ++counters.plane_hits;
      return decided(Status::Separated, cached_n);
    }
  }
  // valid(a) && valid(b) without their centre tests: a finite |c_B - c_A| has finite centres
  if (!a.finite || !b.finite || !std::isfinite(dist)) {
    ++counters.degenerate;
    history.clear();
    return decided(Status::Degenerate);
  }
  // A pair in contact at the previous evaluation goes straight to the iteration, warm-started
  // from its own last normal moved on by its last step: the sign of min d(n) decides
  // separation exactly, and the continuing contact keeps its basin. The Wang test screens
  // pairs that newly come close.
  const bool continuing_contact = state == PairHistory::State::Contact && have_n;
  if (continuing_contact) ++counters.continued;
  // two spheres: their closed form decides every pair exactly, without a Wang test or a start
  const bool spheres = a.sphere && b.sphere;
  if (settings.use_wang && !continuing_contact && !spheres) {
    ++counters.wang_calls;
    const Status ws = wang_classify(a, b, settings.contact);
    if (ws == Status::Degenerate) {
      ++counters.degenerate;
      history.clear();
      return decided(Status::Degenerate);
    }
    if (ws == Status::Separated) {
      SeparatingPlane pl;
      if (build_separating_plane(a, b, pl, have_n ? &cached_n : nullptr)) {
        ++counters.wang_separated;
        history.store_plane(pl.normal, pl.offset, a.center, dc);
        return decided(Status::Separated, pl.normal);
      }
      // no plane to round-off: fall through to the exact iteration
    }
  }
  // ellipsoid_contact without its validity checks, made above (two spheres: its closed form)
  const Vec3 start_n = continuing_contact ? history.predicted_normal(cached_n) : cached_n;
  ContactGeometry g = spheres
      ? valid_sphere_contact(a, b, dc, dist)
      : valid_ellipsoid_contact(a, b, settings.contact, have_n ? &start_n : nullptr);
  counters.iterations += g.iterations;
  // a warm start can lie in the basin of a spurious local minimum of d, far deeper than the
  // contact (a start in the wrong hemisphere: about a body's length); a deep warm result is
  // checked against the cold start, and the shallower minimum is the contact (or the gap)
  // (a cold start that reaches the same minimum, equal to round-off, leaves the warm result)
  bool replaced = false;
  if (have_n && !spheres && g.status != Status::Degenerate) {
    const double thinnest = std::min(a.semi_axes.minCoeff(), b.semi_axes.minCoeff());
    if (g.overlap > CHECKED_OVERLAP_FRACTION * thinnest) {
      ContactGeometry cold = valid_ellipsoid_contact(a, b, settings.contact, nullptr);
      counters.iterations += cold.iterations;
      if (cold.status != Status::Degenerate &&
          cold.overlap < g.overlap - SAME_MINIMUM * thinnest) {
        ++counters.spurious_minima;
        g = cold;
        replaced = true;
      }
    }
  }
  if (g.corrected) ++counters.corrections;
  if (g.status == Status::Degenerate) {
    ++counters.degenerate;
    history.clear();
    return g;
  }
  if (g.overlap <= 0.0) {
    // a disjoint pair's minimiser gives a separating plane through the gap midpoint
    history.store_plane(g.normal, g.normal.dot(g.point), a.center, dc);
    g.status = Status::Separated;
    return g;
  }
  ++counters.contacts;
  if (g.status == Status::NotConverged) ++counters.not_converged;
  // only an iterated normal moves the next start on: a fast-mode contact accepted at its
  // (extrapolated) start would otherwise extrapolate its own extrapolation, and turn on
  const bool iterated = continuing_contact && g.corrected && !replaced;
  history.store_contact(g.normal, dc, iterated ? Vec3(g.normal - cached_n) : Vec3::Zero());
  return g;
}

}    // namespace EllipsoidDep
