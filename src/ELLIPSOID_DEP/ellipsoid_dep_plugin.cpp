/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: the plugin entry point. LAMMPS loads ellipsoiddepplugin.so from
   LAMMPS_PLUGIN_PATH (or "plugin load") and calls lammpsplugin_init, which registers
   every style of the package.
------------------------------------------------------------------------- */

#include "lammpsplugin.h"
#include "version.h"

#include "compute_contact_histo.h"
#include "compute_force_histo.h"
#include "compute_orient_histo.h"
#include "compute_packing_ellipsoid.h"
#include "compute_packing_profile.h"
#include "compute_unbalanced_force.h"
#include "fix_damping_cundall_ellipsoid.h"
#include "fix_nve_ellipsoid.h"
#include "fix_pour_ellipsoid.h"
#include "fix_wall_gran_ellipsoid.h"
#include "fix_wall_gran_region_ellipsoid.h"
#include "granular_contact_rows.h"
#include "pair_granular_ellipsoid.h"

using namespace LAMMPS_NS;

namespace {
template <class Style, class Base> Base *create(LAMMPS *lmp)
{
  return new Style(lmp);
}
template <class Style, class Base> Base *create_with_args(LAMMPS *lmp, int narg, char **arg)
{
  return new Style(lmp, narg, arg);
}

void register_style(lammpsplugin_regfunc register_plugin, void *lmp, void *handle,
                    const char *style, const char *name, const char *info, void *creator)
{
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.style = style;
  plugin.name = name;
  plugin.info = info;
  plugin.author = "ELLIPSOID_DEP developers";
  plugin.creator.v1 = (lammpsplugin_factory1 *) creator;
  plugin.handle = handle;
  (*register_plugin)(&plugin, lmp);
}
}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto reg = (lammpsplugin_regfunc) regfunc;
  register_style(reg, lmp, handle, "pair", "granular/ellipsoid",
                 "general ellipsoid contact (Wang test, cached planes, corrected Perram contact)",
                 (void *) &create<PairGranularEllipsoid, Pair>);
  register_style(reg, lmp, handle, "fix", "pour/ellipsoid", "pour polydisperse general ellipsoids",
                 (void *) &create_with_args<FixPourEllipsoid, Fix>);
  register_style(reg, lmp, handle, "fix", "wall/gran/ellipsoid",
                 "plane walls for general ellipsoids",
                 (void *) &create_with_args<FixWallGranEllipsoid, Fix>);
  register_style(reg, lmp, handle, "fix", "wall/gran/region/ellipsoid",
                 "region walls (block, cylinder, cone, sphere, plane) for general ellipsoids",
                 (void *) &create_with_args<FixWallGranRegionEllipsoid, Fix>);
  register_style(reg, lmp, handle, "fix", "STORE_CONTACT_ROWS/ELLIPSOID_DEP",
                 "pair granular/ellipsoid's contact rows stored back (internal)",
                 (void *) &create_with_args<FixStoreContactRows, Fix>);
  register_style(reg, lmp, handle, "fix", "nve/ellipsoid",
                 "velocity Verlet for ellipsoids (nve/asphere) that does not rotate spheres",
                 (void *) &create_with_args<FixNVEEllipsoid, Fix>);
  register_style(reg, lmp, handle, "fix", "damping/cundall/ellipsoid",
                 "Cundall's local damping for ellipsoids (a settling aid)",
                 (void *) &create_with_args<FixDampingCundallEllipsoid, Fix>);
  register_style(reg, lmp, handle, "compute", "packing/ellipsoid",
                 "volume fraction and coordination number of an ellipsoid deposit",
                 (void *) &create_with_args<ComputePackingEllipsoid, Compute>);
  register_style(reg, lmp, handle, "compute", "packing/profile",
                 "solid fraction profile phi(z) of an ellipsoid deposit (exact slab volumes)",
                 (void *) &create_with_args<ComputePackingProfile, Compute>);
  register_style(reg, lmp, handle, "compute", "contact/histo",
                 "histogram of contact-normal angles with +z",
                 (void *) &create_with_args<ComputeContactHisto, Compute>);
  register_style(reg, lmp, handle, "compute", "force/histo",
                 "distribution of the normal contact forces, P(f/<f>)",
                 (void *) &create_with_args<ComputeForceHisto, Compute>);
  register_style(reg, lmp, handle, "compute", "orient/histo",
                 "histogram of principal-axis angles with +z",
                 (void *) &create_with_args<ComputeOrientHisto, Compute>);
  register_style(reg, lmp, handle, "compute", "unbalanced/force",
                 "unbalanced force ratio: mean net force over mean contact force",
                 (void *) &create_with_args<ComputeUnbalancedForce, Compute>);
}
