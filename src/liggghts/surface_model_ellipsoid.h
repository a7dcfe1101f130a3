/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP adapter for LIGGGHTS-PUBLIC 3.8: `surface ellipsoid`.

   A LIGGGHTS surface model for superquadric particles with blockiness 2 2 (true ellipsoids)
   whose particle-particle contact geometry comes from the ELLIPSOID_DEP contact kernel
   (EllipsoidDep::evaluate_pair: bounding spheres -> cached separating plane -> Wang test ->
   warm-started contact iteration with the normal correction). It holds no geometry of its own:
   it translates LIGGGHTS's per-atom data (x, quaternion, shape = semi-axes) to the kernel and
   the kernel's ContactGeometry back into SurfacesIntersectData (en, deltan, contact_point,
   reff), which LIGGGHTS's normal / tangential / rolling / cohesion models then consume.

   Per-pair history: the kernel's PairHistory (its pipeline's slots) lives in LIGGGHTS's
   contact history (newtonflag 1, PairHistory's swap rule). The pair keeps the
   CONTACT_SURFACE_MODEL contact flag while the history holds something, so a cached separating
   plane survives re-neighbouring (fix contacthistory keeps only flagged pairs).

   Walls (fix wall/gran ... surface ellipsoid): LIGGGHTS's superquadric wall code computes the
   wall contact point and overlap (mesh and primitive walls); this model sets the effective
   radius to the kernel's Gaussian-curvature radius at the wall contact normal (the LAMMPS wall
   fix of ELLIPSOID_DEP uses the same radius).

   Settings (after `surface ellipsoid` in pair_style gran / fix wall/gran):
     ellipsoidTolerance T      relative convergence of the contact iteration (1e-12)
     ellipsoidIterations N     iteration cap per contact evaluation (50)
     ellipsoidCorrection DEG   correct the contact vector when it deviates by more than DEG
                               degrees (0 = always, the default; > 0 = fast mode)
     ellipsoidPlanes yes|no    cache separating planes of disjoint pairs (yes)
     ellipsoidWang yes|no      Wang et al. separation test (yes)
   (the pair_style granular/ellipsoid keywords tolerance, iterations, correction, planes, wang)

   Registration: the SURFACE_MODEL line below is found by `sh Make.sh style` (style_surface_model.h)
   and `sh Make.sh models` (model combinations; add combinations beyond the automatic list to
   style_contact_model_user.whitelist).
------------------------------------------------------------------------- */

#ifdef SURFACE_MODEL
SURFACE_MODEL(SURFACE_ELLIPSOID,ellipsoid,7)
#else
#ifndef SURFACE_MODEL_ELLIPSOID_H_
#define SURFACE_MODEL_ELLIPSOID_H_

#include "surface_model_base.h"

#ifdef SUPERQUADRIC_ACTIVE_FLAG

#include "contact_models.h"
#include "atom.h"
#include "error.h"
#include "math_extra_liggghts_nonspherical.h"
#include "ellipsoid_dep_bridge.h"
#include <cmath>
#include <cstdio>

namespace LIGGGHTS {
namespace ContactModels
{
  template<>
  class SurfaceModel<SURFACE_ELLIPSOID> : public SurfaceModelBase
  {
    int history_offset;
    EllipsoidDepLiggghts::Settings kernel;
    double tolerance_setting;
    double iterations_setting;
    double correction_setting;
    bool planes_setting;
    bool wang_setting;

    // LIGGGHTS's Error::one writes to an unflushed screen only and aborts, so the message is
    // lost when the screen is a pipe or a file: write it to screen and log, flushed, first
    void fail(const char *message)
    {
      if (screen) { fprintf(screen, "ERROR: %s\n", message); fflush(screen); }
      if (logfile) { fprintf(logfile, "ERROR: %s\n", message); fflush(logfile); }
      error->one(FLERR, message);
    }

    // blockiness 2 2 (LIGGGHTS accepts blockiness >= 2)
    inline void check_ellipsoid(int i)
    {
      const double *blk = atom->blockiness[i];
      if (std::fabs(blk[0] - 2.0) > 1e-10 || std::fabs(blk[1] - 2.0) > 1e-10)
        fail("surface ellipsoid needs superquadric particles with blockiness 2 2");
    }

  public:
    SurfaceModel(LAMMPS * lmp, IContactHistorySetup* hsetup, class ContactModelBase *cmb) :
        SurfaceModelBase(lmp, hsetup, cmb),
        tolerance_setting(1e-12),
        iterations_setting(50),
        correction_setting(0.0),
        planes_setting(true),
        wang_setting(true)
    {
      if (!atom->superquadric_flag)
        error->one(FLERR, "surface ellipsoid needs atom_style superquadric");
      // the kernel's per-pair history (PairHistory): every slot odd under i <-> j ("1")
      history_offset = hsetup->add_history_value(EllipsoidDepLiggghts::history_slot_name(0), "1");
      for (int k = 1; k < EllipsoidDepLiggghts::HISTORY_SIZE; k++)
        hsetup->add_history_value(EllipsoidDepLiggghts::history_slot_name(k), "1");
      if (cmb) cmb->add_history_offset("ellipsoid_dep_history_offset", history_offset);
    }

