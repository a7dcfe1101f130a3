#!/usr/bin/env python3
"""The results table of a study (workflow/Snakefile): mean and standard error over seeds.

    study_table.py --results DIR DIR/points/<point>/s<seed>/packing.dat ...

<point> is eta<eta>_zeta<zeta>_dr<delta_r>_N<N>[_W<width>]_<law> (law: a name of the study's
config; width: the box's edge of a set that gives one, empty in the tables otherwise);
each deposit folder holds packing.dat, contact_histo.dat and orient_histo.dat of one seed.
Writes into DIR:
  deposits.csv   one row per deposit: the point, its seed and its numbers
  table.csv      one row per point: seeds and, for each quantity Q, Q_mean and Q_sem (the
                 standard error of the mean over seeds, nan for a single seed), and the files
                 of its seed-mean histograms (relative to DIR)
  points/<point>/contact_mean.dat, orient_mean.dat
                 theta, P(Omega(theta)) mean and standard error over seeds
"""
import argparse
import csv
import math
import os
import re
import sys
from collections import defaultdict

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _paths  # noqa: E402,F401  (tools/_paths.py: the topic folders on sys.path)
from deposit_run import read_histo, read_packing  # noqa: E402

KEYS = ["eta", "zeta", "delta_r", "N", "width", "law"]
# the force measures (K0 ... a_f) are nan for deposits whose packing.dat predates them; the
# window's length and the window means' standard errors (*_se) for those before the window
# (window_steps 0: a snapshot of the bed at rest, which still rings); np: the deposit's ranks
WINDOW = ["sigma_xx", "sigma_yy", "sigma_zz", "K0", "a_n", "a_f"]
QUANTITIES = (["phi", "Z", "Z_no_rattlers", "rattler_fraction", "fabric_anisotropy",
               "nematic_S", "Qzz", "Nslab", "steps", "wall_seconds", "np", "K0",
               "fabric_anisotropy_force", "a_n", "a_f", "sigma_xx", "sigma_yy", "sigma_zz",
               "window_steps"] + [q + "_se" for q in WINDOW])
MEANS = [q for q in QUANTITIES if not q.endswith("_se")]    # table.csv's columns
HISTOGRAMS = {"contact_histo": "contact_mean.dat", "orient_histo": "orient_mean.dat"}


def point_width(point):
    """the box edge a point's name gives (_W<width> after its N), or "" (in.deposit's default)"""
    m = re.search(r"_N[0-9]+_W([0-9.]+)_", point)
    return float(m.group(1)) if m else ""


def deposit_row(packing_path):
    folder = os.path.dirname(os.path.abspath(packing_path))
    point = os.path.basename(os.path.dirname(folder))
    pk = read_packing(packing_path)
    row = {"point": point, "law": point.rsplit("_", 1)[1], "seed": int(pk["seed"]),
           "eta": pk["eta"], "zeta": pk["zeta"], "delta_r": pk["delta_r"], "N": int(pk["N"]),
           "width": point_width(point),
           "rattler_fraction": pk["rattlers"] / pk["Nslab"] if pk["Nslab"] > 0 else math.nan,
           "resumed_from": int(pk["resumed_from"]) if "resumed_from" in pk else "",
           # "" for a resumed deposit whose earlier segments the runner did not yet count
           "earlier_segments_seconds": pk.get("earlier_segments_seconds", ""),
           "at_rest": pk.get("at_rest", 1) == 1}    # older packing.dat: written at rest only
    for q in QUANTITIES:
        row.setdefault(q, pk.get(q, math.nan))
    row["window_steps"] = int(pk.get("window_steps", 0))
    row["folder"] = folder
    return row


def mean_sem(values):
    a = np.asarray(values, float)
    sem = a.std(ddof=1) / math.sqrt(len(a)) if len(a) > 1 else math.nan
    return a.mean(), sem


def write_mean_histogram(rows, name, path):
    curves = [read_histo(os.path.join(r["folder"], name + ".dat")) for r in rows]
    theta = np.asarray(curves[0][0])
    p = np.asarray([c[1] for c in curves])
    sem = p.std(axis=0, ddof=1) / math.sqrt(len(p)) if len(p) > 1 else np.full(len(theta), np.nan)
    with open(path, "w") as f:
        f.write("# theta P_mean P_sem over %d seeds\n" % len(p))
        for t, m, e in zip(theta, p.mean(axis=0), sem):
            f.write("%.6f %.6e %.6e\n" % (t, m, e))


def write_csv(path, columns, rows):
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    os.replace(path + ".tmp", path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--results", required=True, help="the study's results folder")
    ap.add_argument("packing", nargs="+", help="packing.dat of every deposit")
    args = ap.parse_args(argv)
    results = os.path.abspath(args.results)
    deposits = sorted((deposit_row(p) for p in args.packing),
                      key=lambda r: tuple(r[k] for k in KEYS) + (r["seed"],))
    moving = [r["folder"] for r in deposits if not r["at_rest"]]
    if moving:
        sys.exit("study_table: ERROR: deposits not at rest (maxchunks ran out), not a result: "
                 + " ".join(moving))
    write_csv(os.path.join(results, "deposits.csv"),
              ["point"] + KEYS + ["seed"] + QUANTITIES + ["resumed_from", "earlier_segments_seconds"],
              deposits)

    by_point = defaultdict(list)
    for r in deposits:
        by_point[r["point"]].append(r)
    table = []
    for point, rows in by_point.items():
        entry = {k: rows[0][k] for k in ["point"] + KEYS}
        entry["seeds"] = len(rows)
        for q in MEANS:
            entry[q + "_mean"], entry[q + "_sem"] = mean_sem([r[q] for r in rows])
        for histo, fname in HISTOGRAMS.items():
            rel = os.path.join("points", point, fname)
            write_mean_histogram(rows, histo, os.path.join(results, rel))
            entry[histo] = rel
        table.append(entry)
    table.sort(key=lambda e: tuple(e[k] for k in KEYS))
    columns = (["point"] + KEYS + ["seeds"]
               + [q + s for q in MEANS for s in ("_mean", "_sem")] + list(HISTOGRAMS))
    write_csv(os.path.join(results, "table.csv"), columns, table)
    print("study_table: %d deposits, %d points -> %s" % (len(deposits), len(table),
                                                           os.path.join(results, "table.csv")))


if __name__ == "__main__":
    main()
