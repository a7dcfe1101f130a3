#!/usr/bin/env python3
"""Permeability of deposits along the study's lines from the flow solve (doc/howto_pores.md).

    ./ellipsoid-dep python tools/pores/pore_flow_lines.py --out results/flow RUN_DIR [RUN_DIR ...]
        [--flow-voxels-per-d N1,N2,N3] [--flow-box L] [--directions xx,zz]

For each run folder (deposit.dump + packing.dat, read only) the flow solve of
pore_flow_domain.flow_permeability at its defaults (a box of side 5 d cut out of the slab, three
voxels, extrapolated to a vanishing voxel), or at the voxels d / N given (three or more:
extrapolated; one: that voxel alone; flat shapes at the default voxels, fractions of the
smallest semi-axis, need (eta zeta^2)^(1/3) times more voxels per d than spheres in each
direction) writes OUT/<folder name>.json
(skipped when it exists: one command per deposit, and reruns only add what is missing; each
solve is kept in OUT/<folder name>.solves/ as it finishes, so a stopped run resumes); then
OUT/flow_lines.csv (one row per deposit solved in OUT, by this command or an earlier one: eta,
zeta, seed, porosity, k_xx, k_zz in d^2 with their errors, the anisotropy, the ratio to Kozeny-
Carman, the finest voxel's cells, the iterations, the seconds summed over the solves: wall and
solver CPU) and OUT/flow_lines.png (k_xx, k_zz, anisotropy, k_zz / k_KC and k_xx / k_KC against
the aspect ratio on each line: the seeds and their mean with its error,
tools/study/study_flow_lines.py).
"""
import argparse
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _paths  # noqa: E402,F401  (tools/_paths.py: the topic folders on sys.path)
import pore_flow_domain  # noqa: E402
import pore_surface  # noqa: E402
import pores  # noqa: E402
import study_flow_lines  # noqa: E402
import study_stats  # noqa: E402


def solve_folder(folder, out, voxels_per_d, directions, side):
    path = os.path.join(out, os.path.basename(os.path.normpath(folder)) + ".json")
    row = None
    if os.path.exists(path):
        with open(path) as f:
            row = json.load(f)
        if "ratio_to_kozeny_carman" in row["flow"]:
            return row
    particles, box = pores.read_dump(os.path.join(folder, "deposit.dump"))
    d = pore_flow_domain.volume_diameter(particles)
    if row is not None:    # solved before the domain's own medium was part of the solve
        pore_flow_domain.add_medium(row["flow"], particles, box)
        row.pop("k_kozeny_carman", None)    # the slab's, not the domain's
    else:
        pk = pores.read_slab(folder)
        zlo, zhi = pk["zlo"], pk["zhi"]
        k = pore_flow_domain.flow_permeability(
            particles, box, zlo, zhi, voxels_per_d and [d / n for n in voxels_per_d],
            pores.Progress(), directions=directions, side=side,
            solved=path[:-len(".json")] + ".solves")
        v_slab = (box[0, 1] - box[0, 0]) * (box[1, 1] - box[1, 0]) * (zhi - zlo)
        solid = (pore_surface.slab_fraction(particles, zlo, zhi) * particles.volumes).sum()
        row = {"folder": folder, "eta": pk.get("eta"), "zeta": pk.get("zeta"),
               "seed": pk.get("seed"), "porosity": 1.0 - solid / v_slab,
               "specific_surface": pore_surface.slab_surface(particles, zlo, zhi)[0] / v_slab,
               "flow": k}
    with open(path, "w") as f:
        json.dump(row, f, indent=1)
    return row


def table(rows):
    out = []
    for r in rows:
        finest = r["flow"]["resolutions"][-1]
        row = study_flow_lines.deposit_row(r)
        row.update({"voxels_per_d": " ".join("%.3g" % q["voxels_per_d"]
                                             for q in r["flow"]["resolutions"]),
                    "cells_xx": finest["cells"]["xx"], "cells_zz": finest["cells"]["zz"],
                    "iterations": " ".join("%s:%d" % kv
                                           for kv in sorted(finest["iterations"].items()))})
        for key in ("solve_seconds", "solver_cpu_seconds"):
            row[key] = round(row[key])
        out.append(row)
    return sorted(out, key=lambda r: (r["eta"], r["zeta"], r["seed"]))


