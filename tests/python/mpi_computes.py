"""Same results for compute packing/ellipsoid, contact/histo, force/histo, orient/histo,
unbalanced/force on 1 and 2 MPI ranks.

Run as `mpirun -np 2 python3 mpi_computes.py`; exits non-zero on failure.

Each configuration runs twice: once on all ranks (domain split along x, `processors * 1 1`,
contacts straddling the split plane and the periodic boundary, so ghost contacts exist) and
once with `-partition Nx1`, where every rank runs the same input serially. Global values are
reduced on every rank, so each rank compares its own serial result with the parallel one.
Both newton_pair settings are checked (off: a contact across ranks is in both ranks' lists;
on: in one list only).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mpi_helpers as mpi  # noqa: E402
import placed_scenes as ps  # noqa: E402

COMPUTES = """
compute pk all packing/ellipsoid EDGE EDGE
compute pr all packing/ellipsoid 1.2 6.0 rattler 3
compute pa all packing/ellipsoid auto bottom 0.5 top 0.5
compute pc all packing/ellipsoid auto bottom 0.5 top 0.5 surface columns
compute ch all contact/histo bins 12
compute cs all contact/histo bins 8 slab pa select center
compute cz all contact/histo bins 8 zlo 1.0 zhi 2.0
compute ol all orient/histo bins 10
compute os all orient/histo axis short bins 7 fold yes slab pa
region lowz block INF INF INF INF INF 1.6
group low region lowz
compute pg low packing/ellipsoid EDGE EDGE
compute cg low contact/histo bins 8
compute cw all contact/histo bins 12 weight force
compute cf all contact/histo bins 8 slab pa select center weight force
compute fh all force/histo bins 10 max 4
compute fs low force/histo bins 6 max 3 slab pa select center
compute ub all unbalanced/force
compute ug low unbalanced/force
"""
VECTORS = ["pk", "pr", "pa", "pc", "ch", "cs", "cz", "ol", "os", "pg", "cg", "cw", "cf", "fh", "fs",
           "ub", "ug"]
ARRAYS = ["ch", "cs", "cz", "ol", "os", "cg", "cw", "cf", "fh", "fs"]


def configurations():
    box, parts, _ = ps.network()
    yield "network", box, parts
    box, parts = ps.oblate_stacks(ncol=4, height=5)
    # shift by half a column: one column straddles the rank split, one the periodic boundary
    L = box[0][1]
    parts = [(np.array([(x[0] + 1.3) % L, x[1], x[2]]), s, q) for x, s, q in parts]
    yield "oblate stacks", box, parts
    box, parts, _ = ps.random_pairs(npairs=1000)
    yield "random pairs", box, parts


def results(lmp, box, parts, newton):
    ps.build_system(box, parts, newton=newton, lmp=lmp, extra="processors * 1 1")
    lmp.commands_string(COMPUTES)
    lmp.command("run 0")
    out = {}
    for c in VECTORS:
        out["v_" + c] = ps.vector(lmp, c)
    for c in ARRAYS:
        out["a_" + c] = ps.array(lmp, c)
    return out


def main():
    nprocs = mpi.world_size()
    last = None
    failures = []
    for name, box, parts in configurations():
        for newton in ("off", "on"):
            par = mpi.parallel()
            r_par = results(par, box, parts, newton)
            par.close()
            ser = mpi.serial_per_rank(nprocs)
            r_ser = results(ser, box, parts, newton)
            ser.close()
            last = ser
            for key in r_ser:
                a, b = r_ser[key], r_par[key]
                if a.shape != b.shape or not np.allclose(a, b, rtol=1e-11, atol=1e-12):
                    failures.append(f"{name} newton {newton} {key}: serial {a} parallel {b}")
            n_contacts = r_ser["v_ch"][8]
            if n_contacts <= 0:
                failures.append(f"{name}: no contacts at all")
    mpi.finish(last, failures, f"mpi_computes: 1 rank == {nprocs} ranks for all computes")


if __name__ == "__main__":
    main()
