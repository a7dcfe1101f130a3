"""The cost curve's table (bench/cost_curve/cost_table.py) on made-up rows and logs whose
answers are known: the medians, the time per particle-step, the memory per particle, the
communication's share summed over a log's runs, and the exponents in N."""
import csv
import math
import os
import sys

import pytest

from conftest import root_dir

sys.path.insert(0, os.path.join(root_dir(), "bench", "cost_curve"))
import cost_table    # noqa: E402

LOG = """Per MPI rank memory allocation (min/avg/max) = 10 | 11 | {mem} Mbytes
Loop time of {loop1} on 1 procs for 1000 steps with {n} atoms
Comm    | 0.1        | {comm1}      | 0.3        |   0.0 |  5.00
Per MPI rank memory allocation (min/avg/max) = 10 | 11 | 1.5 Mbytes
Loop time of {loop2} on 1 procs for 1000 steps with {n} atoms
Comm    | 0.1        | {comm2}      | 0.3        |   0.0 |  5.00
"""


def make_runs(folder):
    """N = 1000, 4000, 16000 with CPU exactly linear in N (1 us per particle-step at 20 000
    steps), two seeds each (CPU +-10 %), memory 2 kB per particle"""
    rows = []
    for n in (1000, 4000, 16000):
        for seed, f in ((1, 0.9), (2, 1.1)):
            rows.append({"setting": "default", "seed": seed, "N": n, "np": 1,
                         "cpu_seconds": f * n * 20000 * 1e-6, "steps": 20000})
            run = folder / ("default-N%d-s%d" % (n, seed))
            run.mkdir()
            (run / "log.lammps").write_text(LOG.format(mem=2 * n / 1024, n=n, loop1=3.0,
                                                       loop2=1.0, comm1=0.2, comm2=0.2))
    rows.append({"setting": "fast", "seed": 1, "N": 1000, "np": 1, "cpu_seconds": 1.0,
                 "steps": 1})    # another setting: left out
    with open(folder / "rows.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def test_cost_table_by_hand(tmp_path):
    make_runs(tmp_path)
    sizes, fits = cost_table.write(cost_table.load([str(tmp_path)]), str(tmp_path / "out"))
    assert sorted(sizes) == [(1000, 1), (4000, 1), (16000, 1)]
    for (n, _), v in sizes.items():
        assert v["seeds"] == 2 and v["steps"] == 20000
        assert v["cpu_seconds"] == pytest.approx(n * 0.02)    # the median of 0.9 and 1.1
        assert v["us_per_particle_step"] == pytest.approx(1.0)
        assert v["kb_per_particle"] == pytest.approx(2.0)
        assert v["comm_share"] == pytest.approx(0.4 / 4.0)    # summed over the log's runs
    assert fits["cpu_seconds"] == pytest.approx(1.0)
    assert fits["us_per_particle_step"] == pytest.approx(0.0, abs=1e-9)
    assert os.path.getsize(tmp_path / "out" / "cost_curve.png") > 5000
    assert "| 16000 | 1 | 2 | 320 | 20000 | 1.00 |" in (tmp_path / "out" / "table.md").read_text()
    assert math.isnan(cost_table.read_log(str(tmp_path / "rows.csv"))[1])    # no loop time
