"""The pair on 1 and 2 MPI ranks, with newton on and off, and across a restart file."""
import os
import subprocess

import numpy as np
import pytest

from conftest import new_lammps, subprocess_env
from scenes import dense_ellipsoids


def lmp_binary():
    return os.environ["ELLIPSOID_DEP_LMP"]


def run_lmp(tmp_path, text, ranks, name):
    inp = tmp_path / f"in.{name}"
    inp.write_text(text)
    cmd = [lmp_binary(), "-in", str(inp), "-log", "none", "-screen", "none", "-nocite"]
    if ranks > 1:
        cmd = ["mpirun", "-np", str(ranks)] + cmd
    subprocess.run(cmd, cwd=tmp_path, check=True, timeout=600, env=subprocess_env())


def read_dump(path):
    """Last snapshot of a 'custom' dump sorted by id: columns after id."""
    lines = path.read_text().splitlines()
    start = max(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    rows = np.array([[float(v) for v in line.split()] for line in lines[start + 1:]])
    return rows[np.argsort(rows[:, 0])]


FORCE_DUMP = "dump d all custom {every} forces.{name} id xu yu zu fx fy fz tqx tqy tqz\n" \
             "dump_modify d sort id format float %.17g\n"


@pytest.mark.parametrize("newton", ["off", "on"])
def test_two_ranks_give_serial_forces(tmp_path, newton):
    steps = 300
    text = dense_ellipsoids(newton=newton) + FORCE_DUMP.format(every=steps, name="{}") + \
        f"run {steps}\n"
    run_lmp(tmp_path, text.replace("forces.{}", "forces.serial"), 1, "serial")
    run_lmp(tmp_path, text.replace("forces.{}", "forces.mpi"), 2, "mpi")
    serial = read_dump(tmp_path / "forces.serial")
    parallel = read_dump(tmp_path / "forces.mpi")
    assert serial.shape == parallel.shape and len(serial) == 100
    forces = serial[:, 4:]
    scale = np.abs(forces).max()
    assert np.count_nonzero(np.abs(forces[:, :3]).sum(axis=1)) > 50, "too few contacts"
    # the runs differ only in summation order: round-off, grown over a few hundred steps
    np.testing.assert_allclose(parallel[:, 1:4], serial[:, 1:4], rtol=0, atol=1e-9)
    np.testing.assert_allclose(parallel[:, 4:], forces, rtol=0, atol=1e-6 * scale)


def test_newton_on_off_same_trajectory(tmp_path):
    steps = 300
    for newton in ("off", "on"):
        text = dense_ellipsoids(newton=newton) + \
            FORCE_DUMP.format(every=steps, name=newton) + f"run {steps}\n"
        run_lmp(tmp_path, text, 1, newton)
    off = read_dump(tmp_path / "forces.off")
    on = read_dump(tmp_path / "forces.on")
    np.testing.assert_allclose(on[:, 1:4], off[:, 1:4], rtol=0, atol=1e-9)


def forces_now(lmp):
    nlocal = lmp.extract_global("nlocal")
    ids = lmp.numpy.extract_atom("id")[:nlocal]
    order = np.argsort(ids)
    f = lmp.numpy.extract_atom("f")[:nlocal][order].copy()
    t = lmp.numpy.extract_atom("torque")[:nlocal][order].copy()
    return np.hstack([f, t])


def test_restart_mid_contact_keeps_forces(tmp_path):
    restart = str(tmp_path / "mid.restart")
    lmp = new_lammps()
    lmp.commands_string(dense_ellipsoids())
    lmp.command("run 400")
    # compare set-up forces with set-up forces: within a run the damping sees half-step
    # velocities, at set-up full-step ones (as with any LAMMPS granular style)
    lmp.command("run 0")
    before = forces_now(lmp)
    lmp.command(f"write_restart {restart}")
    lmp.command("run 200")
    after_continuous = forces_now(lmp)
    lmp.close()

    lmp = new_lammps()
    lmp.commands_string(f"""
        read_restart {restart}
        comm_modify vel yes
        fix integrate all nve/asphere
        fix fall all gravity 1.0 vector 0 0 -1
        timestep 2e-4
        run 0
        """)
    reread = forces_now(lmp)
    lmp.command("run 200")
    after_restart = forces_now(lmp)
    lmp.close()

    scale = np.abs(before).max()
    assert np.count_nonzero(np.abs(before[:, :3]).sum(axis=1)) > 50
    # the tangential springs and cached planes came back: the same forces to round-off
    np.testing.assert_allclose(reread, before, rtol=0, atol=1e-10 * scale)
    np.testing.assert_allclose(after_restart, after_continuous, rtol=0, atol=1e-8 * scale)
