"""examples/deposit/in.deposit's measuring slab and its normal law, in its measure mode (no
pour: a hand-made deposit of touching unit spheres on a simple cubic lattice, 5 x 5 columns).

* A deposit too shallow for the slab (one mean diameter above the ground and two below the
  surface left out, then at least slabmin mean diameters) is no measurement: packing.dat says
  slab_ok 0 with the slab's thickness, and the log a WARNING; before, phi 0 and Z 0 of an
  empty slab were written as the result. A deep one says slab_ok 1.
* The normal law is a variable: the default gives the pair and the ground the words of the
  hard-coded law before (hertz kn K), hertz/material reaches both with its material.
"""
import math
import os
import re

import pytest

import ed_helpers_pour as h


def write_lattice(path, layers, edge=5):
    n = edge * edge * layers
    with open(path, "w") as f:
        f.write("lattice of unit spheres\n\n%d atoms\n1 atom types\n%d ellipsoids\n\n" % (n, n))
        f.write("0 %d xlo xhi\n0 %d ylo yhi\n0 %d zlo zhi\n\nAtoms # ellipsoid\n\n"
                % (edge, edge, layers + 2))
        centres = [(i + 0.5, j + 0.5, k + 0.5) for i in range(edge) for j in range(edge)
                   for k in range(layers)]
        for a, (x, y, z) in enumerate(centres, 1):
            f.write("%d 1 1 1.0 %g %g %g\n" % (a, x, y, z))
        f.write("\nEllipsoids\n\n")
        for a in range(1, n + 1):
            f.write("%d 1 1 1 1 0 0 0\n" % a)
    return n


def measure(tmp_path, layers, **more):
    """packing.dat (dict of strings) and the log of in.deposit measuring the lattice"""
    data = str(tmp_path / "deposit.data")
    n = write_lattice(data, layers)
    variables = {"measure": data, "measure_steps": 0, "measure_rest": 1, "N": n, "eta": 1,
                 "zeta": 1, "dr": 0, "image": 0, "out": str(tmp_path), "width": 5}
    variables.update(more)
    h.deposit_lammps(tmp_path, variables).close()
    packing = {}
    for line in open(tmp_path / "packing.dat"):
        if not line.startswith("#"):
            key, value = line.split(None, 1)
            packing[key] = value.strip()
    return packing, open(tmp_path / "log.lammps").read()


def warned(log):
    """the log's warnings of a slab too thin (the lines the print wrote, not its echo)"""
    return [line for line in log.splitlines()
            if line.startswith("WARNING: ELLIPSOID_DEP the measuring slab")]


@pytest.mark.parametrize("slabmin", ["1.0", "0"])
def test_too_shallow_for_the_slab(tmp_path, slabmin):
    """two layers: the surface at 2 d, the slab [1 d, 0 d] is empty: no result, whatever
    slabmin asks for"""
    pk, log = measure(tmp_path, 2, slabmin=slabmin)
    assert pk["slab_ok"] == "0" and float(pk["slab_thickness"]) == 0.0
    assert warned(log) == ["WARNING: ELLIPSOID_DEP the measuring slab is 0.000 mean diameters "
                           "thick, under slabmin %s or empty: the deposit is too shallow, its "
                           "phi, Z and forces are not results (packing.dat says slab_ok 0)"
                           % slabmin]


@pytest.mark.parametrize("slabmin,ok", [(1.0, "1"), (2.99, "1"), (3.01, "0")])
def test_deep_enough_for_the_slab(tmp_path, slabmin, ok):
    """six layers: the slab [1 d, 4 d] is 3 mean diameters thick"""
    pk, log = measure(tmp_path, 6, slabmin=slabmin)
    assert float(pk["slab_thickness"]) == pytest.approx(3.0, abs=1e-6)
    assert float(pk["phi"]) == pytest.approx(3.141592653589793 / 6, abs=1e-5)
    assert pk["slab_ok"] == ok and float(pk["slabmin"]) == slabmin
    assert len(warned(log)) == (ok == "0")


