/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: contact force laws, one definition for the pair style and the wall.

   A law is one model of each family (normal, tangential, rolling; force_law_registry.h lists
   them, each model's file states its equation) and the limit_damping option. The laws see
   only a ContactGeometry (from the kernel) and a ContactMotion (velocities at the contact), so
   pair, wall and any other engine feed them the same way. Parsing, validation, mixing and the
   restart layout of the parameters follow the models' parameter rows
   (ellipsoid_force_law_table.cpp). No LAMMPS header.

   ftm2v below: the engine's factor in acceleration = ftm2v force / mass (LAMMPS's
   force->ftm2v; 1 where mass, length, time and force are consistent, not so in LAMMPS's units
   real, metal and electron). The inertia in the equation of motion is then m* / ftm2v.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_FORCE_LAW_H
#define ELLIPSOID_DEP_ELLIPSOID_FORCE_LAW_H

#include "force_law_registry.h"

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace EllipsoidDep {

struct ForceLaw {
  NormalModel normal;
  TangentialModel tangential;
  RollingModel rolling;
  bool limit_damping = false;    // F_n = max(F_n, 0): never attractive on fast separation

  // doubles of per-contact history of the chosen models: the tangential model's slots, then
  // the rolling model's
  int history_size() const { return history_size_of(tangential) + history_size_of(rolling); }
  // the most any law keeps
  static constexpr int MAX_HISTORY_SIZE =
      largest_history_size<TangentialModel>() + largest_history_size<RollingModel>();
  // empty when the parameters lie in their ranges, else a message naming the bad one
  std::string validate() const;

  // Force and torques for one contact. history: history_size() doubles (may be null when 0).
  // The normal points from i to j; the force acts at geometry.point.
  ContactForce compute(const ContactGeometry &geometry, const ContactMotion &motion, double dt,
                       double *history) const;

  // What every law answers for a head-on impact at relative normal speed impact_speed of
  // bodies of effective radius R* and effective mass m* (in mass units), from its normal model:
  // k of the elastic force k xi^(3/2) at R*
  double stiffness(double effective_radius) const;
  // the deepest overlap of the undamped impact
  double deepest_overlap(double effective_radius, double effective_mass, double impact_speed,
                         double ftm2v = 1.0) const;
  // the duration of the undamped impact
  double contact_time(double effective_radius, double effective_mass, double impact_speed,
                      double ftm2v = 1.0) const;
  // m* / gamma at its deepest overlap (HUGE_VAL without damping); a run keeps dt over it, the
  // damping number, small
  double damping_time(double effective_radius, double effective_mass, double impact_speed,
                      double ftm2v = 1.0) const;
  // m_t / gamma_t of the tangential model at the peak normal force and the normal damping
  // of the deepest overlap of that impact (HUGE_VAL when it does not damp). tangential_mass:
  // the effective mass for sliding at the contact, rotation included (rotational_compliance
  // in ellipsoid_shape.h); the same bound on dt
  double tangential_damping_time(double effective_radius, double effective_mass,
                                 double tangential_mass, double impact_speed,
                                 double ftm2v = 1.0) const;
  // the name reports give the contact time ("Hertz")
  const char *elastic_law() const;
};

// The law's history handed to ForceLaw::compute, which advances it in place: the stored
// doubles, or a scratch copy for a look that must not change them (setup forces, single()).
class LawHistory {
 public:
  LawHistory(double *stored, int size, bool advance) : p(stored)
  {
    if (stored && !advance) {
      for (int k = 0; k < size; ++k) scratch[k] = stored[k];
      p = scratch.data();
    }
  }
  LawHistory(const LawHistory &) = delete;
  LawHistory &operator=(const LawHistory &) = delete;
  double *get() const { return p; }

 private:
  std::array<double, ForceLaw::MAX_HISTORY_SIZE> scratch;
  double *p;
};

// Answers a material name: an empty string and the material, or the reason it cannot
// (unknown name, no unit conversion). Supplied by the caller, so this file stays free of I/O.
using MaterialLookup = std::function<std::string(const std::string &name, Material &material)>;

// Parses the force-law words shared by pair_coeff and the wall fix:
//   hertz kn K | hertz/material E nu e | hertz/material NAME
//   | hertz/material E e nu damping coeff_restitution   (LAMMPS pair granular's order)
//   [tangential none | viscous mu | history kt mu [xt X]]
//   [rolling none | constant mu_r | sds k_r gamma_r mu_r]
//   [limit_damping]
// Returns the number of words used; on error returns -1 and sets error to a message that
// names the offending word (callers turn it into a LAMMPS ERROR). Stops at the first word it
// does not know, so callers can parse their own keywords after it.
int parse_force_law(const std::vector<std::string> &words, ForceLaw &law, std::string &error,
                    const MaterialLookup &lookup = nullptr);

// The law of unlike types (or of a particle against a wall of another material), parameter
// by parameter as the rows say: E gives Hertz's reduced modulus
// 1/E* = (1-nu_a^2)/E_a + (1-nu_b^2)/E_b, the rest geometric means (nu arithmetic).
// Returns an empty string, or a refusal naming both laws when their models differ.
std::string mix_laws(const ForceLaw &a, const ForceLaw &b, ForceLaw &mixed);

// Restart layout: limit_damping, then per family the model's code and the parameters of
// every model of the family, in registry and row order; then the optional rows the same way
// (force_law_model.h): values added later come last, so an older record is a prefix.
int packed_law_size();
std::vector<double> pack_law(const ForceLaw &law);
// false when a code is out of range (a corrupt or foreign record)
bool unpack_law(const double *values, ForceLaw &law);

// The three model names of a law, e.g. "hertz/material, tangential history, rolling none"
std::string describe_models(const ForceLaw &law);

}    // namespace EllipsoidDep

#endif
