"""Four MPI ranks (`processors 2 2 1`): a pour with fix balance, a settled deposit continued on
1, 2 and 4 ranks with newton on and off, a restart written on 4 ranks read on 1 and 2.

Run as `mpirun -np 4 python3 mpi4_ranks.py` (oversubscribed on 2 cores); exits non-zero on
failure.

1. All 4 ranks pour triaxial ellipsoids (pair and wall with tangential history and rolling)
   from a region over the left part of the box, with `fix balance ... shift xy`, until the
   deposit is at rest; then `write_restart`. Checks: every particle inserted, none lost,
   finite state, the balancer moved the cuts (imbalance before its last call > after).
2. The restart is read by four runs at once (`-partition 1 1 2`): 1 rank newton on, 1 rank
   newton off, 2 ranks newton on; then by 4 ranks with newton on and with newton off. Each
   run does a set-up `run 0` and continues CONTINUE steps.
   * Set-up forces and torques of every run equal the 4-rank run's to 1e-12 of the largest:
     the same contacts with the same history, only the summation order differs.
   * After CONTINUE steps positions agree to POS_TOL and forces to FORCE_TOL of the largest
     (see the constants: the deposit is at rest, so round-off is not amplified by collisions;
     it grows through the stiff contacts only).
The partitions exchange results through files in a per-job folder; the constructor of the
next LAMMPS instance on all ranks is the barrier.
"""
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from lammps import lammps  # noqa: E402

ARGS = ["-log", "none", "-screen", "none", "-nocite"]
N = 40
LAW = "hertz/material 2e6 0.3 0.3 tangential history 1e4 0.5 rolling constant 0.02"
CHUNK = 1000          # steps between two checks of the rest criterion
MAX_CHUNKS = 20
KE_REST = 1e-6        # kinetic energy per particle at rest (m g d ~ 1 here)
CONTINUE = 1000       # steps of the continued runs
# Each step's forces differ between rank counts by summation order only (~1e-16 relative).
# At rest an overlap xi ~ 1e-3 turns a position error dx into a relative force error
# ~ 1.5 dx / xi, and the damped contacts do not amplify it over CONTINUE steps: measured
# position differences 1e-15 .. 1e-14 and force differences 1e-12 .. 1e-11 of the largest;
# the bounds leave two decades for other compilers and orders.
POS_TOL = 1e-12
FORCE_TOL = 1e-9
SETUP_TOL = 1e-12


def gather(lmp, name):
    return np.array(lmp.gather_atoms(name, 1, 3), dtype=float).reshape(-1, 3)


def scene_commands():
    return [
        "units lj", "atom_style ellipsoid", "atom_modify map array", "boundary p p f",
        "comm_modify vel yes", "processors 2 2 1", "region box block 0 8 0 8 0 10",
        "create_box 1 box", "pair_style granular/ellipsoid",
        # over x < 5 only: the deposit is uneven in x, so the balancer has work to do
        "region ins block 0 5 0 8 1.5 6",
        f"fix p all pour/ellipsoid {N} 1 5821 region ins size mean 0.7 delta_r 0.3 "
        "shape 1.5 1.3 density 1 vol 0.1 200 every 1000",
        "fix bal all balance 500 1.0 shift xy 10 1.01",
    ] + dynamics_commands()


def dynamics_commands():
    """What a continued run re-specifies after read_restart."""
    return [
        f"pair_coeff * * {LAW}",
        "fix g all gravity 1.0 vector 0 0 -1",
        "fix i all nve/asphere",
        f"fix w all wall/gran/ellipsoid {LAW} zplane 0 NULL",
        "compute ke all ke", "compute er all erotate/asphere",
        "variable kep equal (c_ke+c_er)/atoms",
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
           "imbalance": imbalance, "x": gather(lmp, "x")}
    lmp.command("unfix bal")
    lmp.command(f"write_restart {restart}")
    lmp.close()
    return out


