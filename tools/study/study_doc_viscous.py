"""doc/study.md's table of the viscous set's re-run (tools/study/study_doc.py): each finished
re-run deposit (results/viscous_rerun/<point>/s<seed>/packing.dat) beside the same point and
seed of the study's first run (kept in results/viscous_rerun/first_run/<point>/s<seed>/, so the
comparison survives the re-run replacing the study's viscous points), steps, phi and Z; before
it how many are finished and the range of the differences."""
import glob
import os

from deposit_run import read_packing
from study_doc_claims import table


def thousands(steps):
    return "{:,}".format(int(steps)).replace(",", " ")


def viscous_rerun_block(results):
    """results: the study's results folder; the re-run's lies beside it"""
    rerun = os.path.join(os.path.dirname(os.path.normpath(results)), "viscous_rerun")
    rows, dphi, dz = [], [], []
    first_run = os.path.join(rerun, "first_run")
    planned = glob.glob(os.path.join(first_run, "*", "s*", "packing.dat"))
    for path in glob.glob(os.path.join(rerun, "*_viscous", "s*", "packing.dat")):
        point, seed = path.split(os.sep)[-3:-1]
        new = read_packing(path)
        old = read_packing(os.path.join(first_run, point, seed, "packing.dat"))
        dphi.append(new["phi"] - old["phi"])
        dz.append(new["Z"] - old["Z"])
        rows.append(((new["eta"], new["zeta"], int(seed[1:])), [
            "%g" % new["eta"] if new["eta"] == new["zeta"] else "%g, %g" % (new["eta"], new["zeta"]),
            seed[1:]] + ["%s, %.4f, %.2f" % (thousands(d["steps"]), d["phi"], d["Z"])
                         for d in (old, new)]))
    summary = ("Finished: %d of the %d deposits (seeds 1 and 2 of the old set's shapes)."
               % (len(rows), len(planned)))
    if rows:
        summary += (" Re-run minus old: phi %+.3f to %+.3f, Z %+.2f to %+.2f."
                    % (min(dphi), max(dphi), min(dz), max(dz)))
    return summary + "\n\n" + table(["eta = zeta", "seed", "old: steps, phi, Z",
                                     "re-run: steps, phi, Z"], [r for _, r in sorted(rows)])
