/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: the random particles of a pour: size, shape and orientation, and the
   statistics of their distribution.

   Engine independent: C++17 + Eigen only. No LAMMPS header, no MPI, no I/O, no exceptions.
   fix pour/ellipsoid feeds it LAMMPS's RanPark; the kernel tests feed it their own generator.

   Conventions
   - The size of a particle with semi-axes a >= b >= c is r = (abc)^(1/3), the radius of the
     sphere of equal volume.
   - V(r) ~ (r - rmin)^(alpha-1) (rmax - r)^(beta-1) on [rmin, rmax] is the VOLUME
     distribution (the paper's): the total volume of the particles of size r. The NUMBER
     distribution of the particles drawn is therefore n(r) ~ V(r) / r^3.
   - Shape: eta = a/b and zeta = b/c, each uniform on [mean (1 - delta), mean (1 + delta)];
     then c = r (eta zeta^2)^(-1/3), b = zeta c, a = eta b, so abc = r^3 exactly.
   - Orientation: a unit quaternion (w, x, y, z), body -> box, uniform on SO(3).
   - Random numbers: every deviate is built from the caller's uniform deviates on (0, 1) only,
     so the engine's generator and its restart state stay the engine's. The calls per
     particle are, in this order: size() (a rejection loop), semi_axes() (one call per
     factor whose delta > 0), orientation() (three calls).
   Degenerate cases: rmax - rmin <= 1e-12 rmax is mono-sized (size() draws nothing);
   delta = 0 draws nothing for that factor. Preconditions (checked by the caller, who can
   name the bad argument): 0 < rmin <= rmax, alpha, beta > 0, eta (1 - delta_eta) >= 1,
   zeta (1 - delta_zeta) >= 1, 0 <= delta < 1.
------------------------------------------------------------------------- */

#ifndef ELLIPSOID_DEP_ELLIPSOID_POUR_SAMPLER_H
#define ELLIPSOID_DEP_ELLIPSOID_POUR_SAMPLER_H

#include <Eigen/Dense>

#include <functional>

namespace EllipsoidDep {

// a source of independent uniform deviates on (0, 1)
using UniformSource = std::function<double()>;

struct PourDistribution {
  double rmin = 0.5, rmax = 0.5;               // range of the size r
  double alpha = 3.0, beta = 3.0;              // exponents of V(r)
  double eta = 1.0, zeta = 1.0;                // mean a/b and b/c
  double delta_eta = 0.0, delta_zeta = 0.0;    // relative half-widths of eta and zeta
};

class PourSampler {
 public:
  PourSampler(const PourDistribution &distribution, UniformSource uniform);

  double size();                          // r from n(r) ~ V(r) / r^3
  Eigen::Vector3d semi_axes(double r);    // (a, b, c), a >= b >= c, abc = r^3
  void orientation(double quat[4]);       // uniform on SO(3)

  // statistics of the distribution (no random numbers)
  const PourDistribution &distribution() const { return dist; }
  double acceptance() const { return accepted; }        // of the size rejection step
  double mean_volume() const { return volume_mean; }    // 4/3 pi <r^3> under n(r)
  double largest_semi_axis() const;                     // a of rmax, eta_max, zeta_max
  double smallest_semi_axis() const;                    // c of rmin, eta_max, zeta_max
  double flattest_radius() const;    // largest ab/c: that of rmax, eta_max, zeta_max
  double largest_rotational_compliance() const;    // over the corners of the shape ranges

 private:
  PourDistribution dist;
  UniformSource uniform;
  double accepted, volume_mean;

  double shape_factor(double mean, double delta);
};

// x ~ Beta(a, b), a, b > 0, from uniform deviates only (Marsaglia-Tsang gamma deviates)
double beta_deviate(double a, double b, const UniformSource &uniform);

}    // namespace EllipsoidDep

#endif
