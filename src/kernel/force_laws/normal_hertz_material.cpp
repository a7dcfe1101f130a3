/* ----------------------------------------------------------------------
   ELLIPSOID_DEP force laws, normal model hertz/material (see normal_hertz_material.h).
------------------------------------------------------------------------- */

#include "normal_hertz_material.h"

#include <utility>

namespace EllipsoidDep {

// LAMMPS's pair granular writes "hertz/material E damping nu" and names the damping model
// after the keyword "damping"; only the restitution damping is the one this model has.
std::string lammps_damping(const std::string &damping_model, HertzMaterialNormal *normal,
                           bool numbers_given)
{
  const std::string ours = "write 'hertz/material E nu e' or, in LAMMPS's order, "
                           "'hertz/material E e nu damping coeff_restitution'";
  if (!normal || !numbers_given)
    return "damping " + damping_model +
        " applies only to hertz/material with numbers (E e nu): " + ours;
  if (damping_model != "coeff_restitution")
    return "damping " + damping_model +
        " is not available: hertz/material damps by the restitution coefficient e; " + ours;
  std::swap(normal->poisson, normal->restitution);
  return {};
}

}    // namespace EllipsoidDep
