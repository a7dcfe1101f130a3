"""A pour into a container (needles and discs from a region wider than the container's side,
fix wall/gran/region/ellipsoid) on 2 MPI ranks vs 1 rank: the same particles are rejected at
the wall and the same are inserted, at the same places bit for bit (every rank makes the
same decisions against the same walls).

Run as `mpirun -np 2 python3 mpi_pour_container.py`; exits non-zero on failure.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mpi_helpers as mpi  # noqa: E402

LAW = "hertz 1e5 50 tangential history 2e4 0.5"


def pour(lmp):
    lmp.commands_list([
        "units lj", "atom_style ellipsoid", "atom_modify map array", "boundary f f f",
        "comm_modify vel yes", "processors * 1 1", "region box block -3 3 -3 3 -0.5 14",
        "create_box 2 box", "region silo cylinder z 0 0 2.5 0 13.5 open 2",
        "pair_style granular/ellipsoid", f"pair_coeff * * {LAW}",
        f"fix silo all wall/gran/region/ellipsoid {LAW} region silo",
        "region ins cylinder z 0 0 2.95 8 12",
        "fix needles all pour/ellipsoid 10 1 4711 region ins size 0.35 0.35 shape 10 1 "
        "vol 0.1 50 every 100000",
        "fix discs all pour/ellipsoid 7 2 4712 region ins size 0.35 0.35 shape 1 20 "
        "vol 0.1 50 every 100000",
        "fix g all gravity 1.0 vector 0 0 -1", "fix i all nve/ellipsoid", "timestep 2e-4",
        "run 1"])
    return {"x": np.array(lmp.gather_atoms("x", 1, 3), dtype=float).reshape(-1, 3),
            "walled": [lmp.extract_fix(f, 0, 1, 4) for f in ("needles", "discs")],
            "natoms": lmp.get_natoms()}


def main():
    nprocs = mpi.world_size()
    par = mpi.parallel()
    r_par = pour(par)
    par.close()
    ser = mpi.serial_per_rank(nprocs)
    r_ser = pour(ser)
    failures = []
    if r_par["natoms"] != 17 or r_ser["natoms"] != 17:
        failures.append(f"natoms {r_par['natoms']} on {nprocs} ranks, {r_ser['natoms']} on 1")
    if r_par["walled"] != r_ser["walled"] or not sum(r_par["walled"]) > 0:
        failures.append(f"trials at the wall {r_par['walled']} vs {r_ser['walled']}")
    if r_par["x"].shape != r_ser["x"].shape or not np.array_equal(r_par["x"], r_ser["x"]):
        failures.append("inserted positions differ between the rank counts")
    mpi.finish(ser, failures,
               f"mpi_pour_container: {r_par['natoms']} inserted on {nprocs} ranks == 1 rank, "
               f"bit for bit; trials at the wall {r_par['walled']}")


if __name__ == "__main__":
    main()
