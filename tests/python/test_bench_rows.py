"""The whole-deposit benchmarks' bookkeeping (bench/bench_rows.py): a command's peak memory and
CPU time measured on a child whose allocation and work are known, its exit code kept, and a
rows.csv of other columns refused instead of appended to out of line."""
import os
import sys

import pytest

from conftest import root_dir

sys.path.insert(0, os.path.join(root_dir(), "bench"))
import bench_rows    # noqa: E402

# a child that touches 200 MB and spins for about 0.3 s of CPU time, in a grandchild (as an MPI
# rank is under mpirun): the peak must come up from the grandchild
GRANDCHILD = ("import time; b = bytearray(200 * 2**20); b[::4096] = b'x' * len(b[::4096]); "
              "t = time.process_time()\nwhile time.process_time() - t < 0.3: pass")
CHILD = "import subprocess, sys; sys.exit(subprocess.run([sys.executable, '-c', %r]).returncode)"


def test_run_measured_peak_and_cpu():
    proc, cpu, peak_mb = bench_rows.run_measured([sys.executable, "-c", CHILD % GRANDCHILD])
    assert proc.returncode == 0
    assert 200 <= peak_mb < 200 + 100    # the bytearray plus an interpreter
    assert 0.3 <= cpu < 5


def test_run_measured_keeps_the_exit_code_and_output():
    proc, _, peak_mb = bench_rows.run_measured(
        [sys.executable, "-c", "import sys; print('out'); sys.exit(3)"])
    assert proc.returncode == 3 and proc.stdout == "out\n"
    assert 0 < peak_mb < 100


def test_append_row_refuses_other_columns(tmp_path):
    path = str(tmp_path / "rows.csv")
    bench_rows.append_row(path, {"a": 1, "b": 2}, ["a", "b"])
    bench_rows.append_row(path, {"a": 3, "b": 4}, ["a", "b"])
    assert bench_rows.read_rows(path) == [{"a": "1", "b": "2"}, {"a": "3", "b": "4"}]
    with pytest.raises(SystemExit) as e:
        bench_rows.append_row(path, {"a": 5, "c": 6, "b": 7}, ["a", "c", "b"])
    assert "another version" in str(e.value)
    assert len(bench_rows.read_rows(path)) == 2
