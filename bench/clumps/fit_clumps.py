#!/usr/bin/env python3
"""Fit rigid multi-sphere clumps to a triaxial ellipsoid and write LAMMPS molecule files.

    fit_clumps.py [--k 3 7 15] [--eta 1.4] [--zeta 1.8] [--out DIR]

The ellipsoid has semi-axes a = eta zeta c, b = zeta c, c with abc = (d/2)^3, d = 1 (the
volume-equivalent diameter of in.deposit at delta_r 0). A clump of k spheres is symmetric
under the three mirror planes of the ellipsoid: its spheres are orbits of the group,
  O  one sphere at the centre,
  X  a pair at (+-x, 0, 0) on the long axis,  Y  a pair at (0, +-y, 0) on the middle axis,
  P  four at (+-x, +-y, 0) in the a-b plane,
each orbit with its own radius. A layout (the orbits of a k) is fitted by maximising the
intersection over union (IoU) of the sphere union with the ellipsoid, estimated on a fixed
scrambled Sobol point set in the positive octant of the bounding box (the shapes are mirror
symmetric), with scipy's differential evolution (fixed seed); among the layouts of a k the
best IoU wins. The union's volume, surface area and inertia are then estimated on independent
points: volume and inertia by Monte Carlo in the bounding box, the area by points on each
sphere's surface that lie in no other sphere; each with its standard error (1 sigma, binomial).
The ellipsoid's own volume and area are exact (Legendre's elliptic integrals).

Writes per k: clump_k<k>.mol (LAMMPS molecule file: Coords, Types, Diameters, Masses, and the
union's mass, centre of mass and inertia tensor in the header, density 1 over the union's
volume), clump_k<k>.coeff (pair_coeff lines, one per pair of types, mapping the Hertz law to
pair granular per sphere radius; include it after the variables kn K kt mu mstar are set),
clump_k<k>.walls (a group per sphere type and one fix wall/gran each), clump_k<k>.groups
(the group commands again: fix pour's later batches join the groups when it is re-run) and
clump_k<k>.json (the fit and its errors).
"""
import argparse
import json
import math
import os
import sys

import numpy as np
from scipy import optimize, special, stats

ORBIT_SIZE = {"O": 1, "X": 2, "Y": 2, "P": 4}
# layouts tried for each k (orbit letters; the multiplicities sum to k)
LAYOUTS = {3: ["OX"], 7: ["OXXY", "OXP"], 15: ["OXXXPP", "OXXYPP"]}
FIT_POINTS = 2 ** 15          # Sobol points in the positive octant for the fit
CHECK_POINTS = 2 ** 21        # Monte Carlo points for the reported volume and inertia
AREA_POINTS = 2 ** 16         # points per sphere surface for the area


def semi_axes(eta, zeta, d=1.0):
    c = (d / 2.0) / (eta * zeta * zeta) ** (1.0 / 3.0)
    return np.array([eta * zeta * c, zeta * c, c])


def ellipsoid_area(axes):
    """Exact surface area of an ellipsoid (Legendre's form with incomplete elliptic integrals)."""
    a, b, c = sorted(axes, reverse=True)
    if a == c:
        return 4.0 * math.pi * a * a
    phi = math.acos(c / a)
    m = (a * a * (b * b - c * c)) / (b * b * (a * a - c * c))
    s = math.sin(phi)
    return 2.0 * math.pi * c * c + 2.0 * math.pi * a * b / s * (
        (c * c / (a * a)) * special.ellipkinc(phi, m) + s * s * special.ellipeinc(phi, m))


