"""doc/study.md's table of the viscous set's re-run (tools/study/study_doc.py): each deposit of
the study's viscous set (results/study/points/<point>/s<seed>/packing.dat, the re-run since
6 Dec 2026) beside the same point and seed of the first run (results/viscous_rerun/first_run/),
steps, phi and Z. Before the table: the range of the differences, the re-run at the first run's
last time (the same beds?), its creep from where it first met the first run's rest criterion
to its end and over its last LAST_STEPS steps (each re-run's thermo.csv in
results/viscous_rerun/<point>/s<seed>/)."""
import csv
import glob
import os

import numpy as np

from deposit_run import read_packing
from study_doc_claims import table

FIRST_RUN_DT = 6.0e-4    # paper.yaml's vars when the first run was made (00ed1c3, 9e44684)
CALM = 1.0e-3            # paper.yaml's ketol (m g d per particle): the first run's only criterion
LAST_STEPS = 10000       # the creep still left when the present criterion stops a run


def thousands(steps):
    return "{:,}".format(int(steps)).replace(",", " ")


def read_thermo(path):
    """thermo.csv's rows (step, time, ke_per_particle, phi, Z) as floats"""
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def first_calm(rows):
    """the first row whose kinetic energy per particle is below CALM (where the first run's
    criterion stopped it), None if there is none"""
    return next((r for r in rows if r["ke_per_particle"] < CALM), None)


def nearest(rows, column, value):
    """the row whose column (time or step) is nearest value"""
    return min(rows, key=lambda r: abs(r[column] - value))


def comparison_text(pairs):
    """pairs: [(first run's packing, re-run's thermo rows)]: the re-run at the first run's last
    time, and its creep from its first calm row to its end"""
    same = np.array([(r["phi"] - old["phi"], r["Z"] - old["Z"]) for old, rows in pairs
                     for r in [nearest(rows, "time", old["steps"] * FIRST_RUN_DT)]])
    calm = [(first_calm(rows), rows[-1]) for _, rows in pairs]
    if any(c is None for c, _ in calm):
        return ""
    creep = np.array([(end["phi"] - c["phi"], end["Z"] - c["Z"], end["time"] - c["time"])
                      for c, end in calm])
    times = [c["time"] for c, _ in calm]
    last = [rows[-1]["phi"] - nearest(rows, "step", rows[-1]["step"] - LAST_STEPS)["phi"]
            for _, rows in pairs]
    first_end = [old["steps"] * FIRST_RUN_DT for old, _ in pairs]
    return (" At the first run's last time (its steps x dt %g) the re-run differed from it by "
            "phi %+.4f (SD %.4f over the %d deposits) and Z %+.3f (SD %.3f): the same beds at "
            "the same time. The re-run first met the first run's rest criterion (kinetic energy "
            "per particle below %g m g d) at t %.1f to %.1f (the first run stopped at %.1f to "
            "%.1f); from there to its end, %.0f to %.0f time units later, phi rose by %+.4f to "
            "%+.4f and Z by %+.2f to %+.2f, and over its last %s steps phi still rose by "
            "%+.4f to %+.4f: the numbers are those at in.deposit's present rest criterion."
            % (FIRST_RUN_DT, same[:, 0].mean(), same[:, 0].std(ddof=1), len(pairs),
               same[:, 1].mean(), same[:, 1].std(ddof=1), CALM, min(times), max(times),
               min(first_end), max(first_end), creep[:, 2].min(), creep[:, 2].max(),
               creep[:, 0].min(), creep[:, 0].max(), creep[:, 1].min(), creep[:, 1].max(),
               thousands(LAST_STEPS), min(last), max(last)))


def viscous_rerun_block(results):
    """results: the study's results folder; the first run's deposits lie beside it"""
    rerun = os.path.join(os.path.dirname(os.path.normpath(results)), "viscous_rerun")
    rows, dphi, dz, pairs = [], [], [], []
    for path in glob.glob(os.path.join(rerun, "first_run", "*", "s*", "packing.dat")):
        point, seed = path.split(os.sep)[-3:-1]
        old = read_packing(path)
        new = read_packing(os.path.join(results, "points", point, seed, "packing.dat"))
        dphi.append(new["phi"] - old["phi"])
        dz.append(new["Z"] - old["Z"])
        thermo = os.path.join(rerun, point, seed, "thermo.csv")
        pairs.append((old, read_thermo(thermo) if os.path.exists(thermo) else None))
        rows.append(((new["eta"], new["zeta"], int(seed[1:])), [
            "%g" % new["eta"] if new["eta"] == new["zeta"] else "%g, %g" % (new["eta"], new["zeta"]),
            seed[1:]] + ["%s, %.4f, %.2f" % (thousands(d["steps"]), d["phi"], d["Z"])
                         for d in (old, new)]))
    if not rows:
        return "No first run kept."
    summary = ("Re-run minus first run, %d deposits: phi %+.3f to %+.3f, Z %+.2f to %+.2f."
               % (len(rows), min(dphi), max(dphi), min(dz), max(dz)))
    if all(t is not None for _, t in pairs):
        summary += comparison_text(pairs)
    return summary + "\n\n" + table(["eta = zeta", "seed", "first run: steps, phi, Z",
                                     "re-run: steps, phi, Z"], [r for _, r in sorted(rows)])
