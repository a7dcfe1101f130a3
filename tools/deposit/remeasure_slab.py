#!/usr/bin/python3
"""phi and Z of finished deposits in common slabs, for comparing protocols.

    ./ellipsoid-dep python tools/deposit/remeasure_slab.py RUN_DIR [RUN_DIR ...]

Reads each run folder's deposit.dump (the runner's OVITO dump), writes it as a LAMMPS data
file and evaluates compute packing/ellipsoid at run 0 in the fixed bulk slab z in [1, 4] d and
in the default slab (auto bottom 1 top 2, with surface max and surface columns). Contacts are
the pair's overlaps, so the law's constants do not matter. The auto values reproduce the run's
packing.dat (doc/CHANGELOG.md, 2026-12-01, "The pour protocol against the protocol before").
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from remeasure_deposit import contacts_instance    # noqa: E402

SLABS = [("bulk [1, 4]", "1.0 4.0 rattler 2"),
         ("auto", "auto bottom 1 top 2 rattler 2"),
         ("auto, surface columns", "auto bottom 1 top 2 rattler 2 surface columns")]


def remeasure(run_dir):
    lmp = contacts_instance(os.path.join(run_dir, "deposit.dump"))
    for k, (_, args) in enumerate(SLABS):
        lmp.command(f"compute p{k} all packing/ellipsoid {args}")
    lmp.command("run 0 post no")
    out = []
    for k, (name, _) in enumerate(SLABS):
        v = [lmp.extract_compute(f"p{k}", 0, 1)[j] for j in range(6)]
        out.append("%s: phi %.4f Z %.3f (z %.2f-%.2f)" % (name, v[0], v[2], v[4], v[5]))
    lmp.close()
    return out


if __name__ == "__main__":
    for d in sys.argv[1:]:
        print(os.path.basename(os.path.normpath(d)), "|", " | ".join(remeasure(d)))
