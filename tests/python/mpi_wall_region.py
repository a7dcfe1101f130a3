"""fix wall/gran/region/ellipsoid gives the same forces on 1 and 2 MPI ranks.

Run as `mpirun -np 2 python3 mpi_wall_region.py`; exits non-zero on failure. Triaxial
ellipsoids against the side, the floor and the corner of a moving cylinder region and
inside a sphere region, the domain split along x (`processors * 1 1`) through both regions:
the per-atom forces and torques (gathered by ID), the per-atom contacts array and the fix's
face forces after run 0 and after 40 steps (with tangential history, so that the history
travels between ranks), and the forces and positions after the region is defined again
(narrower) and 40 steps more, equal those of a serial copy on every rank.
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mpi_helpers as mpi  # noqa: E402

LAW = "hertz 1e4 50 tangential history 2e3 0.5"


def scene(region):
    rng = np.random.default_rng(17)
    lines = ["units lj", "atom_style ellipsoid", "atom_modify map array", "boundary f f f",
             "comm_modify vel yes", "processors * 1 1", "region box block 0 4 0 4 0 4",
             "create_box 1 box"]
    positions = []
    for k in range(12):    # against the side, on a ring around the split plane x = 2
        angle = 2 * math.pi * k / 12 + 0.1
        positions.append((2 + 1.28 * math.cos(angle), 2 + 1.28 * math.sin(angle),
                          1.0 + 0.15 * (k % 3)))
    positions += [(1.7, 2.3, 0.62), (2.3, 1.6, 0.63), (3.25, 2.0, 0.6)]    # floor, corner
    for k, p in enumerate(positions):
        q = rng.normal(size=4)
        lines += [f"create_atoms 1 single {p[0]} {p[1]} {p[2]}",
                  f"set atom {k + 1} shape 0.5 0.34 0.24",
                  f"set atom {k + 1} quat {q[1]} {q[2]} {q[3]} {math.degrees(q[0])}"]
    lines += ["set type 1 density 1.0", "velocity all create 0.05 4821 loop geom",
              "variable dx equal 0.3*time", region,
              f"fix w all wall/gran/region/ellipsoid {LAW} region r contacts",
              "fix i all nve/asphere", "timestep 1e-4"]
    return "\n".join(lines) + "\n"


REGIONS = ["region r cylinder z 2 2 1.5 0.5 3.5 move v_dx NULL NULL",
           "region r sphere 2 2 2 1.5 rotate v_dx 2 2 2 0 0 1"]


def results(lmp, region):
    lmp.commands_string(scene(region))
    out = {}
    for steps in (0, 40):
        lmp.command(f"run {steps}")
        n = lmp.get_natoms()
        for name in ("f", "torque"):
            out[f"{name}{steps}"] = np.array(lmp.gather_atoms(name, 1, 3)).reshape(n, 3)
        faces = 3 if "cylinder" in region else 1    # closed cylinder: lo cap, hi cap, side
        out[f"vector{steps}"] = np.array([lmp.extract_fix("w", 0, 1, k)
                                          for k in range(3 * faces)])
        out[f"x{steps}"] = np.array(lmp.gather_atoms("x", 1, 3)).reshape(n, 3)
    # the region defined again between runs, narrower: every rank rebuilds the walls and
    # restarts its atoms' wall histories
    lmp.commands_string(f"region r delete\n{region.replace(' 1.5 ', ' 1.45 ')}\nrun 40")
    for name in ("f", "x"):
        out[f"{name}_again"] = np.array(lmp.gather_atoms(name, 1, 3)).reshape(n, 3)
    return out


def main():
    nprocs = mpi.world_size()
    failures, last = [], None
    for region in REGIONS:
        par = mpi.parallel()
        r_par = results(par, region)
        par.close()
        ser = mpi.serial_per_rank(nprocs)
        r_ser = results(ser, region)
        ser.close()
        last = ser
        if not np.abs(r_ser["vector0"]).max() > 0.0:
            failures.append(f"{region}: no wall force at all")
        for key, a in r_ser.items():
            b = r_par[key]
            scale = max(np.abs(a).max(), 1e-300)
            if a.shape != b.shape or not np.allclose(a, b, rtol=1e-10, atol=1e-10 * scale):
                failures.append(f"{region} {key}: serial {a} parallel {b}")
    mpi.finish(last, failures, f"mpi_wall_region: 1 rank == {nprocs} ranks")


if __name__ == "__main__":
    main()
