#!/usr/bin/env python3
"""The deposit as a porous medium: porosity, specific surface, pore sizes, permeability.

    ./ellipsoid-dep pores RUN_DIR [--voxel H] [--flow [--flow-voxel H] [--flow-box L]
                                                     [--flow-box-at X,Y]] [--quiet]
    ./ellipsoid-dep python tools/pores/pores.py --compare OUT.png RUN_DIR [RUN_DIR ...]

Reads RUN_DIR/deposit.dump (the runner's OVITO dump: id type x y z quatw quati quatj quatk
semi_a_x semi_a_y semi_a_z ...) and RUN_DIR/packing.dat (the slab zlo, zhi and phi of compute
packing/ellipsoid) and writes
    RUN_DIR/pores.json         every number below (definitions: doc/howto_pores.md)
    RUN_DIR/pores.png          slices of the pore space coloured by local thickness, the pore
                               size distribution and the porosity profile
    RUN_DIR/pores_voxels.raw   the voxel image of the slab, uint8 (1 solid, 0 pore), x fastest,
    RUN_DIR/pores_voxels.mhd   then y, then z, with its MetaImage header (spacing, origin)
Exact from the particles: porosity (closed-form ellipsoid-slab volumes) and specific surface
(Carlson's R_G for whole particles, a converged quadrature over the cut ones). From the voxel
image (periodic in x and y): pore size distribution (local thickness from the Euclidean
distance transform), connectivity from the bottom to the top of the slab, and the voxel
porosity; these are computed at the voxel size H and at 2 H to show their convergence.
Kozeny-Carman permeability k = porosity^3 / (5 S_v^2) from the exact values. With --flow:
k_xx, k_yy, k_zz from Stokes-flow solves with OpenFOAM (pore_flow.py) on a box of side
5 d cut out of the slab at three voxel sizes, extrapolated to a vanishing voxel
(pore_flow_domain.py, pore_flow_fit.py); --flow-voxel H: at H alone.

The parts, beside this file in tools/pores/: reading the particles and the slab in
pore_input.py, exact volumes and areas in pore_surface.py, the voxel view (pore sizes,
connectivity, tortuosity) in pore_voxels.py, the largest inscribed ball in pore_inscribed.py,
the flow solve in pore_flow.py (one image), pore_flow_domain.py (the domain and the voxels) and
pore_flow_fit.py (the extrapolation), the picture in pore_picture.py.

--compare reads pores.json (running the analysis where it is missing) and packing.dat of
several run folders and plots porosity, specific surface and permeability against the shape
along the lines eta = zeta, prolate (zeta = 1, vs eta) and oblate (eta = 1, vs zeta).
"""
import argparse
import csv
import json
import math
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _paths  # noqa: E402,F401  (tools/_paths.py: the topic folders on sys.path)
from deposit_run import read_packing  # noqa: E402
# Particles and rotation_matrices: pores' names for its callers too
from pore_input import Particles, read_dump, read_slab, rotation_matrices  # noqa: E402,F401
from pore_picture import plot  # noqa: E402
from pore_surface import (KOZENY_CONSTANT, kozeny_carman, slab_fraction,  # noqa: E402
                          slab_surface)
from pore_flow_domain import (FLOW_BOX, FLOW_OFFSET_COUNT, FLOW_VOXEL_FRACTIONS,  # noqa: E402
                              flow_permeability)
from pore_voxels import analyse_voxels  # noqa: E402
from study_stats import Pooled  # noqa: E402

VOXEL_FRACTION = 0.125    # default voxel size: this fraction of the smallest semi-axis
MAX_VOXEL_FRACTION = 0.5  # larger voxels cannot resolve the thinnest particle dimension


class Progress:
    """progress lines on stderr for large deposits (silent when quiet or small)"""

    def __init__(self, quiet=False):
        self.quiet = quiet
        self.t0 = time.time()

    def __call__(self, msg):
        if not self.quiet:
            print("[pores %6.1f s] %s" % (time.time() - self.t0, msg), file=sys.stderr,
                  flush=True)


# ---------------------------------------------------------------------------------------------
# the analysis


