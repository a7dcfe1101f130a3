"""compute packing/profile gives the same profile on 1 and 2 MPI ranks.

Run as `mpirun -np 2 python3 mpi_packing_profile.py`; exits non-zero on failure.

Each configuration runs on all ranks, split along x (`processors * 1 1`: particles straddle
the split plane and the periodic boundary) and along z (`processors 1 1 *`: one bin holds
particles of both ranks), and once with `-partition Nx1`, where every rank runs the same input
serially; the global array is reduced on every rank, so each rank compares its own serial
result with the parallel ones.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mpi_helpers as mpi  # noqa: E402
import placed_scenes as ps  # noqa: E402

COMPUTES = """
compute p1 all packing/profile 0.13
compute p2 all packing/profile 0.5 zlo 0.7 zhi 3.1
region lowz block INF INF INF INF INF 1.6
group low region lowz
compute p3 low packing/profile 0.21
"""
ARRAYS = ["p1", "p2", "p3"]


def configurations():
    box, parts = ps.lattice(n=(4, 4, 4), seed=6)
    # shift by half a cell in x: a column of particles straddles the periodic boundary
    parts = [(np.array([(x[0] + 0.5) % 4.0, x[1], x[2]]), s, q) for x, s, q in parts]
    yield "lattice", box, parts, "p p f"
    box, parts, _ = ps.network()
    yield "network, periodic z", box, parts, "p p p"


def results(lmp, box, parts, periodic, processors):
    ps.build_system(box, parts, periodic=periodic, lmp=lmp, extra=f"processors {processors}")
    lmp.commands_string(COMPUTES)
    lmp.command("run 0")
    return {c: ps.array(lmp, c) for c in ARRAYS}


def main():
    nprocs = mpi.world_size()
    failures = []
    last = None
    for name, box, parts, periodic in configurations():
        ser = mpi.serial_per_rank(nprocs)
        r_ser = results(ser, box, parts, periodic, "* * *")
        ser.close()
        last = ser
        for processors in ("* 1 1", "1 1 *"):
            par = mpi.parallel()
            r_par = results(par, box, parts, periodic, processors)
            par.close()
            for key in ARRAYS:
                a, b = r_ser[key], r_par[key]
                if a.shape != b.shape or not np.allclose(a, b, rtol=1e-12, atol=1e-14):
                    failures.append(f"{name} processors {processors} {key}: serial {a} "
                                    f"parallel {b}")
        if not r_ser["p1"][:, 2].sum() > 0:
            failures.append(f"{name}: empty profile")
    mpi.finish(last, failures, f"mpi_packing_profile: 1 rank == {nprocs} ranks")


if __name__ == "__main__":
    main()
