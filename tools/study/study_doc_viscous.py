"""doc/study.md's table of the viscous set's re-run (tools/study/study_doc.py): each deposit of
the study's viscous set (results/study/points/<point>/s<seed>/packing.dat, the re-run since
6 Dec 2026) beside the same point and seed of the first run (results/viscous_rerun/first_run/,
made at a time step beyond the law's stability bound), steps, phi and Z; before it the range of
the differences and the creep after the bed is calm (each re-run's thermo.csv in
results/viscous_rerun/<point>/s<seed>/)."""
import csv
import glob
import os

from deposit_run import read_packing
from study_doc_claims import table


def thousands(steps):
    return "{:,}".format(int(steps)).replace(",", " ")


CALM = 1e-3    # kinetic energy per particle below which the bed is called calm


def creep(path):
    """(step, phi, Z) where a thermo.csv's kinetic energy per particle falls below CALM for good
    (its last crossing) and (step, phi, Z) at its end; None if it never does"""
    with open(path) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    moving = [i for i, r in enumerate(rows) if r["ke_per_particle"] >= CALM]
    first = moving[-1] + 1 if moving else 0
    if first >= len(rows):
        return None
    return tuple((r["step"], r["phi"], r["Z"]) for r in (rows[first], rows[-1]))


def creep_text(rerun, rows):
    """after the bed is calm: the range of the rise in phi and Z and of the steps it took, and
    the thinnest shape's first seed in full"""
    found = {key: creep(os.path.join(rerun, point, seed, "thermo.csv"))
             for key, point, seed in rows}
    found = {k: c for k, c in found.items() if c}
    if not found:
        return ""
    dphi = [end[1] - calm[1] for calm, end in found.values()]
    dz = [end[2] - calm[2] for calm, end in found.values()]
    steps = [end[0] - calm[0] for calm, end in found.values()]
    thin = max(found, key=lambda k: (k[0], k[1], -k[2]))    # the first seed
    (s0, p0, z0), (s1, p1, z1) = found[thin]
    return (" After the kinetic energy per particle fell below %g for good (%d deposits), phi "
            "still rose by %+.3f to %+.3f and Z by %+.2f to %+.2f over the remaining %s to %s "
            "steps; at eta = zeta = %g, seed %d: phi %.4f and Z %.2f at step %s, %.4f and %.2f "
            "at %s." % (CALM, len(found), min(dphi), max(dphi), min(dz), max(dz),
                        thousands(min(steps)), thousands(max(steps)), thin[0], thin[2], p0, z0,
                        thousands(s0), p1, z1, thousands(s1)))


def viscous_rerun_block(results):
    """results: the study's results folder; the first run's deposits lie beside it"""
    first_run = os.path.join(os.path.dirname(os.path.normpath(results)), "viscous_rerun",
                             "first_run")
    rows, dphi, dz, runs = [], [], [], []
    for path in glob.glob(os.path.join(first_run, "*", "s*", "packing.dat")):
        point, seed = path.split(os.sep)[-3:-1]
        old = read_packing(path)
        new = read_packing(os.path.join(results, "points", point, seed, "packing.dat"))
        dphi.append(new["phi"] - old["phi"])
        dz.append(new["Z"] - old["Z"])
        runs.append(((new["eta"], new["zeta"], int(seed[1:])), point, seed))
        rows.append(((new["eta"], new["zeta"], int(seed[1:])), [
            "%g" % new["eta"] if new["eta"] == new["zeta"] else "%g, %g" % (new["eta"], new["zeta"]),
            seed[1:]] + ["%s, %.4f, %.2f" % (thousands(d["steps"]), d["phi"], d["Z"])
                         for d in (old, new)]))
    if not rows:
        return "No first run kept."
    summary = ("Re-run minus first run, %d deposits: phi %+.3f to %+.3f, Z %+.2f to %+.2f."
               % (len(rows), min(dphi), max(dphi), min(dz), max(dz))
               + creep_text(os.path.dirname(first_run), runs))
    return summary + "\n\n" + table(["eta = zeta", "seed", "first run: steps, phi, Z",
                                     "re-run: steps, phi, Z"], [r for _, r in sorted(rows)])