def continued(lmp, restart, newton):
    lmp.command(f"read_restart {restart}")
    lmp.commands_list(["comm_modify vel yes", f"newton {newton}"] + dynamics_commands())
    lmp.command("run 0")
    out = {"f0": gather(lmp, "f"), "t0": gather(lmp, "torque")}
    lmp.command(f"run {CONTINUE}")
    out.update({"x": gather(lmp, "x"), "f": gather(lmp, "f"), "t": gather(lmp, "torque"),
                "natoms": lmp.get_natoms()})
    return out


def barrier():
    lammps(cmdargs=ARGS).close()


def compare(name, ref, r, failures):
    fs, ts = np.abs(ref["f0"]).max(), np.abs(ref["t0"]).max()
    d_setup = max(np.abs(r["f0"] - ref["f0"]).max() / fs, np.abs(r["t0"] - ref["t0"]).max() / ts)
    d = r["x"] - ref["x"]
    d[:, :2] -= 8.0 * np.round(d[:, :2] / 8.0)       # periodic x, y
    dx = np.abs(d).max()
    df = np.abs(r["f"] - ref["f"]).max() / np.abs(ref["f"]).max()
    if r["natoms"] != ref["natoms"] or not np.isfinite(r["x"]).all():
        failures.append(f"{name}: natoms {r['natoms']} or non-finite positions")
    if not d_setup < SETUP_TOL:
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
    job = os.environ.get("PMIX_NAMESPACE", os.environ.get("OMPI_MCA_ess_base_jobid",
                                                          str(os.getppid())))
    work = os.path.join(tempfile.gettempdir(), "mpi4_ranks_" + job.replace("/", "_"))
    os.makedirs(work, exist_ok=True)
    restart = os.path.join(work, "settled.restart")
    failures = []

    settled = pour_and_settle(restart)

    # 1 rank newton on | 1 rank newton off | 2 ranks newton on, side by side
    part = ARGS + ["-partition", "1", "1", "2", "-plog", "none", "-pscreen", "none",
                   "-in", os.devnull]
    lmp = lammps(cmdargs=part)
    universe = lmp.extract_setting("universe_rank")
    which = {0: ("1 rank newton on", "on"), 1: ("1 rank newton off", "off"),
             2: ("2 ranks newton on", "on"), 3: ("2 ranks newton on", "on")}[universe]
    lmp.command("processors * * 1")
    r = continued(lmp, restart, which[1])
    lmp.close()
    if universe in (0, 1, 2):
        np.savez(os.path.join(work, f"part{universe}.npz"), **r)
    barrier()

    runs = {}
    for newton in ("on", "off"):
        lmp = lammps(cmdargs=ARGS)
        runs[newton] = continued(lmp, restart, newton)
        if newton == "off":
            lmp.finalize()
        else:
            lmp.close()

    if rank != 0:
        return
    n = N
    if settled["natoms"] != n or settled["inserted"] != n:
        failures.append(f"pour: natoms {settled['natoms']} inserted {settled['inserted']}")
    if not settled["kep"] < KE_REST:
        failures.append(f"pour not at rest after {settled['step']} steps: KE {settled['kep']}")
    if not np.isfinite(settled["x"]).all():
        failures.append("pour: non-finite positions")
    # every call leaves the load no worse; at least one call had something to do
    before, after = max(settled["imbalance"])
    if any(a > b + 1e-12 for b, a in settled["imbalance"]) or not before > after:
        failures.append(f"fix balance: imbalance before/after {settled['imbalance']}")
    ref = runs["on"]
    lines = [compare("4 ranks newton off", ref, runs["off"], failures)]
    for k, (name, _) in enumerate([("1 rank newton on", 0), ("1 rank newton off", 0),
                                   ("2 ranks newton on", 0)]):
        r = dict(np.load(os.path.join(work, f"part{k}.npz")))
        lines.append(compare(name, ref, r, failures))
    if failures:
        for f in failures:
            print(f"FAIL {f}", flush=True)
        sys.exit(1)
    print(f"mpi4_ranks: {n} poured on 4 ranks with fix balance (imbalance "
          f"{before:.3g} -> {after:.3g}), at rest after {settled['step']} steps; vs 4 ranks "
          "newton on: " + "; ".join(lines), flush=True)


if __name__ == "__main__":
    main()
