/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: contact force laws, one definition for the pair style and the wall.

   A law is three sub-models (normal, tangential, rolling), each a kind and its parameters.
   The laws see only a ContactGeometry (from the kernel) and a ContactMotion (velocities at
   the contact), so pair, wall and any other engine feed them the same way. Parsing,
   validation, mixing and the restart layout of the parameters come from one table per
   sub-model (ellipsoid_force_law_table.cpp). No LAMMPS header.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_FORCE_LAW_H
#define ELLIPSOID_DEP_ELLIPSOID_FORCE_LAW_H

#include "ellipsoid_contact.h"

#include <functional>
#include <string>
#include <vector>

namespace EllipsoidDep {

// Motion of the two bodies at the contact. For a wall, body j is the (resting) wall.
struct ContactMotion {
  Vec3 v_i = Vec3::Zero(), v_j = Vec3::Zero();              // centre velocities
  Vec3 omega_i = Vec3::Zero(), omega_j = Vec3::Zero();      // angular velocities (box frame)
  Vec3 branch_i = Vec3::Zero(), branch_j = Vec3::Zero();    // contact point minus centres
  double effective_mass = 0.0;                              // m_i m_j / (m_i + m_j); m_i for a wall
};

struct ContactForce {
  Vec3 force_i = Vec3::Zero();     // force on i (on j: -force_i)
  Vec3 torque_i = Vec3::Zero();    // torque on i about its centre
  Vec3 torque_j = Vec3::Zero();    // torque on j about its centre
  double normal_force = 0.0;       // signed normal magnitude (> 0 repulsive)
};

struct NormalModel {
  enum class Kind { Hertz, HertzMaterial };
  Kind kind = Kind::Hertz;
  double kn = 0.0;               // hertz: F = kn xi^3/2 + damping xi^1/2 dxi/dt
  double damping = 0.0;          // hertz: the paper's K
  double youngs = 0.0;           // hertz/material: E (of the like material that gives E*)
  double poisson = 0.0;          // hertz/material: nu
  double restitution = 1.0;      // hertz/material: e in (0, 1]
  bool limit_damping = false;    // clip the normal force at zero (never attractive)
};

struct TangentialModel {
  enum class Kind { None, Viscous, History };
  Kind kind = Kind::None;
  double mu_viscous = 0.0;    // viscous: F_t = -mu F_n v_t (mu in time/length)
  double kt = 0.0;            // history: tangential spring
  double mu = 0.0;            // history: Coulomb coefficient
};

struct RollingModel {
  enum class Kind { None, Constant };
  Kind kind = Kind::None;
  double mu_roll = 0.0;    // constant: |M_r| = mu_roll R* F_n, against relative rolling
};

struct ForceLaw {
  NormalModel normal;
  TangentialModel tangential;
  RollingModel rolling;

  // doubles of per-contact history this law needs (tangential displacement)
  int history_size() const { return tangential.kind == TangentialModel::Kind::History ? 3 : 0; }
  // empty when the parameters lie in their ranges, else a message naming the bad one
  std::string validate() const;

  // Force and torques for one contact. history: history_size() doubles (may be null when 0).
  // The normal points from i to j; the force acts at geometry.point.
  ContactForce compute(const ContactGeometry &geometry, const ContactMotion &motion, double dt,
                       double *history) const;

  // k of the elastic normal force k xi^3/2 at effective radius R*
  double hertz_stiffness(double effective_radius) const;
  // gamma of the normal damping force gamma dxi/dt at overlap xi (given as sqrt(xi), which
  // compute has at hand), effective radius R* and effective mass m*
  double damping_coefficient(double effective_radius, double sqrt_overlap,
                             double effective_mass) const;
};

// Deepest overlap of an undamped Hertz impact, F = stiffness xi^3/2, at relative normal
// speed impact_speed: (5 m* v^2 / (4 k))^(2/5).
double hertz_max_overlap(double stiffness, double effective_mass, double impact_speed);

// ftm2v below: the engine's factor in acceleration = ftm2v force / mass (LAMMPS's
// force->ftm2v; 1 where mass, length, time and force are consistent, not so in LAMMPS's units
// real, metal and electron). The inertia in the equation of motion is then m* / ftm2v.

// Duration of an undamped Hertz impact, F = stiffness xi^3/2, at relative normal speed
// impact_speed: 2 (2/5) B(2/5, 1/2) (5 m*/(4 k))^(2/5) v^(-1/5) ~ 3.218 (m*^2/(k^2 v))^(1/5).
double hertz_contact_time(double stiffness, double effective_mass, double impact_speed,
                          double ftm2v = 1.0);

// m* / gamma at the deepest overlap of that impact (HUGE_VAL without damping). Velocity Verlet
// integrates a damper stably only for dt / (m*/gamma) < 2: dt over this time is the damping
// number a run must keep small. gamma is the one compute() applies, from m* in mass units as
// given (LAMMPS's pair granular's convention for the restitution damping); the time divides
// the inertia m* / ftm2v by it.
double hertz_damping_time(const ForceLaw &law, double effective_radius, double effective_mass,
                          double impact_speed, double ftm2v = 1.0);

// A named material of the materials file, in the units of the simulation.
struct Material {
  double youngs, poisson, restitution;
};
// Answers a material name: an empty string and the material, or the reason it cannot
// (unknown name, no unit conversion). Supplied by the caller, so this file stays free of I/O.
using MaterialLookup = std::function<std::string(const std::string &name, Material &material)>;

// Parses the force-law words shared by pair_coeff and the wall fix:
//   hertz kn K | hertz/material E nu e | hertz/material NAME
//   | hertz/material E e nu damping coeff_restitution   (LAMMPS pair granular's order)
//   [tangential none | viscous mu | history kt mu] [rolling none | constant mu_r]
//   [limit_damping]
// Returns the number of words used; on error returns -1 and sets error to a message that
// names the offending word (callers turn it into a LAMMPS ERROR). Stops at the first word it
// does not know, so callers can parse their own keywords after it.
int parse_force_law(const std::vector<std::string> &words, ForceLaw &law, std::string &error,
                    const MaterialLookup &lookup = nullptr);

// The law of unlike types (or of a particle against a wall of another material), parameter
// by parameter as the tables say: E gives Hertz's reduced modulus
// 1/E* = (1-nu_a^2)/E_a + (1-nu_b^2)/E_b, the rest geometric means (nu arithmetic).
// Returns an empty string, or a refusal naming both models when the kinds differ.
std::string mix_laws(const ForceLaw &a, const ForceLaw &b, ForceLaw &mixed);

// Restart layout: every parameter of every table, in table order, after the kinds.
int packed_law_size();
std::vector<double> pack_law(const ForceLaw &law);
// false when a kind is out of range (a corrupt or foreign record)
bool unpack_law(const double *values, ForceLaw &law);

// The three model names of a law, e.g. "hertz/material, tangential history, rolling none"
std::string describe_models(const ForceLaw &law);

}    // namespace EllipsoidDep

#endif