def plot(rows, path):
    """k_xx, k_zz, k_xx / k_zz, k_zz / k_KC and k_xx / k_KC against the line's aspect ratio, one
    colour per line: the seeds (open) and their mean with its error (statistical and
    extrapolation's combined)"""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    panels = (("k_xx", r"$k_{xx}$ ($d^2$)"), ("k_zz", r"$k_{zz}$ ($d^2$)"),
              ("anisotropy", r"$k_{xx} / k_{zz}$"),
              ("k_zz_over_kozeny_carman", r"$k_{zz} / k_{KC}$"),
              ("k_xx_over_kozeny_carman", r"$k_{xx} / k_{KC}$"))
    means = study_flow_lines.shape_means(rows)
    fig, axes = plt.subplots(1, len(panels), figsize=(4.0 * len(panels), 3.4))
    for ax, (key, label) in zip(axes, panels):
        for c, (name, (_, axis)) in enumerate(study_stats.LINES.items()):
            i = 1 if axis == "zeta" else 0
            shapes = sorted((s for s in means if s != "pooled" and study_stats.on_line(name, *s)),
                            key=lambda s: s[i])
            if not shapes:
                continue
            seeds = [r for r in rows if study_stats.on_line(name, r["eta"], r["zeta"])]
            ax.plot([r[("eta", "zeta")[i]] for r in seeds], [r[key] for r in seeds], "o",
                    mfc="none", ms=4, color="C%d" % c)
            err = [math.hypot(means[s][key]["stat"] or 0.0, means[s][key]["sys"] or 0.0)
                   for s in shapes]
            ax.errorbar([s[i] for s in shapes], [means[s][key]["mean"] for s in shapes], err,
                        fmt="-", capsize=3, color="C%d" % c,
                        label="%s (x: %s)" % (name, "zeta" if i else "eta"))
        ax.set(xlabel="aspect ratio on the line", ylabel=label)
        ax.legend(fontsize=7)
    fig.suptitle("flow solve (OpenFOAM simpleFoam), voxels d/%s extrapolated, delta_r = 0"
                 % rows[0]["voxels_per_d"].replace(" ", ", d/"), fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dirs", nargs="+", metavar="RUN_DIR")
    ap.add_argument("--out", required=True, help="folder of the small outputs")
    ap.add_argument("--flow-voxels-per-d", default=None, metavar="N1,N2,N3",
                    help="voxels d / N instead of the default (fractions of the smallest "
                         "semi-axis); one N: that voxel alone, no extrapolation")
    ap.add_argument("--flow-box", type=float, default=pore_flow_domain.FLOW_BOX, metavar="L",
                    help="side of the cut box in d (0: the whole slab)")
    ap.add_argument("--directions", default="xx,zz")
    args = ap.parse_args(argv)
    per_d = None
    if args.flow_voxels_per_d:
        try:
            per_d = [float(n) for n in args.flow_voxels_per_d.split(",")]
        except ValueError:
            per_d = []
        if len(per_d) == 2 or not per_d or not all(n > 0 for n in per_d):
            ap.error("--flow-voxels-per-d %s: one N or three or more, all > 0"
                     % args.flow_voxels_per_d)
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for folder in args.run_dirs:
        try:
            rows.append(solve_folder(folder, args.out, per_d,
                                     tuple(args.directions.split(",")), args.flow_box))
        except (ValueError, RuntimeError, OSError) as e:    # RuntimeError: pore_flow.FlowError
            print("pore_flow_lines: %s skipped: %s" % (folder, e), file=sys.stderr)
    if not rows:
        sys.exit("pore_flow_lines: no deposit solved")
    for r in study_flow_lines.solved(args.out):    # earlier commands' deposits too
        if "ratio_to_kozeny_carman" not in r["flow"]:
            try:
                solve_folder(r["folder"], args.out, per_d, tuple(args.directions.split(",")),
                             args.flow_box)
            except (ValueError, RuntimeError, OSError) as e:
                sys.exit("pore_flow_lines: %s in %s has no flow domain medium yet and it cannot "
                         "be added: %s" % (r["folder"], args.out, e))
    t = table(study_flow_lines.solved(args.out))
    with open(os.path.join(args.out, "flow_lines.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(t[0]))
        w.writeheader()
        w.writerows(t)
    plot(t, os.path.join(args.out, "flow_lines.png"))
    for r in t:    # every deposit in OUT
        print("eta %-4g zeta %-4g seed %-3g  k_xx %.4g  k_zz %.4g  k_xx/k_zz %.3f  k_zz/k_KC %.3f"
              % (r["eta"], r["zeta"], r["seed"], r["k_xx"], r["k_zz"], r["anisotropy"],
                 r["k_zz_over_kozeny_carman"]))


if __name__ == "__main__":
    main()
