/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: contact force laws, one definition for the pair style and the wall.

   The laws see only a ContactGeometry (from the kernel) and a ContactMotion (velocities at
   the contact), so pair, wall and any other engine feed them the same way. No LAMMPS header.
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

struct ForceLaw {
  enum class Normal { Hertz, HertzMaterial };
  enum class Tangential { None, Viscous, History };
  enum class Rolling { None, Constant };

  Normal normal = Normal::Hertz;
  double kn = 0.0;             // hertz: F = kn xi^3/2 + damping xi^1/2 dxi/dt
  double damping = 0.0;        // hertz: the paper's K
  double youngs = 0.0;         // hertz/material: E (both bodies the same material)
  double poisson = 0.0;        // hertz/material: nu
  double restitution = 1.0;    // hertz/material: e in (0, 1]

  Tangential tangential = Tangential::None;
  double mu_viscous = 0.0;    // viscous: F_t = -mu F_n v_t (mu in time/length)
  double kt = 0.0;            // history: tangential spring
  double mu = 0.0;            // history: Coulomb coefficient

  Rolling rolling = Rolling::None;
  double mu_roll = 0.0;    // constant: |M_r| = mu_roll R* F_n, against relative rolling

  // doubles of per-contact history this law needs (tangential displacement)
  int history_size() const { return tangential == Tangential::History ? 3 : 0; }
  // empty when the parameters make sense, else a message naming the bad one
  std::string validate() const;

  // Force and torques for one contact. history: history_size() doubles (may be null when 0).
  // The normal points from i to j; the force acts at geometry.point.
  ContactForce compute(const ContactGeometry &geometry, const ContactMotion &motion, double dt,
                       double *history) const;
};

// Looks up a named material (E, nu, e); false when unknown. Supplied by the caller (the
// LAMMPS styles read potentials/*.materials), so this file stays free of I/O.
using MaterialLookup = std::function<bool(const std::string &name, double &youngs, double &poisson,
                                          double &restitution)>;

// Parses the force-law words shared by pair_coeff and the wall fix:
//   hertz kn K | hertz/material E nu e | hertz/material NAME
//   [tangential none | viscous mu | history kt mu] [rolling none | constant mu_r]
// Returns the number of words used; on error returns -1 and sets error to a message that
// names the offending word (callers turn it into a LAMMPS ERROR). Stops at the first word it
// does not know, so callers can parse their own keywords after it.
int parse_force_law(const std::vector<std::string> &words, ForceLaw &law, std::string &error,
                    const MaterialLookup &lookup = nullptr);

}    // namespace EllipsoidDep

#endif