    inline void registerSettings(Settings& settings)
    {
      settings.registerDoubleSetting("ellipsoidTolerance", tolerance_setting, 1e-12);
      settings.registerDoubleSetting("ellipsoidIterations", iterations_setting, 50);
      settings.registerDoubleSetting("ellipsoidCorrection", correction_setting, 0.0);
      settings.registerYesNo("ellipsoidPlanes", planes_setting, true);
      settings.registerYesNo("ellipsoidWang", wang_setting, true);
    }

    inline void postSettings(IContactHistorySetup *, ContactModelBase *)
    {
      if (!(tolerance_setting > 0.0))
        error->all(FLERR, "surface ellipsoid: ellipsoidTolerance must be > 0");
      if (!(iterations_setting >= 1.0) || iterations_setting != std::floor(iterations_setting))
        error->all(FLERR, "surface ellipsoid: ellipsoidIterations must be an integer >= 1");
      if (!(correction_setting >= 0.0 && correction_setting < 90.0))
        error->all(FLERR, "surface ellipsoid: ellipsoidCorrection must be in [0, 90) degrees");
      kernel.tolerance = tolerance_setting;
      kernel.max_iterations = static_cast<int>(iterations_setting);
      kernel.correction_angle = correction_setting * M_PI / 180.0;
      kernel.use_planes = planes_setting;
      kernel.use_wang = wang_setting;
    }

    inline void connectToProperties(PropertyRegistry&) {}

    // narrow phase (pair only; LIGGGHTS's broad phase has already found the bounding spheres
    // overlapping)
    inline bool checkSurfaceIntersect(SurfacesIntersectData & sidata)
    {
      sidata.is_non_spherical = true;
      const int i = sidata.i;
      const int j = sidata.j;
      check_ellipsoid(i);
      check_ellipsoid(j);

      double scratch[EllipsoidDepLiggghts::HISTORY_SIZE] = {};
      double *const history =
          sidata.contact_history ? &sidata.contact_history[history_offset] : scratch;

      EllipsoidDepLiggghts::Contact c;
      const bool touching = EllipsoidDepLiggghts::pair_contact(
          atom->x[i], atom->quaternion[i], atom->shape[i],
          atom->x[j], atom->quaternion[j], atom->shape[j], kernel, history, c);
      if (c.status == 4)
        fail("surface ellipsoid: degenerate particle data (non-finite position, quaternion or "
             "shape)");

      // keep the history (cached plane or normal) across re-neighbouring while it holds something
      if (sidata.contact_flags) {
        if (EllipsoidDepLiggghts::history_in_use(history)) *sidata.contact_flags |= CONTACT_SURFACE_MODEL;
        else *sidata.contact_flags &= ~CONTACT_SURFACE_MODEL;
      }
      if (!touching) return false;

      // LIGGGHTS: en points from j to i (like delta = x_i - x_j); the kernel's normal is i -> j
      sidata.en[0] = -c.normal[0];
      sidata.en[1] = -c.normal[1];
      sidata.en[2] = -c.normal[2];
      sidata.deltan = c.overlap;
      sidata.contact_point[0] = c.point[0];
      sidata.contact_point[1] = c.point[1];
      sidata.contact_point[2] = c.point[2];
      sidata.reff = c.effective_radius;
      return true;
    }

    inline void surfacesIntersect(SurfacesIntersectData & sidata, ForceData&, ForceData&)
    {
      if (sidata.is_wall) {
        // wall geometry from LIGGGHTS's superquadric wall code; R* from the kernel:
        // the particle's outer normal at the contact is -en (en points from the wall into it)
        const int i = sidata.i;
        check_ellipsoid(i);
        const double outer[3] = {-sidata.en[0], -sidata.en[1], -sidata.en[2]};
        sidata.reff = EllipsoidDepLiggghts::gaussian_radius(atom->x[i], atom->quaternion[i],
                                                            atom->shape[i], outer);
      }
      // relative velocities at the contact point (vn, vtr, wr, cri, crj) from en and the point
      MathExtraLiggghtsNonspherical::surfacesIntersectNonSpherical(sidata, atom->x);
    }

    inline void endSurfacesIntersect(SurfacesIntersectData&,TriMesh *, double * const) {}
    inline void surfacesClose(SurfacesCloseData&, ForceData&, ForceData&) {}
    void beginPass(SurfacesIntersectData&, ForceData&, ForceData&) {}
    void endPass(SurfacesIntersectData&, ForceData&, ForceData&) {}
    inline void tally_pp(double,int,int,int) {}
    inline void tally_pw(double,int,int,int) {}
  };
}
}

#else  // SUPERQUADRIC_ACTIVE_FLAG

SURFACE_MODEL_DUMMY(SURFACE_ELLIPSOID, "surface ellipsoid needs LIGGGHTS built with SUPERQUADRIC_ACTIVE_FLAG")

#endif // SUPERQUADRIC_ACTIVE_FLAG

#endif // SURFACE_MODEL_ELLIPSOID_H_
#endif // SURFACE_MODEL