def spheres_of(layout, params):
    """Centres (k, 3), radii (k,) and orbit index per sphere from the layout's parameters.
    Parameters per orbit: O: r; X: x, r; Y: y, r; P: x, y, r."""
    centres, radii, orbit = [], [], []
    p = list(params)
    for index, kind in enumerate(layout):
        if kind == "O":
            pts, r = [(0.0, 0.0, 0.0)], p.pop(0)
        elif kind == "X":
            x, r = p.pop(0), p.pop(0)
            pts = [(x, 0.0, 0.0), (-x, 0.0, 0.0)]
        elif kind == "Y":
            y, r = p.pop(0), p.pop(0)
            pts = [(0.0, y, 0.0), (0.0, -y, 0.0)]
        else:
            x, y, r = p.pop(0), p.pop(0), p.pop(0)
            pts = [(sx * x, sy * y, 0.0) for sx in (1, -1) for sy in (1, -1)]
        centres += pts
        radii += [r] * len(pts)
        orbit += [index] * len(pts)
    return np.array(centres), np.array(radii), np.array(orbit)


def bounds_of(layout, axes):
    a, b, c = axes
    rmax = 1.2 * b
    per = {"O": [(0.05, rmax)], "X": [(0.0, a), (0.05, rmax)], "Y": [(0.0, b), (0.05, rmax)],
           "P": [(0.0, a), (0.0, b), (0.05, rmax)]}
    return [bd for kind in layout for bd in per[kind]]


def in_union(points, centres, radii):
    d2 = ((points[:, None, :] - centres[None, :, :]) ** 2).sum(axis=2)
    return (d2 <= radii[None, :] ** 2).any(axis=1)


def in_ellipsoid(points, axes):
    return ((points / axes) ** 2).sum(axis=1) <= 1.0


def octant_points(axes, n, seed):
    """Scrambled Sobol points in [0, 1.3 a] x [0, 1.3 b] x [0, 1.3 c] (covers every clump the
    bounds allow that could matter: spheres reaching further only lose IoU)."""
    box = 1.3 * axes.max() * np.ones(3)
    return stats.qmc.Sobol(3, scramble=True, seed=seed).random(n) * box


def iou(layout, params, points, inside_e):
    centres, radii, _ = spheres_of(layout, params)
    inside_u = in_union(points, centres, radii)
    union = np.count_nonzero(inside_u | inside_e)
    return np.count_nonzero(inside_u & inside_e) / union if union else 0.0


def fit_layout(layout, axes, seed=1):
    points = octant_points(axes, FIT_POINTS, seed)
    inside_e = in_ellipsoid(points, axes)
    result = optimize.differential_evolution(
        lambda p: -iou(layout, p, points, inside_e), bounds_of(layout, axes), seed=seed,
        tol=1e-6, maxiter=200, popsize=10, polish=False)
    return result.x, -result.fun


