/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP adapter for LIGGGHTS-PUBLIC 3.8: a plain-double bridge to the engine-independent
   contact kernel (src/kernel of the ELLIPSOID_DEP repository).

   This header has no Eigen and no LIGGGHTS include, so LIGGGHTS's heavy contact-model template
   units do not see Eigen; ellipsoid_dep_bridge.cpp is the only file that includes the kernel.
   No contact geometry here: it packs LIGGGHTS's per-atom arrays into EllipsoidDep::Ellipsoid and
   calls EllipsoidDep::evaluate_pair / gaussian_radius.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_BRIDGE_H
#define ELLIPSOID_DEP_BRIDGE_H

namespace EllipsoidDepLiggghts {

// doubles of the kernel's per-pair history (its pipeline's slots: LIGGGHTS's own models keep
// theirs), checked against EllipsoidDep::PairHistory::PIPELINE_SIZE in the .cpp. Its swap rule
// is LIGGGHTS's history "newtonflag 1" (PairHistory::swapped).
const int HISTORY_SIZE = 10;
// name of history slot k < HISTORY_SIZE (for LIGGGHTS's history registry)
const char *history_slot_name(int k);
// true while the history keeps a separating plane or a contact normal (keep the pair's history)
bool history_in_use(double *history);

// kernel knobs (EllipsoidDep::PipelineSettings)
struct Settings {
  double tolerance = 1e-12;
  int max_iterations = 50;
  double correction_angle = 0.0;
  double wang_band = 1e-9;
  bool use_planes = true;
  bool use_wang = true;
};

struct Contact {
  int status =
      0;    // EllipsoidDep::Status (0 separated, 2 overlapping, 3 not converged, 4 degenerate)
  double normal[3] = {0, 0, 0};     // unit, from body i (A) to body j (B)
  double overlap = 0.0;             // > 0 in contact; -distance (or a lower bound) otherwise
  double point[3] = {0, 0, 0};      // contact point (box frame)
  double effective_radius = 0.0;    // R* = R_i R_j / (R_i + R_j), Gaussian-curvature radii
};

// One pair. x: centre, q: unit quaternion (w, x, y, z) body -> box, shape: semi-axes along the
// body axes (LIGGGHTS's superquadric `shape`). history: HISTORY_SIZE doubles kept per pair.
// Returns true when the bodies overlap (out holds the geometry).
bool pair_contact(const double *xi, const double *qi, const double *shapei, const double *xj,
                  const double *qj, const double *shapej, const Settings &settings,
                  double *history, Contact &out);

// Gaussian-curvature radius sqrt(R1 R2) of the ellipsoid where its outer unit normal is n.
double gaussian_radius(const double *x, const double *q, const double *shape, const double *n);

// Totals over this process of the kernel's counters (EllipsoidDep::PIPELINE_COUNTERS), for
// reporting: counter k < counter_count() has a machine-readable name and a value.
int counter_count();
const char *counter_name(int k);
long long counter_value(int k);

}    // namespace EllipsoidDepLiggghts

#endif
