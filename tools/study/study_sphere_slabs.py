#!/usr/bin/python3
"""The spheres' contact normals near the floor and above it (doc/study.md, "The spheres' contact
normals near the floor"): whether the spheres' departure from isotropy is the floor's layering.

    ./ellipsoid-dep python tools/study/study_sphere_slabs.py --out results/study/sphere_slabs.csv RUN_DIR ...

Each run folder's deposit.dump (the runner's, with settings.json for its law and seed) is read
back and compute contact/histo (18 bins over [0, pi], a contact counted where its point lies)
measures the contact normals in a low slab, z in [1, 3.5] d, which holds the layers the floor
orders (the density profile's oscillations), and a high one, [3.5, 6] d. Per bin of the upper
half (the curve is symmetric about pi/2 by construction) the csv keeps 4 pi P - 1 and the
bin's contacts (its fraction x the samples), from which sphere_slabs_summary gives per law and
slab the pooled deviation, its Poisson error and Pearson's chi^2 against isotropy, scaled by
the Birge ratio where the seeds scatter beyond counting.
"""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np
from scipy import stats

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _paths  # noqa: E402,F401  (tools/_paths.py: the topic folders on sys.path)

SLABS = {"low": (1.0, 3.5), "high": (3.5, 6.0)}
BINS = 18
COLUMNS = ["law", "seed", "slab", "theta", "deviation", "contacts"]


def law_of(settings):
    return settings["tangential"].split()[0].replace("history", "coulomb")


def measure(run_dir):
    """csv rows of one deposit: per slab and upper-half bin, theta, 4 pi P - 1, contacts"""
    from remeasure_deposit import contacts_instance    # LAMMPS only to measure
    settings = json.load(open(os.path.join(run_dir, "settings.json")))
    rows = []
    lmp = contacts_instance(os.path.join(run_dir, "deposit.dump"))
    for name, (lo, hi) in SLABS.items():
        lmp.command("compute %s all contact/histo bins %d zlo %g zhi %g" % (name, BINS, lo, hi))
    lmp.command("run 0 post no")
    for name in SLABS:
        histo = np.array(lmp.numpy.extract_compute(name, 0, 2))    # theta, P, fraction
        samples = lmp.extract_compute(name, 0, 1)[8]
        for theta, p, fraction in histo[:BINS // 2, :3]:
            rows.append({"law": law_of(settings), "seed": settings["seed"], "slab": name,
                         "theta": "%.4f" % theta, "deviation": "%.5f" % (4 * math.pi * p - 1),
                         "contacts": "%.1f" % (fraction * samples)})
    lmp.close()
    return rows


def sphere_slabs_summary(rows):
    """{(law, slab): {seeds, theta, deviation, se, chi2, dof, p, seeds_chi2, seeds_dof, birge}}:
    the seeds' counts pooled per bin, deviation = counts / expected - 1 (expected: the
    isotropic share, counts / (1 + a seed's deviation), summed), its Poisson error sqrt(counts)
    / expected, Pearson's chi^2 against isotropy; the seeds against their pooled deviation
    (seeds_chi2 on (seeds - 1) (bins - 1) dof) and, where they scatter beyond counting, the
    Birge ratio that scales the errors and divides chi^2 before p"""
    groups = {}
    for r in rows:
        groups.setdefault((r["law"], r["slab"]), {}).setdefault(int(r["seed"]), []).append(r)
    out = {}
    for key, seeds in groups.items():
        dev = np.array([[float(r["deviation"]) for r in v] for v in seeds.values()])
        counts = np.array([[float(r["contacts"]) for r in v] for v in seeds.values()])
        expected = counts / (1 + dev)
        mean = counts.sum(0) / expected.sum(0) - 1
        se = np.sqrt(counts.sum(0)) / expected.sum(0)
        dof = dev.shape[1] - 1    # the normalisation fixes one combination of the bins
        fitted = (1 + mean) * expected    # each seed's counts at the pooled deviation
        seeds_chi2 = float(np.sum((counts - fitted) ** 2 / fitted))
        seeds_dof = (len(seeds) - 1) * dof
        birge = math.sqrt(seeds_chi2 / seeds_dof) if seeds_dof else None
        scale = max(1.0, birge or 1.0)
        chi2 = float(np.sum((counts.sum(0) - expected.sum(0)) ** 2 / expected.sum(0)))
        out[key] = {"seeds": sorted(seeds), "theta": [float(r["theta"]) for r in
                                                       next(iter(seeds.values()))],
                    "deviation": mean.tolist(), "se": (scale * se).tolist(),
                    "chi2": chi2 / scale ** 2, "dof": dof,
                    "p": float(stats.chi2.sf(chi2 / scale ** 2, dof)),
                    "seeds_chi2": seeds_chi2, "seeds_dof": seeds_dof, "birge": birge}
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True, help="the csv to write")
    ap.add_argument("runs", nargs="+", metavar="RUN_DIR", help="sphere deposits' run folders")
    args = ap.parse_args(argv)
    rows = []
    for run in args.runs:
        if not os.path.exists(os.path.join(run, "deposit.dump")):
            sys.exit("study_sphere_slabs: %s has no deposit.dump" % run)
        rows += measure(run)
        print("study_sphere_slabs: measured %s" % run, flush=True)
    with open(args.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)
    print("study_sphere_slabs: wrote %s" % args.out)


if __name__ == "__main__":
    main()
