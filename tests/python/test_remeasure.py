"""tools/deposit/remeasure_deposit.py measures a finished deposit again exactly as in.deposit measured it.

Specification:
- a deposit's dump read back in in.deposit's measure mode gives the packing.dat and the two
  histograms the run wrote itself (the dump keeps 10 digits): counts equal, the rest to 1e-6;
- keys the runner appended (wall_seconds, np) are kept, and `remeasured 1` is added;
- in.deposit's slab ends two mean diameters below the surface of the column maxima
  (surface columns): one particle added 2 d above the deposit moves the slab's top by its
  column's share, not by 2 d;
- in place, the first measurement is kept as packing.dat.orig.
"""
import pytest

import ed_helpers_pour as h
import remeasure_deposit

COUNTS = ("N", "steps", "at_rest", "Nslab", "rattlers", "seed")


def short_deposit(out):
    """in.deposit, 150 particles, at most 8 chunks of 1000 steps: landed"""
    args = {"N": "150", "maxchunks": "8", "chunk": "1000", "image": "0", "out": str(out),
            "dr": "0.3"}
    h.deposit_lammps(out, args).close()
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
        else:    # one unit of the last printed digit (%.6f)
            assert float(new[key]) == pytest.approx(float(value), abs=1.1e-6), key
    assert new["remeasured"] == "1"
    for name in ("contact_histo.dat", "orient_histo.dat"):
        a, b = histogram(run / name), histogram(into / name)
        assert len(a) == 18 and len(b) == 18
        for ra, rb in zip(a, b):
            assert rb == pytest.approx(ra, rel=1e-5, abs=1e-12), name    # %g: 6 digits

    # one more particle lying 2 d above the highest one, measured again in place
    lines = open(run / "deposit.dump").read().splitlines()
    columns = lines[8].split()[2:]
    rows = [line.split() for line in lines[9:]]
    z = columns.index("z")
    top = max(rows, key=lambda r: float(r[z]))
    extra = list(top)
    extra[columns.index("id")] = str(len(rows) + 1)
    extra[z] = repr(float(top[z]) + 2.0)
    lines[3] = str(len(rows) + 1)
    zlo, zhi = (float(v) for v in lines[7].split()[:2])
    lines[7] = "%r %r" % (zlo, zhi + 3.0)    # the box's top, so that it holds the particle
    (run / "deposit.dump").write_text("\n".join(lines + [" ".join(extra)]) + "\n")
    _, moved = remeasure_deposit.remeasure(str(run), str(run))
    shift = float(moved["zhi"]) - float(old["zhi"])
    assert 0 < shift < 0.15, shift    # its column's share of 2 d (25 columns), not 2 d
    assert (run / "packing.dat.orig").read_text().startswith("# ELLIPSOID_DEP")
    assert "remeasured" not in (run / "packing.dat.orig").read_text()
