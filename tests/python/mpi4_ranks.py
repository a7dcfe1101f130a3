"""Four MPI ranks (`processors 2 2 1`): a pour with fix balance, a settled deposit continued on
1, 2 and 4 ranks with newton on and off, a restart written on 4 ranks read on 1 and 2.

Run as `mpirun -np 4 python3 mpi4_ranks.py` (oversubscribed on 2 cores); exits non-zero on
failure.

1. All 4 ranks pour triaxial ellipsoids (pair and wall with tangential history and rolling)
   from a region over the left part of the box, with `fix balance ... shift xy`, until the
   deposit is at rest; then `write_restart`. Checks: every particle inserted exactly once,
   none lost, finite state; no balancing step made the load worse and at least one improved it.
2. The restart is read by 1 rank newton on, 1 rank newton off, 2 ranks newton on (side by
   side, `-partition 1 1 2`), and by 4 ranks newton on (the reference) and newton off.
   * Set-up forces and torques (`run 0`) with the pour's law equal the reference to
     SETUP_TOL of the largest contact force (same contacts and histories; the summation
     order differs, and with newton off pairs across ranks are evaluated from both sides).
   * CONTINUE steps with the law without rolling resistance: positions agree to POS_TOL
     and contact forces to FORCE_TOL of the largest.
   Why no rolling resistance in the continuation: the *constant* rolling torque points
   against the rolling angular velocity whatever its size, so at rest its direction is set
   by round-off; a 1e-16 difference then grows to 3e-7 in positions within 300 steps
   (measured with mu_r = 0.02). Without it the comparison stays at 1e-13 after 1000 steps.
Scale: at rest the net force on a particle nearly vanishes (contacts balance gravity), so
differences are measured against the largest contact force |f - m g|.
The partitions exchange results through files in a per-job folder; the constructor of the
next LAMMPS instance on all ranks is the barrier.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from lammps import lammps  # noqa: E402

import mpi_helpers as mpi  # noqa: E402

ARGS = mpi.ARGS
N = 40
SMOOTH = "hertz/material 2e6 0.3 0.2 tangential history 1e4 0.5"
LAW = SMOOTH + " rolling constant 0.1"
CHUNK = 1000          # steps between two checks of the rest criterion
MAX_CHUNKS = 20
KE_REST = 1e-5        # kinetic energy per particle at rest (m g d ~ 1 here)
CONTINUE = 1000       # steps of the continued runs
# Set-up, newton on: the same contacts summed in another order, ~1e-16 of each force;
# measured 8e-17 .. 1e-16. Newton off evaluates a pair that crosses a rank or the periodic boundary
# from both sides: the contact iteration converges to 1e-12 relative on the contact points
# from two starts, and an overlap ~1e-3 of the size turns that into ~1e-9 on a force;
# measured 2e-12 .. 2e-11.
SETUP_TOL = {"on": 1e-13, "off": 1e-9}
# Continued: those differences grown through stiff contacts and friction springs over
# CONTINUE steps: measured positions 4e-14 .. 2.2e-13 (sizes ~1), forces 1e-11 .. 2e-11 of
# the largest; the bounds are 50 and 500 times that.
POS_TOL = 1e-11
FORCE_TOL = 1e-8


def gather(lmp, name, width=3):
    return np.array(lmp.gather_atoms(name, 1, width), dtype=float).reshape(-1, width)


def contact_forces(lmp):
    """f - m g (gravity 1 along -z): the forces of the pair and the wall."""
    f = gather(lmp, "f")
    f[:, 2] += gather(lmp, "rmass", 1)[:, 0]
    return f


def scene_commands():
    return [
        "units lj", "atom_style ellipsoid", "atom_modify map array", "boundary p p f",
        "comm_modify vel yes", "processors 2 2 1", "region box block 0 8 0 8 0 8",
        "create_box 1 box", "pair_style granular/ellipsoid",
        # over x < 5 only: the deposit is uneven in x, so the balancer has work to do
        "region ins block 0 5 0 8 1.5 4.5",
        f"fix p all pour/ellipsoid {N} 1 5821 region ins size mean 0.7 delta_r 0.3 "
        "shape 1.5 1.3 density 1 vol 0.15 200 every 600",
        "fix bal all balance 500 1.0 shift xy 10 1.01",
    ] + dynamics_commands(LAW)


def dynamics_commands(law):
    """What a continued run re-specifies after read_restart."""
    return [
        f"pair_coeff * * {law}",
        "fix g all gravity 1.0 vector 0 0 -1",
        "fix i all nve/asphere",
        f"fix w all wall/gran/ellipsoid {law} zplane 0 NULL",
        "compute ke all ke", "compute er all erotate/asphere",
        "variable kep equal (c_ke+c_er)/(atoms+(atoms<1))",
        "thermo_style custom step atoms v_kep", "thermo_modify lost error",
        "thermo 1000", "timestep 1e-3",
    ]


def pour_and_settle(restart):
    lmp = lammps(cmdargs=ARGS)
    lmp.commands_list(scene_commands())
    imbalance = []
    for _ in range(MAX_CHUNKS):
        lmp.command(f"run {CHUNK}")
        imbalance.append((lmp.extract_fix("bal", 0, 1, 2), lmp.extract_fix("bal", 0, 0)))
        if lmp.extract_fix("p", 0, 0) == N and lmp.extract_variable("kep") < KE_REST:
            break
    out = {"natoms": lmp.get_natoms(), "inserted": lmp.extract_fix("p", 0, 0),
           "kep": lmp.extract_variable("kep"), "step": lmp.extract_global("ntimestep"),
           "imbalance": imbalance, "x": gather(lmp, "x"), "ids": np.array(lmp.gather_atoms("id", 0, 1))}
    lmp.command("unfix bal")
    lmp.command(f"write_restart {restart}")
    lmp.close()
    return out


def read(restart, newton, law, cmdargs=ARGS, processors=None):
    lmp = lammps(cmdargs=cmdargs)
    if processors:
        lmp.command(f"processors {processors}")
    lmp.command(f"read_restart {restart}")
    lmp.commands_list(["comm_modify vel yes", f"newton {newton} on"] + dynamics_commands(law))
    return lmp


def setup_forces(lmp):
    lmp.command("run 0")
    return {"f0": contact_forces(lmp), "t0": gather(lmp, "torque")}


def continued(lmp):
    lmp.command(f"run {CONTINUE}")
    return {"x": gather(lmp, "x"), "f": contact_forces(lmp), "natoms": lmp.get_natoms()}


def one_run(restart, newton, cmdargs=ARGS, processors=None):
    lmp = read(restart, newton, LAW, cmdargs, processors)
    out = setup_forces(lmp)
    lmp.close()
    lmp = read(restart, newton, SMOOTH, cmdargs, processors)
    out.update(continued(lmp))
    out["newton"] = newton
    return lmp, out


def barrier():
    lammps(cmdargs=ARGS).close()


def compare(name, ref, r, failures):
    scale_f = np.abs(ref["f0"]).max()
    d_setup = max(np.abs(r["f0"] - ref["f0"]).max() / scale_f,
                  np.abs(r["t0"] - ref["t0"]).max() / np.abs(ref["t0"]).max())
    d = r["x"] - ref["x"]
    d[:, :2] -= 8.0 * np.round(d[:, :2] / 8.0)       # periodic x, y
    dx = np.abs(d).max()
    df = np.abs(r["f"] - ref["f"]).max() / np.abs(ref["f"]).max()
    if r["natoms"] != ref["natoms"] or not np.isfinite(r["x"]).all():
        failures.append(f"{name}: natoms {r['natoms']} or non-finite positions")
    if not d_setup < SETUP_TOL[str(r["newton"])]:
        failures.append(f"{name}: set-up forces after read_restart differ by {d_setup:.3g}")
    if not (dx < POS_TOL and df < FORCE_TOL):
        failures.append(f"{name}: after {CONTINUE} steps positions differ by {dx:.3g}, "
                        f"forces by {df:.3g} of the largest")
    return f"{name}: set-up {d_setup:.2g}, x {dx:.2g}, f {df:.2g}"


def main():
    probe = lammps(cmdargs=ARGS)
    nprocs = probe.extract_setting("world_size")
    rank = probe.extract_setting("world_rank")
    probe.close()
    if nprocs != 4:
        sys.exit(f"mpi4_ranks.py needs 4 ranks, got {nprocs}")
    work = mpi.job_folder("mpi4_ranks_")
    restart = os.path.join(work, "settled.restart")
    failures = []

    settled = pour_and_settle(restart)

    # partitions: universe ranks 0 | 1 | 2 3
    part = ARGS + ["-partition", "1", "1", "2", "-plog", "none", "-pscreen", "none",
                   "-in", os.devnull]
    probe = lammps(cmdargs=part)
    universe = probe.extract_setting("universe_rank")
    probe.close()
    newton = "off" if universe == 1 else "on"
    lmp, r = one_run(restart, newton, part, processors="* * 1")
    lmp.close()
    if universe < 3:
        np.savez(os.path.join(work, f"part{universe}.npz"), **r)
    barrier()

    runs = {}
    for newton in ("on", "off"):
        lmp, runs[newton] = one_run(restart, newton)
        if newton == "off":
            lmp.finalize()
        else:
            lmp.close()

    if rank != 0:
        return
    if settled["natoms"] != N or settled["inserted"] != N or \
            len(np.unique(settled["ids"])) != N:
        failures.append(f"pour: natoms {settled['natoms']} inserted {settled['inserted']}")
    if not settled["kep"] < KE_REST:
        failures.append(f"pour not at rest after {settled['step']} steps: KE {settled['kep']}")
    if not np.isfinite(settled["x"]).all():
        failures.append("pour: non-finite positions")
    steps = settled["imbalance"]
    if any(after > before + 1e-12 for before, after in steps) or \
            not any(after < before for before, after in steps):
        failures.append(f"fix balance: imbalance (before, after) {steps}")
    ref = runs["on"]
    lines = [compare("4 ranks newton off", ref, runs["off"], failures)]
    for k, name in enumerate(["1 rank newton on", "1 rank newton off", "2 ranks newton on"]):
        lines.append(compare(name, ref, dict(np.load(os.path.join(work, f"part{k}.npz"))),
                             failures))
    if failures:
        for f in failures:
            print(f"FAIL {f}", flush=True)
        sys.exit(1)
    best = min(steps, key=lambda s: s[1] - s[0])
    print(f"mpi4_ranks: {N} poured on 4 ranks with fix balance (imbalance {best[0]:.3g} -> "
          f"{best[1]:.3g}), at rest (KE {settled['kep']:.2g}) after {settled['step']} steps; "
          "vs 4 ranks newton on: " + "; ".join(lines), flush=True)


if __name__ == "__main__":
    main()
