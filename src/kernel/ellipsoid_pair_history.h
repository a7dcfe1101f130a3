/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP kernel: the per-pair history of a pair of bodies A, B, as named slots over
   the doubles an engine keeps per neighbour pair (LAMMPS fix NEIGH_HISTORY, LIGGGHTS contact
   history). The only place that knows the layout.

   Layout (PairHistory::size(law size) doubles: the pipeline's geometry, then the force law's)
     STATE          0     0 nothing, +-1 separating plane, +-2 contact normal (read with fabs)
     NORMAL         1-3   unit normal from A to B: the plane normal or the last contact normal
     PLANE_U        4     plane state: the plane passes through c_A + (1/2 + u)(c_B - c_A)
     NORMAL_STEP    4-6   contact state: the last change of the contact normal, n_k - n_(k-1)
                          (zero at the first evaluation of a contact); the next iteration
                          starts from n_k + (n_k - n_(k-1)), which is one order closer to
                          n_(k+1) than n_k for a smooth motion, and needs fewer iterations
     SEPARATION     7-9   contact state: c_B - c_A at the contact's last evaluation, the
                          pair's fingerprint. An engine keys the history by the partner's ID,
                          so a row can reach another pair (IDs renumbered) or another periodic
                          image of the same partner (a box narrower than the reach); a contact
                          whose centres moved more than belongs_to()'s tolerance since is
                          not this pair's
     LAW            10-   the force law's history, ForceLaw::history_size() doubles: the
                          named slots its models declare (tangential_history.h: the
                          tangential displacement s, 10-12); none for laws without history
   evaluate_pair reads and writes slots 0-9 (PIPELINE_SIZE); the force law owns the rest,
   which evaluate_pair only clears, with the pipeline's, when a row is not the pair's. Slot 4
   belongs to the plane or to the contact, as the state says. An engine keeps rows of one size
   for all pairs, size(the largest history of its laws); a pair of a law that keeps less
   leaves the rest of its law slots at zero. A row holds non-zero values only while in use:
   every change of the state to empty clears the pipeline's slots, and the law's hold values
   only after a contact (an engine clears them when its pair leaves contact), so forgetting
   a row not in use writes nothing (forget()).

   The i/j swap rule, for every slot of the pipeline and of the laws: its value changes sign
   when A and B are swapped (the state by convention, n -> -n, u -> -u, step -> -step,
   dc -> -dc; a law's slots are declared so, e.g. s -> -s), so the swapped pair's history is
   the negated copy (swapped()). That is the default transfer of LAMMPS's fix NEIGH_HISTORY
   and LIGGGHTS's "newtonflag 1" history values, so neither engine needs a custom transfer.
   Storing the plane relative to the two centres (u, not an absolute offset) also makes it
   independent of periodic images and of which rank holds which copy.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_PAIR_HISTORY_H
#define ELLIPSOID_DEP_ELLIPSOID_PAIR_HISTORY_H

#include "ellipsoid_wang.h"

#include <algorithm>
#include <limits>

namespace EllipsoidDep {

class PairHistory {
 public:
  static constexpr int STATE = 0, NORMAL = 1, PLANE_U = 4, NORMAL_STEP = 4, SEPARATION = 7;
  static constexpr int PIPELINE_SIZE = 10;    // slots evaluate_pair uses
  static constexpr int LAW = PIPELINE_SIZE;   // the first of the force law's slots
  static constexpr int LAYOUT_VERSION = 3;    // changes with the layout (restart files)
  // doubles per pair for laws that keep law_size doubles each
  static constexpr int size(int law_size) { return PIPELINE_SIZE + law_size; }

  // the state slot holds +-code (the sign follows the pair order)
  enum class State : int { Empty = 0, Plane = 1, Contact = 2 };

  explicit PairHistory(double *values) : v(values) {}

  // The history of the pair seen with A and B swapped (n doubles).
  static void swapped(const double *values, double *out, int n)
  {
    for (int k = 0; k < n; ++k) out[k] = -values[k];
  }

  State state() const
  {
    const int code = static_cast<int>(std::fabs(v[STATE]) + 0.5);
    if (code == static_cast<int>(State::Plane)) return State::Plane;
    if (code == static_cast<int>(State::Contact)) return State::Contact;
    return State::Empty;
  }
  // true while the cache keeps a plane or a normal (engines keep such pairs' history)
  bool in_use() const { return v[STATE] != 0.0; }
  Vec3 normal() const { return Vec3(v[NORMAL], v[NORMAL + 1], v[NORMAL + 2]); }
  // the cached normal when there is one and it is plausibly unit, 1/2 < |n| < 2 (false
  // otherwise); one test of |n|^2, which any NaN or infinite component fails
  bool usable_normal(Vec3 &n) const
  {
    n = normal();
    const double n2 = n.squaredNorm();
    return state() != State::Empty && n2 > 0.25 && n2 < 4.0;
  }
  // the cached plane in absolute terms {n.x = offset}, for the current centre c_A and
  // dc = c_B - c_A (the pipeline tests it with plane_separates() below; the tests check that
  // both agree with the Wang test's plane_separates())
  SeparatingPlane plane(const Vec3 &ca, const Vec3 &dc) const
  {
    SeparatingPlane pl;
    pl.normal = normal();
    pl.offset = pl.normal.dot(ca + (0.5 + v[PLANE_U]) * dc);
    return pl;
  }

  // plane_separates() for the cached plane (normal n), in the centres' own terms: with
  // nd = n.dc it holds A below when h_A(n) < (1/2 + u) nd and B above when h_B(-n) < (1/2 - u) nd;
  // no absolute offset is formed. Any NaN or an infinite n.dc (a centre at infinity, which
  // would pass both comparisons) makes it false.
  bool plane_separates(const Ellipsoid &a, const Ellipsoid &b, const Vec3 &dc) const
  {
    const Vec3 n = normal();
    const double nd = n.dot(dc), u = v[PLANE_U];
    return std::isfinite(nd) && std::sqrt(n.dot(a.inverse_form * n)) < (0.5 + u) * nd &&
        std::sqrt(n.dot(b.inverse_form * n)) < (0.5 - u) * nd;
  }

  // the plane {n.x = offset} as (n, u); a plane that does not cross the centre line (n.dc <= 0)
  // cannot be stored and clears the cache
  void store_plane(const Vec3 &n, double offset, const Vec3 &ca, const Vec3 &dc)
  {
    const double nd = n.dot(dc);
    if (!(nd > 0.0)) {
      clear();
      return;
    }
    set_plane(n, (offset - n.dot(ca)) / nd - 0.5);
  }
  // a contact normal, its change since the previous evaluation (zero for a new contact) and
  // the centres' separation dc = c_B - c_A it was found at
  void store_contact(const Vec3 &n, const Vec3 &dc, const Vec3 &step = Vec3::Zero())
  {
    v[STATE] = static_cast<double>(static_cast<int>(State::Contact));
    for (int k = 0; k < 3; ++k) {
      v[NORMAL + k] = n[k];
      v[NORMAL_STEP + k] = step[k];
      v[SEPARATION + k] = dc[k];
    }
  }
  // true when the stored contact was found for centres separated by dc to within tolerance:
  // the same pair and periodic image one evaluation later (any NaN makes it false)
  bool belongs_to(const Vec3 &dc, double tolerance) const
  {
    const Vec3 stored(v[SEPARATION], v[SEPARATION + 1], v[SEPARATION + 2]);
    return (dc - stored).squaredNorm() <= tolerance * tolerance;
  }
  // belongs_to()'s tolerance for bodies a and b: half the smallest semi-axis of either. A
  // contact's centres move far less between two evaluations (its overlap changes by less);
  // two images of one partner are a box length apart, at least twice a semi-axis of the
  // partner, and two other atoms' centres are further apart than a semi-axis unless they
  // overlap by more than that
  static double identity_tolerance(const Ellipsoid &a, const Ellipsoid &b)
  {
    return 0.5 * std::min(a.semi_axes.minCoeff(), b.semi_axes.minCoeff());
  }
  // where the next iteration of a continuing contact starts (not normalised): the stored
  // normal moved on by its last step, unless the step is not that of a smooth motion
  // (longer than MAX_PREDICTED_STEP, or not finite); n is usable_normal()'s
  Vec3 predicted_normal(const Vec3 &n) const
  {
    const Vec3 step(v[NORMAL_STEP], v[NORMAL_STEP + 1], v[NORMAL_STEP + 2]);
    return step.squaredNorm() < MAX_PREDICTED_STEP * MAX_PREDICTED_STEP ? Vec3(n + step) : n;
  }
  static constexpr double MAX_PREDICTED_STEP = 0.05;    // radians per evaluation
  // forget the plane or normal (the law's slots are the force law's)
  void clear()
  {
    for (int k = 0; k < PIPELINE_SIZE; ++k) v[k] = 0.0;
  }
  // clear() for a row that may be empty, which holds zeros already (of either sign after
  // swapped(); an empty row's slots are not read): the bounding rejects, most evaluations of
  // a dilute scene, leave their rows unwritten
  void forget()
  {
    if (in_use()) clear();
  }
  // forget everything: a row made for another pair or image, with law_size slots of the law
  void clear_row(int law_size)
  {
    clear();
    clear_law(law_size);
  }

  // the force law's history (ForceLaw::compute's history)
  double *law() { return v + LAW; }
  // law_size <= MOST slots: a bound the caller knows at compile time (ForceLaw::
  // MAX_HISTORY_SIZE) makes this a few stores instead of a call to memset in a pair loop
  template <int MOST = std::numeric_limits<int>::max()> void clear_law(int law_size)
  {
    for (int k = 0; k < law_size && k < MOST; ++k) v[LAW + k] = 0.0;
  }

 private:
  double *v;

  void set_plane(const Vec3 &n, double u)
  {
    v[STATE] = static_cast<double>(static_cast<int>(State::Plane));
    v[NORMAL] = n[0];
    v[NORMAL + 1] = n[1];
    v[NORMAL + 2] = n[2];
    v[PLANE_U] = u;
    // the rest of the contact's step and its separation
    v[NORMAL_STEP + 1] = v[NORMAL_STEP + 2] = 0.0;
    v[SEPARATION] = v[SEPARATION + 1] = v[SEPARATION + 2] = 0.0;
  }
};

}    // namespace EllipsoidDep

#endif