def analyse(particles, box, zlo, zhi, voxel=None, progress=None, voxel_fraction=VOXEL_FRACTION):
    """every pore-space quantity of the slab [zlo, zhi]; voxel quantities at voxel and 2 voxel.
    Keys starting with '_' hold arrays for the picture and the image file."""
    progress = progress or Progress(quiet=True)
    if not zhi > zlo:
        raise ValueError("the slab needs zhi > zlo")
    smallest = float(particles.semi.min())
    if voxel is None:
        voxel = voxel_fraction * smallest
    if not voxel > 0:
        raise ValueError("the voxel size must be > 0")
    if voxel > MAX_VOXEL_FRACTION * smallest:
        raise ValueError("voxel %.4g too large: at most %g x the smallest semi-axis (%.4g)"
                         % (voxel, MAX_VOXEL_FRACTION, MAX_VOXEL_FRACTION * smallest))
    area_xy = (box[0, 1] - box[0, 0]) * (box[1, 1] - box[1, 0])
    v_slab = area_xy * (zhi - zlo)
    v_solid = float((slab_fraction(particles, zlo, zhi) * particles.volumes).sum())
    porosity = 1.0 - v_solid / v_slab
    if porosity < 0:
        raise ValueError("the particles' volume in the slab exceeds the slab's (porosity %.4g): "
                         "they overlap, this is not a deposit" % porosity)
    surface, quad_change, ncut = slab_surface(particles, zlo, zhi)
    s_v = surface / v_slab
    progress("exact: porosity %.5f, specific surface %.5g" % (porosity, s_v))

    fine = analyse_voxels(particles, box, zlo, zhi, voxel, progress)
    coarse = analyse_voxels(particles, box, zlo, zhi, 2 * voxel, progress, check=False)
    compared = ("porosity_voxel", "largest_inscribed_radius", "largest_inscribed_radius_voxel",
                "mean_pore_radius", "connected_z",
                "connected_pore_fraction", "geometric_tortuosity")
    result = {
        "slab": {"zlo": zlo, "zhi": zhi, "area_xy": area_xy, "volume": v_slab},
        "particles": len(particles),
        "porosity": porosity,
        "solid_volume": v_solid,
        "specific_surface": s_v,
        "specific_surface_per_solid_volume": surface / v_solid if v_solid > 0 else 0.0,
        "surface_area": surface,
        "surface_cut_particles": ncut,
        "surface_quadrature_relative_change": quad_change,
        "kozeny_carman_permeability": kozeny_carman(porosity, s_v),
        "kozeny_carman": {"formula": "k = porosity^3 / (K S_v^2), S_v = specific_surface",
                          "K": KOZENY_CONSTANT},
        "hydraulic_radius": porosity / s_v if s_v > 0 else math.inf,
        "voxel_size": fine["voxel_size"],
        "voxel_default_fraction_of_smallest_semi_axis": voxel_fraction,
        "convergence": {"voxel_size": [fine["voxel_size"], coarse["voxel_size"]]},
    }
    for key in ("voxel_spacing", "grid", "porosity_voxel", "largest_inscribed_radius",
                "largest_inscribed_centre", "largest_inscribed_radius_voxel", "mean_pore_radius",
                "connected_z", "connected_pore_fraction", "geometric_tortuosity",
                "pore_size_distribution", "margin"):
        result[key] = fine[key]
    for key in compared:
        result["convergence"][key] = [fine[key], coarse[key]]
    result["convergence"]["porosity_exact"] = porosity
    for key in ("_solid_slab", "_thickness", "_grid"):
        result[key] = fine[key]
    return result


def write_voxel_image(result, run_dir):
    """uint8 raw stack (1 solid, 0 pore; x fastest, then y, then z) + MetaImage header"""
    solid = result["_solid_slab"]
    grid = result["_grid"]
    raw = os.path.join(run_dir, "pores_voxels.raw")
    solid.astype(np.uint8).transpose(2, 1, 0).tofile(raw)
    origin = (grid.origin[0], grid.origin[1], result["slab"]["zlo"])
    with open(os.path.join(run_dir, "pores_voxels.mhd"), "w") as f:
        f.write("ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
                "DimSize = %d %d %d\nElementSpacing = %.17g %.17g %.17g\n"
                "Offset = %.17g %.17g %.17g\nElementType = MET_UCHAR\n"
                "ElementDataFile = pores_voxels.raw\n"
                % (solid.shape + tuple(grid.spacing) + origin))
    return {"file": "pores_voxels.raw", "header": "pores_voxels.mhd", "dtype": "uint8",
            "values": {"solid": 1, "pore": 0}, "order": "x fastest, then y, then z",
            "shape_xyz": list(solid.shape), "spacing": list(grid.spacing), "origin": list(origin),
            "periodic": ["x", "y"]}


