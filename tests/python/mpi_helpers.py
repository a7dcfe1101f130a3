"""What the MPI checks (mpi_*.py, run under `mpirun -np 2 python3 FILE`) share: LAMMPS
instances on all ranks or one serial copy per rank, and the exit that reports failures.

A serial copy per rank (`-partition Nx1`) runs the same input on every rank; global values
are reduced on every rank, so each rank compares its own serial result with the parallel one.
"""
import os
import sys
import tempfile

from lammps import lammps

ARGS = ["-log", "none", "-screen", "none", "-nocite"]


def world_size():
    probe = lammps(cmdargs=ARGS)
    nprocs = probe.extract_setting("world_size")
    probe.close()
    return nprocs


def parallel():
    """A LAMMPS instance on all ranks."""
    return lammps(cmdargs=ARGS)


def serial_per_rank(nprocs):
    """A LAMMPS instance of its own on every rank (the library interface never reads the
    input file that -partition requires)."""
    return lammps(cmdargs=ARGS + ["-partition", f"{nprocs}x1", "-plog", "none", "-pscreen",
                                  "none", "-in", os.devnull])


def finish(lmp, failures, success):
    """MPI_Finalize through lmp (mpirun then sees a clean exit); print every failure with the
    rank and exit 1, or print `success` on rank 0."""
    lmp.finalize()
    rank = int(os.environ.get("OMPI_COMM_WORLD_RANK", os.environ.get("PMI_RANK", "0")))
    if failures:
        for f in failures:
            print(f"[rank {rank}] FAIL {f}", flush=True)
        sys.exit(1)
    if rank == 0:
        print(success, flush=True)


def job_folder(prefix):
    """A scratch folder of the same name on every rank of one MPI job (the job's Open MPI /
    PMIx namespace is shared by its ranks)."""
    job = os.environ.get("PMIX_NAMESPACE", os.environ.get("OMPI_MCA_ess_base_jobid",
                                                          str(os.getppid())))
    work = os.path.join(tempfile.gettempdir(), prefix + job.replace("/", "_"))
    os.makedirs(work, exist_ok=True)
    return work
