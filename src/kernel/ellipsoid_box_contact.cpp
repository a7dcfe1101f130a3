/* ----------------------------------------------------------------------
   ELLIPSOID_DEP kernel: ellipsoid outside a box (see ellipsoid_box_contact.h)
------------------------------------------------------------------------- */

#include "ellipsoid_box_contact.h"

#include "ellipsoid_normal_patch.h"

namespace EllipsoidDep {

namespace {

  constexpr int EDGE_SAMPLES = 16;
  constexpr int CORNER_SAMPLES = 8;    // per angle

  // the smallest overlap found so far: its value, direction (box frame) and convergence
  struct Candidate {
    double value = HUGE_VAL;
    Vec3 n = Vec3::Zero();
    bool converged = true;
    void offer(double v, const Vec3 &direction, bool settled)
    {
      if (v < value) value = v, n = direction, converged = settled;
    }
  };

}    // namespace

ContactGeometry ellipsoid_box_contact(const Ellipsoid &e, const Vec3 &center, const Mat3 &frame,
                                      const Vec3 &lower, const Vec3 &upper)
{
  ContactGeometry g;
  g.status = Status::Degenerate;
  if (!valid(e) || !finite3(center) || !frame.allFinite() || lower.hasNaN() || upper.hasNaN() ||
      (lower.array() > upper.array()).any())
    return g;
  // the particle in the box's frame: centre and inverse form
  const Vec3 c = frame.transpose() * (e.center - center);
  const Mat3 m = frame.transpose() * e.inverse_form * frame;
  const double bound[2][3] = {{lower[0], lower[1], lower[2]}, {upper[0], upper[1], upper[2]}};
  const double sign[2] = {-1.0, 1.0};
  auto finite_face = [&](int side, int k) {
    return std::isfinite(bound[side][k]);
  };

  Candidate best;
  // faces
  bool any_face = false;
  for (int side = 0; side < 2; side++)
    for (int k = 0; k < 3; k++) {
      if (!finite_face(side, k)) continue;
      any_face = true;
      const Vec3 n = sign[side] * Vec3::Unit(k);
      best.offer(support(m, n) + sign[side] * (bound[side][k] - c[k]), n, true);
    }
  if (!any_face) return g;
  const double reach =
      e.bounding_radius + std::max(0.0, box_clearance(center, frame, lower, upper, e.center));

  // edges: faces (side1, k1) and (side2, k2), k1 < k2; the point of the edge nearest the centre
  for (int k1 = 0; k1 < 3 && best.value > 0.0; k1++)
    for (int k2 = k1 + 1; k2 < 3; k2++) {
      const int k3 = 3 - k1 - k2;
      for (int side1 = 0; side1 < 2; side1++)
        for (int side2 = 0; side2 < 2; side2++) {
          if (!finite_face(side1, k1) || !finite_face(side2, k2)) continue;
          Vec3 p;
          p[k1] = bound[side1][k1];
          p[k2] = bound[side2][k2];
          p[k3] = std::min(upper[k3], std::max(lower[k3], c[k3]));
          if ((p - c).norm() > reach + best.value) continue;
          const NormalPatch patch{
              m,  Vec3::Unit(k3), sign[side1] * Vec3::Unit(k1), sign[side2] * Vec3::Unit(k2), p - c,
              0.0};
          const IntervalMinimum edge =
              minimise_on_interval(NormalArc{patch}, 0.0, 0.5 * PI, false, EDGE_SAMPLES);
          best.offer(edge.value, patch.normal(edge.x, 0.5 * PI), edge.converged);
        }
    }

  // corners
  for (int corner = 0; corner < 8 && best.value > 0.0; corner++) {
    const int side[3] = {corner & 1, (corner >> 1) & 1, (corner >> 2) & 1};
    if (!finite_face(side[0], 0) || !finite_face(side[1], 1) || !finite_face(side[2], 2)) continue;
    const Vec3 p(bound[side[0]][0], bound[side[1]][1], bound[side[2]][2]);
    if ((p - c).norm() > reach + best.value) continue;
    const NormalPatch patch{m,
                            sign[side[2]] * Vec3::UnitZ(),
                            sign[side[0]] * Vec3::UnitX(),
                            sign[side[1]] * Vec3::UnitY(),
                            p - c,
                            0.0};
    const PatchMinimum vertex = minimise_on_patch(patch, 0.5 * PI, CORNER_SAMPLES, CORNER_SAMPLES);
    best.offer(vertex.value, vertex.n, vertex.converged);
  }

  // an overlap <= 0 along any direction separates the bodies, converged or not
  return solid_contact(e, frame * best.n, best.value, 0.0, best.converged || best.value <= 0.0);
}

double box_clearance(const Vec3 &center, const Mat3 &frame, const Vec3 &lower, const Vec3 &upper,
                     const Vec3 &x)
{
  // infinite bounds: no face
  const Vec3 s = frame.transpose() * (x - center);
  const Vec3 beyond = (lower - s).cwiseMax(s - upper);
  if ((beyond.array() > 0.0).any()) return beyond.cwiseMax(0.0).norm();
  return beyond.maxCoeff();
}

}    // namespace EllipsoidDep
