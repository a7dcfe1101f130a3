"""A pour on 2 MPI ranks vs 1 rank, and a restart file written on 2 ranks read on 1.

Run as `mpirun -np 2 python3 mpi_robustness.py`; exits non-zero on failure.

The pour of scenes.mid_pour_commands (triaxial ellipsoids, pair and wall with tangential
history and rolling, x and y periodic) runs once on all ranks (`processors 2 1 1`: the
subdomain boundary at x = 4 and the periodic boundary at x = 0 both cut the pile, so
contacts with history cross both) and once serially on every rank (`-partition Nx1`).
Checks:
* no particle lost, all N inserted on both;
* set-up forces at mid-pour agree to 1e-5 of the largest (the runs differ only in summation
  order; round-off grown over 3000 steps, measured 2.6e-7), the final packing density
  agrees to 0.03;
* the restart file written by the 2-rank run, read by a 1-rank run, gives the 2-rank
  set-up forces to 1e-12 (contact and plane histories survive the change of rank count).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mpi_helpers as mpi  # noqa: E402
import scenes  # noqa: E402


def gather(lmp, name):
    return np.array(lmp.gather_atoms(name, 1, 3), dtype=float).reshape(-1, 3)


def pour(lmp, workfile):
    lmp.command("processors * 1 1")
    lmp.commands_list(["pair_style granular/ellipsoid"] + scenes.mid_pour_commands())
    lmp.command(f"run {scenes.MID_POUR_HALF}")
    lmp.command("run 0")
    out = {"f": gather(lmp, "f"), "t": gather(lmp, "torque"), "x": gather(lmp, "x")}
    if workfile:
        lmp.command(f"write_restart {workfile}")
    lmp.command(f"run {scenes.MID_POUR_REST}")
    out["natoms"] = lmp.get_natoms()
    out["inserted"] = lmp.extract_fix("p", 0, 0)
    out["pk"] = float(lmp.numpy.extract_compute("pk", 0, 1)[0])
    out["x_end"] = gather(lmp, "x")
    return out


def main():
    nprocs = mpi.world_size()
    restart = os.path.join(mpi.job_folder("mpi_robustness_"), "par.restart")
    failures = []

    par = mpi.parallel()
    r_par = pour(par, restart)
    par.close()

    ser = mpi.serial_per_rank(nprocs)
    r_ser = pour(ser, None)
    ser.close()

    re = mpi.serial_per_rank(nprocs)
    re.command(f"read_restart {restart}")
    re.command("comm_modify vel yes")
    re.commands_list(scenes.mid_pour_continuation())
    re.command("timestep 1e-3")
    re.command("run 0")
    f_re, t_re = gather(re, "f"), gather(re, "torque")
    natoms_re = re.get_natoms()

    n = scenes.MID_POUR_N
    for name, r in (("2 ranks", r_par), ("1 rank", r_ser)):
        if r["natoms"] != n or r["inserted"] != n:
            failures.append(f"{name}: natoms {r['natoms']} inserted {r['inserted']} != {n}")
        if not np.isfinite(r["x_end"]).all():
            failures.append(f"{name}: non-finite positions")
    scale = np.abs(r_ser["f"]).max()
    df = np.abs(r_par["f"] - r_ser["f"]).max() / scale
    if not df < 1e-5:
        failures.append(f"mid-pour set-up forces 2 ranks vs 1: {df:.3g} of the largest")
    dpk = abs(r_par["pk"] - r_ser["pk"])
    if not dpk < 0.03:
        failures.append(f"packing 2 ranks {r_par['pk']} vs 1 rank {r_ser['pk']}")
    scale_t = np.abs(r_par["t"]).max()
    dre = max(np.abs(f_re - r_par["f"]).max() / scale, np.abs(t_re - r_par["t"]).max() / scale_t)
    if natoms_re != len(r_par["f"]) or not dre < 1e-12:
        failures.append(f"restart from 2 ranks read on 1: natoms {natoms_re}, force diff {dre:.3g}")
    mpi.finish(re, failures,
               f"mpi_robustness: pour of {n} on {nprocs} ranks == 1 rank (set-up forces "
               f"{df:.2g} of max, packing {r_par['pk']:.4f} vs {r_ser['pk']:.4f}); restart "
               f"written on {nprocs} read on 1: forces to {dre:.2g}")


if __name__ == "__main__":
    main()
