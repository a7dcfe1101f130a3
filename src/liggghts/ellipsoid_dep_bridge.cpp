/* ----------------------------------------------------------------------
   ELLIPSOID_DEP adapter for LIGGGHTS-PUBLIC 3.8: bridge to the contact kernel
   (see ellipsoid_dep_bridge.h). Translation only; the geometry is the kernel's.
------------------------------------------------------------------------- */

#include "ellipsoid_dep_bridge.h"

#include "ellipsoid_kernel.h"

namespace EllipsoidDepLiggghts {

static_assert(HISTORY_SIZE == EllipsoidDep::PairHistory::PIPELINE_SIZE,
              "per-pair history size mismatch");

namespace {
  EllipsoidDep::PipelineCounters totals;

  EllipsoidDep::Ellipsoid make(const double *x, const double *q, const double *shape)
  {
    return EllipsoidDep::make_ellipsoid(EllipsoidDep::Vec3(x[0], x[1], x[2]), q,
                                        EllipsoidDep::Vec3(shape[0], shape[1], shape[2]));
  }

  void copy(const EllipsoidDep::Vec3 &v, double *out)
  {
    out[0] = v[0];
    out[1] = v[1];
    out[2] = v[2];
  }
}    // namespace

bool pair_contact(const double *xi, const double *qi, const double *shapei, const double *xj,
                  const double *qj, const double *shapej, const Settings &settings,
                  double *history, Contact &out)
{
  using namespace EllipsoidDep;
  PipelineSettings ps;
  ps.contact.tolerance = settings.tolerance;
  ps.contact.max_iterations = settings.max_iterations;
  ps.contact.correction_angle = settings.correction_angle;
  ps.contact.wang_band = settings.wang_band;
  ps.use_planes = settings.use_planes;
  ps.use_wang = settings.use_wang;

  const Ellipsoid a = make(xi, qi, shapei);
  const Ellipsoid b = make(xj, qj, shapej);
  const ContactGeometry g = evaluate_pair(a, b, ps, history, totals);

  out.status = static_cast<int>(g.status);
  out.overlap = g.overlap;
  const bool contact =
      (g.status == Status::Overlapping || g.status == Status::NotConverged) && g.overlap > 0.0;
  if (contact) {
    copy(g.normal, out.normal);
    copy(g.point, out.point);
    out.effective_radius = g.effective_radius;
  }
  return contact;
}

double gaussian_radius(const double *x, const double *q, const double *shape, const double *n)
{
  const EllipsoidDep::Ellipsoid e = make(x, q, shape);
  return EllipsoidDep::gaussian_radius(e, EllipsoidDep::Vec3(n[0], n[1], n[2]).normalized());
}

const char *history_slot_name(int k)
{
  using EllipsoidDep::PairHistory;
  static const char *const names[HISTORY_SIZE] = {"ellipsoid_dep_state", "ellipsoid_dep_nx",
                                                  "ellipsoid_dep_ny", "ellipsoid_dep_nz",
                                                  "ellipsoid_dep_u_or_stepx", "ellipsoid_dep_stepy",
                                                  "ellipsoid_dep_stepz", "ellipsoid_dep_dcx",
                                                  "ellipsoid_dep_dcy", "ellipsoid_dep_dcz"};
  static_assert(PairHistory::STATE == 0 && PairHistory::NORMAL == 1 && PairHistory::PLANE_U == 4 &&
                    PairHistory::NORMAL_STEP == 4 && PairHistory::SEPARATION == 7,
                "slot names follow the PairHistory layout");
  return names[k];
}

bool history_in_use(double *history)
{
  return EllipsoidDep::PairHistory(history).in_use();
}

int counter_count()
{
  return EllipsoidDep::NUM_PIPELINE_COUNTERS;
}

const char *counter_name(int k)
{
  return EllipsoidDep::PIPELINE_COUNTERS[k].name;
}

long long counter_value(int k)
{
  return totals.*EllipsoidDep::PIPELINE_COUNTERS[k].member;
}

}    // namespace EllipsoidDepLiggghts