def public(result):
    return {k: v for k, v in result.items() if not k.startswith("_")}


def run_folder(run_dir, voxel=None, quiet=False, picture=True, flow=False, flow_voxel=None,
               voxel_fraction=VOXEL_FRACTION, flow_box=FLOW_BOX, flow_box_at=None,
               flow_offsets=FLOW_OFFSET_COUNT):
    """analyse RUN_DIR/deposit.dump in the slab of RUN_DIR/packing.dat; write pores.json,
    the voxel image and pores.png (with flow: the permeability tensor's diagonal from the
    flow solve too, at the default voxels and extrapolated, or at flow_voxel alone); return
    the public result"""
    progress = Progress(quiet)
    for name in ("deposit.dump", "packing.dat"):
        if not os.path.isfile(os.path.join(run_dir, name)):
            raise ValueError("%s: no %s (not a finished deposit's run folder)" % (run_dir, name))
    particles, box = read_dump(os.path.join(run_dir, "deposit.dump"))
    pk = read_slab(run_dir)
    progress("%d particles, slab z in [%g, %g]" % (len(particles), pk["zlo"], pk["zhi"]))
    # the flow first: its bad input (no pore path, a voxel too large) ends the run early
    k = (flow_permeability(particles, box, pk["zlo"], pk["zhi"],
                           None if flow_voxel is None else [flow_voxel], progress,
                           side=flow_box, at=flow_box_at, offset_count=flow_offsets)
         if flow else None)
    result = analyse(particles, box, pk["zlo"], pk["zhi"], voxel, progress, voxel_fraction)
    if "phi" in pk:
        result["porosity_check"] = {"one_minus_phi_packing_dat": 1.0 - pk["phi"],
                                    "difference": result["porosity"] - (1.0 - pk["phi"])}
    result["voxel_image"] = write_voxel_image(result, run_dir)
    if k is not None:
        result["permeability_flow"] = k
    for key in ("eta", "zeta", "delta_r", "N", "seed", "at_rest"):    # at_rest 0: said
        if key in pk:
            result[key] = pk[key]
    if picture:
        title = "eta %g zeta %g" % (pk.get("eta", 0), pk.get("zeta", 0))
        plot(result, particles, os.path.join(run_dir, "pores.png"), title)
    out = public(result)
    with open(os.path.join(run_dir, "pores.json"), "w") as f:
        json.dump(out, f, indent=1)
    return out


# ---------------------------------------------------------------------------------------------
# several runs against the shape


SHAPE_LINES = (("eta = zeta", lambda e, z: e == z, 0, "o-"),
               ("prolate, zeta = 1 (vs eta)", lambda e, z: z == 1.0, 0, "s--"),
               ("oblate, eta = 1 (vs zeta)", lambda e, z: e == 1.0, 1, "^-."))
COMPARED = (("porosity", "porosity"),
            ("specific_surface", r"specific surface $S_v$ (1 / length)"),
            ("kozeny_carman_permeability", r"$k_{KC} = \epsilon^3 / (5 S_v^2)$ (length$^2$)"))


