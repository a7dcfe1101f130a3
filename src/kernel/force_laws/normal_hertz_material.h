/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP force laws, normal model "hertz/material E nu e" (or a material's NAME):
   Hertz with the contact's curvature and the restitution damping,

     F_n = 4/3 E* sqrt(R*) xi^(3/2) + gamma_n dxi/dt
     gamma_n = -2 sqrt(5/6) beta sqrt(S_n m*),  S_n = 2 E* sqrt(R* xi),
     beta = ln e / sqrt(ln^2 e + pi^2)          (LAMMPS's damping coeff_restitution)

   E* is Hertz's reduced modulus, 1/E* = (1-nu_a^2)/E_a + (1-nu_b^2)/E_b, which is
   E / (2 (1 - nu^2)) for one material: unlike materials are mixed into the E that gives the
   pair's E* at the mixed nu (Mix::ReducedModulus), so this model holds one E and one nu.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_NORMAL_HERTZ_MATERIAL_H
#define ELLIPSOID_DEP_NORMAL_HERTZ_MATERIAL_H

#include "force_law_model.h"
#include "hertz_elastic.h"

#include <cmath>
#include <string>

namespace EllipsoidDep {

// A named material of the materials file, in the units of the simulation.
struct Material {
  double youngs, poisson, restitution;
};

inline constexpr Range POISSON_RATIO = {-1.0, 0.5, false, false};
inline constexpr Range RESTITUTION = {0.0, 1.0, false, true};
// the factor of the damping derived from the restitution coefficient
inline const double SQRT_5_6 = std::sqrt(5.0 / 6.0);

struct HertzMaterialNormal : HertzElastic<HertzMaterialNormal> {
  static constexpr const char *NAME = "hertz/material";
  double youngs = 0.0;         // E (of the like material that gives E*)
  double poisson = 0.0;        // nu
  double restitution = 1.0;    // e in (0, 1]

  using Row = ParameterRow<HertzMaterialNormal>;
  static constexpr std::array ROWS{
      Row{"E", &HertzMaterialNormal::youngs, POSITIVE, Mix::ReducedModulus,
          &HertzMaterialNormal::poisson},
      Row{"nu", &HertzMaterialNormal::poisson, POISSON_RATIO, Mix::Arithmetic},
      Row{"e", &HertzMaterialNormal::restitution, RESTITUTION, Mix::Geometric}};

  double reduced_modulus() const { return youngs / (2.0 * (1.0 - poisson * poisson)); }
  double stiffness(double effective_radius) const
  {
    return 4.0 / 3.0 * reduced_modulus() * std::sqrt(effective_radius);
  }
  double damping_coefficient(double effective_radius, double sqrt_overlap,
                             double effective_mass) const
  {
    const double log_e = std::log(restitution);
    const double beta = log_e / std::sqrt(log_e * log_e + PI * PI);
    const double stiffness_n = 2.0 * reduced_modulus() * std::sqrt(effective_radius) * sqrt_overlap;
    return -2.0 * SQRT_5_6 * beta * std::sqrt(stiffness_n * effective_mass);
  }

  void set(const Material &material)
  {
    youngs = material.youngs;
    poisson = material.poisson;
    restitution = material.restitution;
  }
};

// LAMMPS pair granular's "hertz/material E e nu damping coeff_restitution": swaps the numbers,
// read as E nu e, into this model's order. normal: the law's hertz/material model (null when
// it has another); numbers_given: not a material's name. Empty, or the refusal.
std::string lammps_damping(const std::string &damping_model, HertzMaterialNormal *normal,
                           bool numbers_given);

}    // namespace EllipsoidDep

#endif
