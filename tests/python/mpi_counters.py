"""Pair::extract("counters/NAME") is this rank's count and not a collective call.

Run under `mpirun -np 2`: a pair of touching spheres on each side of the rank boundary. Rank 0
alone asks for a counter; then both ranks run LAMMPS again, so a collective inside the
extract would leave the ranks in different collectives (a hang, ended by the alarm, or mixed
messages). Each rank's count goes to a shared file; their sum must equal compute pair's
vector, which is the sum over ranks.
"""
import os
import signal
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mpi_helpers import finish, job_folder, parallel  # noqa: E402

signal.alarm(120)    # a rank stuck in an unmatched collective fails instead of hanging

lmp = parallel()
rank = lmp.extract_setting("world_rank")
lmp.commands_string("""
units lj
atom_style ellipsoid
comm_modify vel yes
processors 2 1 1
region box block 0 8 0 4 0 4
create_box 1 box
create_atoms 1 single 1.0 2 2
create_atoms 1 single 1.98 2 2
create_atoms 1 single 5.0 2 2
create_atoms 1 single 5.98 2 2
set type 1 shape 1 1 1
set type 1 density 1
pair_style granular/ellipsoid
pair_coeff * * hertz 1e4 10
compute counters all pair granular/ellipsoid
fix integrate all nve/asphere
run 5
""")
mine = lmp.extract_pair("counters/pairs") if rank == 0 else None
lmp.command("run 5")    # collective: both ranks must arrive here
local = lmp.extract_pair("counters/pairs")
total = float(lmp.numpy.extract_compute("counters", 0, 1)[0])    # summed over the ranks
folder = job_folder("ed_counters_")
with open(os.path.join(folder, f"rank{rank}.tmp"), "w") as f:
    f.write(repr(local))
os.replace(os.path.join(folder, f"rank{rank}.tmp"), os.path.join(folder, f"rank{rank}"))
paths = [os.path.join(folder, f"rank{r}") for r in range(2)]
while not all(os.path.exists(p) for p in paths):    # the alarm bounds the wait
    time.sleep(0.05)
counts = [float(open(p).read()) for p in paths]
failures = []
if rank == 0 and not (mine is not None and mine > 0):
    failures.append(f"rank 0's lone extract gave {mine}")
if sum(counts) != total:
    failures.append(f"ranks' counts {counts} do not sum to compute pair's {total}")
if local >= total:
    failures.append(f"this rank's count {local} is not a part of the total {total}")
finish(lmp, failures, "mpi_counters: extract is per rank, not collective; ranks sum to compute pair")