def compare(run_dirs, out_png, voxel=None, quiet=False):
    """porosity, specific surface and Kozeny-Carman permeability against the shape along the
    study's lines; seeds of one shape are averaged; error bars and the table's *_sem: the
    seed SD pooled per group of shapes (tools/study/study_stats.py) / sqrt(the shape's seeds)"""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    by_shape = {}
    for d in run_dirs:
        path = os.path.join(d, "pores.json")
        if os.path.exists(path):
            with open(path) as f:
                res = json.load(f)
        else:
            res = run_folder(d, voxel=voxel, quiet=quiet, picture=False)
        pk = read_packing(os.path.join(d, "packing.dat"))
        if not all(isinstance(pk.get(k), float) for k in ("eta", "zeta")):
            raise ValueError("%s/packing.dat: no eta or zeta" % d)
        by_shape.setdefault((pk["eta"], pk["zeta"]), []).append(res)
    fig, axes = plt.subplots(1, len(COMPARED), figsize=(4.2 * len(COMPARED), 3.6))
    table = []
    pooled = {k: Pooled({s: [r[k] for r in rs] for s, rs in by_shape.items()})
              for k, _ in COMPARED}
    for ax, (key, label) in zip(axes, COMPARED):
        for name, on_line, which, style in SHAPE_LINES:
            shapes = sorted((s for s in by_shape if on_line(*s)), key=lambda s: s[which])
            if not shapes:
                continue
            e = [pooled[key].se(s) for s in shapes]    # None: no group with two seeds
            ax.errorbar([s[which] for s in shapes], [pooled[key].mean(s) for s in shapes],
                        yerr=None if all(v is None for v in e) else
                        [0.0 if v is None else v for v in e], fmt=style, capsize=3, label=name)
        ax.set(xlabel=r"aspect ratio ($\eta$ or $\zeta$)", ylabel=label)
        ax.legend(fontsize=7)
    for (eta, zeta), rs in sorted(by_shape.items()):
        row = {"eta": eta, "zeta": zeta, "runs": len(rs)}
        for k, _ in COMPARED:
            se = pooled[k].se((eta, zeta))
            row[k] = pooled[k].mean((eta, zeta))
            row[k + "_sem"] = "" if se is None else se
        table.append(row)
    fig.tight_layout()
    fig.savefig(out_png, dpi=120)
    plt.close(fig)
    with open(os.path.splitext(out_png)[0] + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(table[0]) if table else ["eta", "zeta", "runs"])
        w.writeheader()
        w.writerows(table)
    return table


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dirs", nargs="+", metavar="RUN_DIR")
    ap.add_argument("--voxel", type=float, default=None,
                    help="voxel size (default %g x the smallest semi-axis)" % VOXEL_FRACTION)
    ap.add_argument("--voxel-fraction", type=float, default=VOXEL_FRACTION,
                    help="without --voxel: the voxel as this fraction of the smallest semi-axis "
                         "(default %g)" % VOXEL_FRACTION)
    ap.add_argument("--compare", metavar="OUT.png", default=None,
                    help="plot several runs against the shape instead (and write the table "
                         "of means and standard errors to OUT.csv)")
    ap.add_argument("--flow", action="store_true",
                    help="also the permeability tensor's diagonal from a Stokes-flow solve "
                         "(OpenFOAM; ./ellipsoid-dep pores installs it on first use)")
    ap.add_argument("--flow-voxel", type=float, default=None,
                    help="one voxel size for the flow solve, no extrapolation (default: %s x "
                         "the smallest semi-axis, extrapolated to a vanishing voxel)"
                         % ", ".join("%.4g" % f for f in FLOW_VOXEL_FRACTIONS))
    ap.add_argument("--flow-box", type=float, default=FLOW_BOX, metavar="L",
                    help="the flow domain: a box of side L d cut out of the slab (default %g; "
                         "0: the whole slab)" % FLOW_BOX)
    ap.add_argument("--flow-box-at", default=None, metavar="X,Y",
                    help="the cut box's centre (default: the box's centre)")
    ap.add_argument("--flow-offsets", type=int, default=FLOW_OFFSET_COUNT, metavar="M",
                    help="each flow voxel's k is the mean over M offsets of the grid (1, 2 or "
                         "4; default %d; 1: the grid on the domain's corner)"
                         % FLOW_OFFSET_COUNT)
    ap.add_argument("--quiet", action="store_true", help="no progress lines")
    args = ap.parse_args(argv)
    import pore_flow
    try:
        report(ap, args)
    except (ValueError, RuntimeError, OSError, pore_flow.FlowError) as e:
        print("pores: ERROR: %s" % e, file=sys.stderr)
        sys.exit(2)
    except MemoryError:
        print("pores: ERROR: out of memory; give a larger --voxel or --flow-voxel",
              file=sys.stderr)
        sys.exit(2)


