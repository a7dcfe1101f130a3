/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: the per-pair pipeline of the paper (Fig. 2) for callers that keep a
   small per-pair history between steps (PairHistory): bounding spheres -> cached separating
   plane -> Wang test (disjoint: build and cache a plane) -> contact iteration warm-started
   from the cached normal extrapolated by its last step -> normal correction. Its settings
   and the counters of what it did.

   Conventions
   - A is the first body, B the second; the history belongs to the ordered pair (A, B) (see
     ellipsoid_pair_history.h for the layout and the swap rule).
   - Every evaluation ends in exactly one of: bounding reject, plane hit, Wang test (or the
     iteration directly when use_wang is off, the closed form directly for two spheres),
     continued contact.
   - A contact history is used only by the pair and periodic image it was made for
     (PairHistory::belongs_to); another pair's row is cleared, the force law's slots
     included, and counted (foreign_histories): the pair is then evaluated as new.
   - A warm-started result deeper than CHECKED_OVERLAP_FRACTION of the smaller smallest
     semi-axis is evaluated again from the cold start; the shallower of the two minima of d
     is the result (the replacement counted, spurious_minima).

   Degenerate cases
   - Invalid bodies or a non-finite centre distance: Degenerate, counted, history cleared.
     Non-finite input never hits the bounding or the plane shortcut (NaN compares false).
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_PIPELINE_H
#define ELLIPSOID_DEP_ELLIPSOID_PIPELINE_H

#include "ellipsoid_contact.h"
#include "ellipsoid_pair_history.h"

