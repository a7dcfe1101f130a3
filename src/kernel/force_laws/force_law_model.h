/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws: what a sub-model declares, in its own file (normal_*.h,
   tangential_*.h, rolling_*.h), and the types its force sees. force_law_registry.h lists the
   models; ellipsoid_force_law.h composes one model of each family into a law.

   Every model is a struct with
     NAME          its word in pair_coeff, after the family's keyword ("history")
     ROWS          its parameters (ParameterRow), in the order pair_coeff reads them and the
                   restart record stores them
     HISTORY_SIZE  doubles of per-contact history it keeps (named slots in its header), each
                   of which changes sign when i and j swap (ellipsoid_pair_history.h)
   and the equation of its force as a comment. What each family's models answer:
     normal      normal_force(R*, xi, sqrt(xi), dxi/dt, m*): NormalForce, F_n > 0 repulsive
                 and its damping coefficient; and, for a head-on impact at relative normal
                 speed v (ftm2v: see ellipsoid_force_law.h) stiffness(R*), deepest_overlap,
                 peak_force, peak_damping, contact_time, damping_time; ELASTIC_LAW, the name
                 reports give its contact time ("Hertz")
     tangential  add_force(n, v_t, max(F_n, 0), gamma_n, dt, its history, force on i);
                 damping_coefficient(F_n, gamma_n), its dF_t / dv_t at the normal force F_n
                 and normal damping coefficient gamma_n (0: none)
   A row marked optional is a keyword parameter: given as "word value" after the model's
   numbers, its default the field's initialiser; the restart record stores it after every
   family's models (ellipsoid_force_law_table.cpp), so a record without it is the start of
   one with it.
     rolling     add_torque(n, motion, R*, max(F_n, 0), dt, its history, ContactForce)
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_FORCE_LAW_MODEL_H
#define ELLIPSOID_DEP_FORCE_LAW_MODEL_H

#include "ellipsoid_contact.h"

#include <array>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>
#include <variant>

namespace EllipsoidDep {

// Motion of the two bodies at the contact. For a wall, body j is the (resting) wall.
struct ContactMotion {
  Vec3 v_i = Vec3::Zero(), v_j = Vec3::Zero();              // centre velocities
  Vec3 omega_i = Vec3::Zero(), omega_j = Vec3::Zero();      // angular velocities (box frame)
  Vec3 branch_i = Vec3::Zero(), branch_j = Vec3::Zero();    // contact point minus centres
  double effective_mass = 0.0;                              // m_i m_j / (m_i + m_j); m_i for a wall
};

// What a normal model answers at a contact.
struct NormalForce {
  double force;      // F_n, > 0 repulsive
  double damping;    // gamma_n = dF_n / d(dxi/dt) (0: undamped)
};

struct ContactForce {
  Vec3 force_i = Vec3::Zero();     // force on i (on j: -force_i)
  Vec3 torque_i = Vec3::Zero();    // torque on i about its centre
  Vec3 torque_j = Vec3::Zero();    // torque on j about its centre
  double normal_force = 0.0;       // signed normal magnitude (> 0 repulsive)
};

// The allowed values of a parameter.
struct Range {
  double lo, hi;
  bool lo_closed, hi_closed;

  constexpr bool contains(double x) const
  {
    return (lo_closed ? x >= lo : x > lo) && (hi_closed ? x <= hi : x < hi);
  }
};

inline constexpr double INF = std::numeric_limits<double>::infinity();
inline constexpr Range POSITIVE = {0.0, INF, false, false};
inline constexpr Range NON_NEGATIVE = {0.0, INF, true, false};

// How a parameter of unlike types (or of a particle and a wall) is mixed.
enum class Mix {
  Geometric,         // sqrt(a b)
  Arithmetic,        // (a + b) / 2
  ReducedModulus,    // Young's modulus: the like-material E with Hertz's E* at the mixed nu
};

// One parameter of a model: its word in messages, its field, range and mixing rule.
template <class Model> struct ParameterRow {
  const char *word;
  double Model::*field;
  Range range;
  Mix mix;
  double Model::*poisson = nullptr;    // ReducedModulus: the Poisson ratio it pairs with
  bool optional = false;               // a keyword parameter (see the top of this file)
};

// Calls f with the model a family's variant holds: an if-chain the compiler inlines, and no
// exception path (std::visit has one; the kernel throws none).
template <std::size_t I = 0, class Variant, class F> decltype(auto) visit_model(Variant &v, F &&f)
{
  if constexpr (I + 1 < std::variant_size_v<std::remove_const_t<Variant>>)
    if (v.index() != I) return visit_model<I + 1>(v, std::forward<F>(f));
  return f(*std::get_if<I>(&v));
}

// The largest HISTORY_SIZE of a family's models.
template <class Variant, std::size_t... I>
constexpr int largest_history_size(std::index_sequence<I...>)
{
  int size = 0;
  for (int s : {std::variant_alternative_t<I, Variant>::HISTORY_SIZE...})
    size = s > size ? s : size;
  return size;
}
template <class Variant> constexpr int largest_history_size()
{
  return largest_history_size<Variant>(std::make_index_sequence<std::variant_size_v<Variant>>{});
}

// The HISTORY_SIZE of the model a family's variant holds.
template <class Variant> int history_size_of(const Variant &v)
{
  return visit_model(v, [](const auto &model) {
    return std::decay_t<decltype(model)>::HISTORY_SIZE;
  });
}

}    // namespace EllipsoidDep

#endif