def report(ap, args):
    if args.compare:
        for row in compare(args.run_dirs, args.compare, args.voxel, args.quiet):
            print("eta %-5g zeta %-5g runs %d  porosity %.4f  S_v %.4f  k_KC %.4g" % (
                row["eta"], row["zeta"], row["runs"], row["porosity"], row["specific_surface"],
                row["kozeny_carman_permeability"]))
        print("pores: wrote %s" % args.compare)
        return
    if len(args.run_dirs) != 1:
        ap.error("one RUN_DIR (or --compare OUT.png RUN_DIR ...)")
    d = args.run_dirs[0]
    if not os.path.isdir(d):
        raise ValueError("%s: no such folder" % d)
    if not 0 < args.voxel_fraction <= MAX_VOXEL_FRACTION:
        raise ValueError("--voxel-fraction %g: needs 0 < fraction <= %g"
                         % (args.voxel_fraction, MAX_VOXEL_FRACTION))
    if not args.flow_box >= 0:
        raise ValueError("--flow-box %g: needs L >= 0 (0: the whole slab)" % args.flow_box)
    at = None
    if args.flow_box_at is not None:
        try:
            at = [float(v) for v in args.flow_box_at.split(",")]
        except ValueError:
            at = []
        if len(at) != 2:
            raise ValueError("--flow-box-at %s: needs X,Y" % args.flow_box_at)
    r = run_folder(d, args.voxel, args.quiet, flow=args.flow, flow_voxel=args.flow_voxel,
                   voxel_fraction=args.voxel_fraction, flow_box=args.flow_box, flow_box_at=at,
                   flow_offsets=args.flow_offsets)
    c = r["convergence"]
    print("pores: %s (%d particles, slab z in [%.4g, %.4g])"
          % (d, r["particles"], r["slab"]["zlo"], r["slab"]["zhi"]))
    print("  porosity            %.5f" % r["porosity"] + (
        "   (1 - phi of packing.dat: %.5f)" % r["porosity_check"]["one_minus_phi_packing_dat"]
        if "porosity_check" in r else ""))
    print("  specific surface    %.5g per unit length (%.5g per solid volume)"
          % (r["specific_surface"], r["specific_surface_per_solid_volume"]))
    print("  Kozeny-Carman k     %.4g  (K = %g)" % (r["kozeny_carman_permeability"],
                                                   KOZENY_CONSTANT))
    print("  voxel H, 2H         %.4g, %.4g" % tuple(c["voxel_size"]))
    print("  porosity (voxels)   %.5f, %.5f" % tuple(c["porosity_voxel"]))
    print("  mean pore radius    %.4g, %.4g" % tuple(c["mean_pore_radius"]))
    print("  largest pore radius %.4g, %.4g" % tuple(c["largest_inscribed_radius"]))
    print("  connected in z      %s, %s" % tuple(c["connected_z"]))
    print("  geometric tortuosity %s, %s" % tuple(
        "none" if t is None else "%.4f" % t for t in c["geometric_tortuosity"]))
    if "permeability_flow" in r:
        print_flow(r["permeability_flow"], r["porosity"])
    print("  files: pores.json pores.png pores_voxels.raw pores_voxels.mhd")


def print_flow(k, porosity):
    dom = k["domain"]
    print("  flow domain         %s %s d (the slab's exact porosity %.4f)" % (
        dom["kind"], " x ".join("%.3g" % s for s in dom["sides_d"]), porosity))
    for r in k["resolutions"]:
        print("  flow at d/%-5.3g     xx %.4g  yy %.4g  zz %.4g  (xx+yy)/2zz %.4f  (pores %.4f, "
              "%d + %d cells)" % (r["voxels_per_d"], r["xx"], r["yy"], r["zz"],
                                  r["anisotropy_xx_zz"], r["porosity_voxel"], r["cells"]["xx"],
                                  r["cells"]["zz"]))
    if "extrapolation" in k:
        e = k["extrapolation"]
        print("  flow k0 (d^2; between the line in h^2 and the finest voxel)")
        print("                      " + "  ".join(
            "%s %.4g +- %.2g (%.4g to %.4g)" % (a, k[a], k[a + "_error"], e[a]["k0_fixed_p"],
                                                e[a]["k_finest"])
            for a in ("xx", "yy", "zz")))
        print("  anisotropy k0       %.4f +- %.2g" % (k["anisotropy_xx_zz"],
                                                     k["anisotropy_xx_zz_error"]))
    print("  k / Kozeny-Carman   xx %.3f  yy %.3f  zz %.3f" % tuple(
        k["ratio_to_kozeny_carman"][a] for a in ("xx", "yy", "zz")))


if __name__ == "__main__":
    main()