def union_properties(centres, radii, axes, seed=7):
    """Volume, inertia tensor (density 1) and area of the union, with standard errors."""
    rng = np.random.default_rng(seed)
    half = np.max(np.abs(centres) + radii[:, None], axis=0)
    box_volume = np.prod(2 * half)
    hits, sums, inertia_sums = 0, np.zeros(3), np.zeros(6)
    n_total, inter_e = 0, 0
    for _ in range(CHECK_POINTS // 2 ** 17):
        pts = rng.uniform(-half, half, (2 ** 17, 3))
        inside = in_union(pts, centres, radii)
        inside_e = in_ellipsoid(pts, axes)
        p = pts[inside]
        hits += len(p)
        n_total += len(pts)
        x, y, z = p.T
        inertia_sums += [(y * y + z * z).sum(), (x * x + z * z).sum(), (x * x + y * y).sum(),
                         -(y * z).sum(), -(x * z).sum(), -(x * y).sum()]
        sums += p.sum(axis=0)
        inter_e += np.count_nonzero(inside & inside_e)
    frac = hits / n_total
    volume = box_volume * frac
    volume_se = box_volume * math.sqrt(frac * (1 - frac) / n_total)
    inertia = inertia_sums * box_volume / n_total
    # area: uniform points on each sphere, kept where no other sphere covers them
    area, area_var = 0.0, 0.0
    for i, (c, r) in enumerate(zip(centres, radii)):
        u = rng.normal(size=(AREA_POINTS, 3))
        u /= np.linalg.norm(u, axis=1)[:, None]
        pts = c + r * u
        others = np.arange(len(radii)) != i
        d2 = ((pts[:, None, :] - centres[None, others, :]) ** 2).sum(axis=2)
        exposed = np.count_nonzero(~(d2 < radii[None, others] ** 2).any(axis=1)) / AREA_POINTS
        sphere_area = 4 * math.pi * r * r
        area += sphere_area * exposed
        area_var += sphere_area ** 2 * exposed * (1 - exposed) / AREA_POINTS
    return {"volume": volume, "volume_se": volume_se, "inertia": inertia.tolist(),
            "com": (sums * box_volume / n_total / volume).tolist(),
            "area": area, "area_se": math.sqrt(area_var),
            "intersection_volume": box_volume * inter_e / n_total}


def fit(k, eta, zeta, seed=1):
    """The best layout of k spheres (largest IoU), described by describe()."""
    axes = semi_axes(eta, zeta)
    best = None
    for layout in LAYOUTS[k]:
        params, score = fit_layout(layout, axes, seed)
        if best is None or score > best[2]:
            best = (layout, params, score)
    layout, params, score = best
    clump = describe(layout, params, eta, zeta)
    clump["fit_iou_octant"] = score
    clump["fit"] = {"points": FIT_POINTS, "method": "differential_evolution on the IoU, Sobol "
                    "points in the positive octant, seed %d" % seed}
    return clump


def describe(layout, params, eta, zeta):
    """The clump of these parameters: spheres, union volume, area, inertia and their errors
    against the ellipsoid."""
    axes = semi_axes(eta, zeta)
    centres, radii, orbit = spheres_of(layout, params)
    props = union_properties(centres, radii, axes)
    v_e = 4.0 / 3.0 * math.pi * np.prod(axes)
    a_e = ellipsoid_area(axes)
    v_u = props["volume"]
    return {"k": len(radii), "eta": eta, "zeta": zeta, "semi_axes": axes.tolist(),
            "layout": layout, "params": list(map(float, params)), "centres": centres.tolist(),
            "radii": radii.tolist(), "orbit": orbit.tolist(),
            "iou": props["intersection_volume"] / (v_u + v_e - props["intersection_volume"]),
            "ellipsoid_volume": v_e, "ellipsoid_area": a_e,
            "volume": v_u, "volume_se": props["volume_se"],
            "volume_error": v_u / v_e - 1, "volume_error_se": props["volume_se"] / v_e,
            "area": props["area"], "area_se": props["area_se"],
            "area_error": props["area"] / a_e - 1, "area_error_se": props["area_se"] / a_e,
            "mass": v_u, "com": props["com"], "inertia": props["inertia"]}


def write_files(base, clump):
    """base.mol, base.coeff, base.walls and base.json of a clump."""
    write_molecule(base + ".mol", clump)
    write_coefficients(base + ".coeff", base + ".walls", base + ".groups", clump)
    with open(base + ".json", "w") as f:
        json.dump(clump, f, indent=1)


def write_molecule(path, clump):
    centres, radii, orbit = (np.array(clump[key]) for key in ("centres", "radii", "orbit"))
    sphere_vol = 4.0 / 3.0 * np.pi * radii ** 3
    masses = clump["mass"] * sphere_vol / sphere_vol.sum()    # the union's mass, shared by volume
    ixx, iyy, izz = clump["inertia"][:3]
    with open(path, "w") as f:
        f.write("# clump of %d spheres fitted to the ellipsoid eta %g zeta %g (bench/clumps/"
                "fit_clumps.py); mass, com, inertia: the union at density 1\n\n"
                % (clump["k"], clump["eta"], clump["zeta"]))
        f.write("%d atoms\n%.10g mass\n0 0 0 com\n" % (len(radii), clump["mass"]))
        # the principal axes are x, y, z (three mirror planes): the products are zero
        f.write("%.10g %.10g %.10g 0 0 0 inertia\n\n" % (ixx, iyy, izz))
        f.write("Coords\n\n")
        for i, c in enumerate(centres):
            f.write("%d %.10g %.10g %.10g\n" % (i + 1, *c))
        f.write("\nTypes\n\n")
        for i, o in enumerate(orbit):
            f.write("%d %d\n" % (i + 1, o + 1))
        f.write("\nDiameters\n\n")
        for i, r in enumerate(radii):
            f.write("%d %.10g\n" % (i + 1, 2 * r))
        f.write("\nMasses\n\n")
        for i, m in enumerate(masses):
            f.write("%d %.10g\n" % (i + 1, m))


def orbit_radii(clump):
    radii, orbit = np.array(clump["radii"]), np.array(clump["orbit"])
    return [float(radii[orbit == o][0]) for o in range(orbit.max() + 1)]


def write_coefficients(coeff_path, walls_path, groups_path, clump):
    """Our Hertz law F = kn xi^3/2 + K xi^1/2 dxi/dt holds for every pair of spheres, whatever
    their radii: pair granular's hertz is kn_g sqrt(R*) xi^3/2 and its viscoelastic damping
    eta_n0 m* sqrt(R*) xi^1/2 dxi/dt, so per pair of types kn_g = kn / sqrt(R*) and
    eta_n0 = K / (m* sqrt(R*)) (m* of two bodies: the pair uses the rigid bodies' masses).
    The wall has R* = r and m* = the body mass; fix wall/gran has one law per fix, so there
    is one per sphere type, on a group of that type (groups_path adds new atoms to them)."""
    r = orbit_radii(clump)
    with open(coeff_path, "w") as f:
        f.write("# pair granular per type pair for clump_k%d (fit_clumps.py); needs kn K kt mu "
                "mstar\n" % clump["k"])
        for i in range(len(r)):
            for j in range(i, len(r)):
                rs = r[i] * r[j] / (r[i] + r[j])
                f.write("pair_coeff %d %d hertz $(v_kn/sqrt(%.10g)) $(v_K/(v_mstar*sqrt(%.10g))) "
                        "damping viscoelastic tangential linear_history ${kt} 0.0 ${mu}\n"
                        % (i + 1, j + 1, rs, rs))
    with open(walls_path, "w") as f:
        f.write("# the floor per type for clump_k%d (fit_clumps.py); needs kn K kt mu mbody\n"
                % clump["k"])
        for i, ri in enumerate(r):
            f.write("group floortype%d type %d\n" % (i + 1, i + 1))
        for i, ri in enumerate(r):
            f.write("fix ground%d floortype%d wall/gran granular hertz $(v_kn/sqrt(%.10g)) "
                    "$(v_K/(v_mbody*sqrt(%.10g))) damping viscoelastic tangential linear_history "
                    "${kt} 0.0 ${mu} zplane 0.0 NULL\n" % (i + 1, i + 1, ri, ri))
    with open(groups_path, "w") as f:
        f.write("# the floor groups of clump_k%d: re-run to add newly poured atoms\n" % clump["k"])
        for i in range(len(r)):
            f.write("group floortype%d type %d\n" % (i + 1, i + 1))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--k", type=int, nargs="+", default=[3, 7, 15])
    ap.add_argument("--eta", type=float, default=1.4)
    ap.add_argument("--zeta", type=float, default=1.8)
    ap.add_argument("--out", default=".")
    args = ap.parse_args(argv)
    bad = [k for k in args.k if k not in LAYOUTS]
    if bad:
        sys.exit("fit_clumps: no layout for k = %s (known: %s)"
                 % (bad, sorted(LAYOUTS)))
    if args.eta < 1 or args.zeta < 1:
        sys.exit("fit_clumps: eta and zeta must be >= 1 (a >= b >= c)")
    os.makedirs(args.out, exist_ok=True)
    for k in args.k:
        clump = fit(k, args.eta, args.zeta)
        write_files(os.path.join(args.out, "clump_k%d" % k), clump)
        print("k %2d layout %-6s IoU %.4f volume error %+.4f +- %.4f area error %+.4f +- %.4f"
              % (k, clump["layout"], clump["iou"], clump["volume_error"],
                 clump["volume_error_se"], clump["area_error"], clump["area_error_se"]))


if __name__ == "__main__":
    main()