def law_words(log, *command):
    """the words of the last echo of a command in the log (after variable substitution)"""
    lines = [line.split() for line in log.splitlines()
             if line.split()[:len(command)] == list(command)]
    return lines[-1]


def test_normal_law_variable(tmp_path):
    _, log = measure(tmp_path, 2)
    assert law_words(log, "pair_coeff") == ["pair_coeff", "*", "*", "hertz", "1.0e4", "200.0",
                                            "tangential", "history", "2.0e3", "0.5"]
    ground = law_words(log, "fix", "ground")
    assert ground[:12] == ["fix", "ground", "all", "wall/gran/ellipsoid", "hertz", "1.0e4",
                           "200.0", "tangential", "history", "2.0e3", "0.5", "zplane"]
    _, log = measure(tmp_path, 2, kn="3e4", K="50")
    assert law_words(log, "pair_coeff")[3:7] == ["hertz", "3e4", "50", "tangential"]
    # E nu e in LJ units (the materials file's SI values are refused in lj units)
    _, log = measure(tmp_path, 2, normal="hertz/material", material="3e4 0.3 0.5")
    assert law_words(log, "pair_coeff")[3:8] == ["hertz/material", "3e4", "0.3", "0.5",
                                                 "tangential"]
    assert law_words(log, "fix", "ground")[4:9] == ["hertz/material", "3e4", "0.3", "0.5",
                                                    "tangential"]


def test_runner_fails_on_a_slab_too_thin(tmp_path):
    """tools/deposit/deposit_run.py on a deposit whose measured slab is thinner than its input's
    slabmin: no phi printed as a result, a non-zero exit, packing.dat says slab_ok 0 (the
    runner's own estimate passes N 200; the input asks for 9 mean diameters)"""
    from study_helpers import PY, TOOLS, run
    strict = tmp_path / "in.strict"
    strict.write_text("variable slabmin index 9\ninclude %s\n" % h.DEPOSIT)
    out = tmp_path / "run"
    text = run([PY, os.path.join(TOOLS, "deposit", "deposit_run.py"), "--np", "1", "--N", "200",
                "--ketol", "1e-2", "--input", str(strict), "--out", str(out), "--quiet",
                "--no-image", "--no-plots"], str(tmp_path), 600, ok=False)
    assert "deposit_run: the deposit is too shallow for its measuring slab" in text
    assert "volume fraction phi" not in text
    packing = open(out / "packing.dat").read()
    assert "slab_ok 0\n" in packing and "slabmin 9\n" in packing


@pytest.mark.parametrize("dr", [0.0, 0.6, 0.8])
def test_depth_estimate_uses_the_pours_sizes(tmp_path, dr):
    """tools/deposit/deposit_depth.py's mean volume is the one fix pour/ellipsoid logs (its sampler's,
    6 digits), and its number-mean diameter that of 2000 poured particles (compute
    packing/ellipsoid's dmean, within 5 standard errors of the mean)"""
    import deposit_depth
    h.deposit_lammps(tmp_path, {"N": 2000, "dr": dr, "chunk": 1, "maxchunks": 1, "image": 0,
                                "out": str(tmp_path), "slabmin": 0}).close()
    log = open(tmp_path / "log.lammps").read()
    logged = float(re.search(r"mean volume (\S+)\n", log).group(1))
    volume, diameter = deposit_depth.size_moments(dr)
    assert volume == pytest.approx(logged, rel=1e-5)
    dmean = float(re.search(r"^dmean (\S+)$", open(tmp_path / "packing.dat").read(),
                            re.M).group(1))
    spread = 2 * 0.5 * dr / math.sqrt(2000)    # bounds the SD of 2r / sqrt(N)
    assert dmean == pytest.approx(diameter, abs=5 * spread + 1e-6)