namespace EllipsoidDep {

struct PipelineSettings {
  ContactSettings contact;
  bool use_planes = true;    // cache separating planes of disjoint pairs
  bool use_wang = true;      // false: go straight to the contact iteration
  int law_slots = 0;         // the force law's slots after the pipeline's in each history row
                             // (PairHistory::LAW; cleared with a foreign row)
};

// A warm-started result deeper than this fraction of the smaller body's smallest semi-axis
// (far beyond any overlap a force law resolves) is checked against a cold start: a warm start
// can reach a spurious local minimum of d, which would make a false contact (of a disjoint
// pair) or a far too deep one
inline constexpr double CHECKED_OVERLAP_FRACTION = 0.5;
// two minima of d closer than this fraction of the thinner semi-axis are the same one (the
// iteration meets its tolerance far below it; a spurious minimum is about a body's length off)
inline constexpr double SAME_MINIMUM = 1e-9;

struct PipelineCounters {
  long long pairs = 0;               // pairs evaluated
  long long plane_hits = 0;          // cached plane still separates
  long long wang_calls = 0;          // Wang tests
  long long contacts = 0;            // overlapping results
  long long iterations = 0;          // summed over contact evaluations
  long long corrections = 0;         // normal-correcting step applied
  long long not_converged = 0;       // iteration cap reached (contact still used, flagged)
  long long bounding_rejects = 0;    // bounding spheres disjoint
  long long degenerate = 0;          // input that could not be handled
  long long continued = 0;           // contacts of the previous step re-evaluated without Wang
  long long wang_separated = 0;      // Wang said disjoint and a plane was built
  long long foreign_histories = 0;   // contact histories made for another pair or image
  long long spurious_minima = 0;     // deep warm-started results a cold start beat
  void add(const PipelineCounters &o);
};

// The counters by name, in their one order: every consumer (summation, the LAMMPS pair's
// vector, its end-of-run report, the LIGGGHTS bridge) iterates over this table.
struct CounterField {
  const char *name;     // machine-readable key
  const char *label;    // human-readable, follows the value in reports
  long long PipelineCounters::*member;
};
inline constexpr CounterField PIPELINE_COUNTERS[] = {
    {"pairs", "pairs tested", &PipelineCounters::pairs},
    {"plane_hits", "plane hits", &PipelineCounters::plane_hits},
    {"wang_calls", "Wang tests", &PipelineCounters::wang_calls},
    {"contacts", "contacts", &PipelineCounters::contacts},
    {"iterations", "iterations", &PipelineCounters::iterations},
    {"corrections", "corrections", &PipelineCounters::corrections},
    {"not_converged", "not converged", &PipelineCounters::not_converged},
    {"bounding_rejects", "bounding rejects", &PipelineCounters::bounding_rejects},
    {"degenerate", "degenerate", &PipelineCounters::degenerate},
    {"continued", "continued contacts", &PipelineCounters::continued},
    {"wang_separated", "Wang separations", &PipelineCounters::wang_separated},
    {"foreign_histories", "foreign histories", &PipelineCounters::foreign_histories},
    {"spurious_minima", "spurious minima", &PipelineCounters::spurious_minima},
};
inline constexpr int NUM_PIPELINE_COUNTERS =
    static_cast<int>(sizeof(PIPELINE_COUNTERS) / sizeof(PIPELINE_COUNTERS[0]));

// Position of a counter in PIPELINE_COUNTERS, and so in every array in that order.
constexpr int counter_index(long long PipelineCounters::*member)
{
  for (int k = 0; k < NUM_PIPELINE_COUNTERS; ++k)
    if (PIPELINE_COUNTERS[k].member == member) return k;
  return -1;
}

// The bounding-sphere test that opens every evaluation: dc = c_B - c_A, its length, the sum of
// the bounding radii. NaN compares false: non-finite input is never apart.
struct BoundingTest {
  Vec3 dc;
  double dist, reach;
  bool apart;
};
// The centres and bounding radii alone, for callers that have not built the bodies.
inline BoundingTest bounding_test(const Vec3 &center_a, double radius_a, const Vec3 &center_b,
                                  double radius_b)
{
  BoundingTest t;
  // in scalars: Eigen's norm() of a 3-vector packs and shuffles twice the instructions for
  // the same sum, (x^2 + y^2) + z^2, on the path of every candidate pair
  const double dx = center_b[0] - center_a[0], dy = center_b[1] - center_a[1],
               dz = center_b[2] - center_a[2];
  t.dc = Vec3(dx, dy, dz);
  t.dist = std::sqrt(dx * dx + dy * dy + dz * dz);
  t.reach = radius_a + radius_b;
  t.apart = t.dist > t.reach && std::isfinite(t.dist) && std::isfinite(t.reach);
  return t;
}
inline BoundingTest bounding_test(const Ellipsoid &a, const Ellipsoid &b)
{
  return bounding_test(a.center, a.bounding_radius, b.center, b.bounding_radius);
}

// What an evaluation does with a pair whose bounding spheres are apart (history cleared,
// counted), for callers that test first and skip the call; true when the pair was apart.
inline bool reject_apart(const BoundingTest &t, double *cache, PipelineCounters &counters)
{
  if (!t.apart) return false;
  ++counters.pairs;
  ++counters.bounding_rejects;
  PairHistory(cache).forget();
  return true;
}

// Evaluates one pair; updates its history (the PairHistory::PIPELINE_SIZE doubles of the
// pipeline; the law's only when the row is another pair's) and the counters.
// Returns Overlapping (or NotConverged, still with usable geometry) when there is a contact,
// else Separated (or Degenerate).
ContactGeometry evaluate_pair(const Ellipsoid &a, const Ellipsoid &b,
                              const PipelineSettings &settings, double *cache,
                              PipelineCounters &counters);
// evaluate_pair after its opening, for a caller that made the bounding test (bounds, of a and
// b) and found the pair not apart (reject_apart false), so that the test runs once per pair
ContactGeometry evaluate_near_pair(const Ellipsoid &a, const Ellipsoid &b,
                                   const BoundingTest &bounds, const PipelineSettings &settings,
                                   double *cache, PipelineCounters &counters);

// A result of evaluate_pair that forces act on: Overlapping, or NotConverged (usable geometry).
inline bool in_contact(const ContactGeometry &g)
{
  return g.status == Status::Overlapping || g.status == Status::NotConverged;
}

}    // namespace EllipsoidDep

#endif
