"""The bookkeeping the whole-deposit benchmarks share (bench/clumps, bench/accuracy,
bench/cost_curve): a run's CPU time, peak memory and commit, the rows.csv of the runs done
so far, which lets an interrupted invocation continue where it stopped, and the LAMMPS log
lines they read.

    bench_rows.py --peak-rss CMD [ARG ...]   runs CMD, then prints its largest process's peak
                                             resident set (run_measured's wrapper)"""
import csv
import json
import os
import re
import resource
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def children_cpu():
    """User + system CPU seconds of the finished child processes (and theirs): the cost of a
    run without the share of the cores that other jobs took (wall time on a loaded machine)."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


# LAMMPS's lines after each run: its loop time, ranks, steps and atoms; its CPU use; the
# largest memory estimate per rank; and the pair's counters (cumulative since the pair was
# defined, summed over the ranks)
LOOP = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms")
CPU_USE = re.compile(r"^(\S+)% CPU use with")
MEMORY = re.compile(r"^Per MPI rank memory allocation \(min/avg/max\) = \S+ \| \S+ \| (\S+) Mbytes")
COUNTERS = "granular/ellipsoid counters: "


def read_counters(line):
    """the pair's counters of a log line as a dict; None if the line has none"""
    return json.loads(line[len(COUNTERS):]) if line.startswith(COUNTERS) else None


PEAK_RSS = "bench_rows: peak resident set of the largest process (kB): "


def run_measured(cmd):
    """cmd run to its end: (its CompletedProcess with the output captured, the CPU seconds of
    its processes, the peak resident set in MB of the largest of them, e.g. an MPI rank).
    A wrapper process runs cmd, so that getrusage's children's peak covers only this command's
    process tree (Linux carries a child's largest descendant up to its parent)."""
    cpu0 = children_cpu()
    proc = subprocess.run([sys.executable, os.path.abspath(__file__), "--peak-rss"] + cmd,
                          capture_output=True, text=True)
    cpu = children_cpu() - cpu0
    peak_kb = [line[len(PEAK_RSS):] for line in proc.stderr.splitlines()
               if line.startswith(PEAK_RSS)]
    return proc, cpu, float(peak_kb[-1]) / 1024 if peak_kb else float("nan")


def commit():
    """the checkout's short commit, +dirty with uncommitted changes to tracked files"""
    head = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                          capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True).stdout.strip()
    return head + ("+dirty" if dirty else "")


def read_rows(path):
    """the rows of a rows.csv as dicts of strings; none if it does not exist yet"""
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def append_row(path, row, fields):
    """one run's row, the header first in a new file; a file of other columns (an older
    version's) is refused rather than appended to out of line"""
    new = not os.path.exists(path)
    if not new:
        with open(path) as f:
            header = next(csv.reader(f), None)
        if header != list(fields):
            sys.exit("%s holds the columns of another version of this benchmark: give another "
                     "--out (or move the file away)" % path)
    with open(path, "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        if new:
            w.writeheader()
        w.writerow({k: row[k] for k in fields})


if __name__ == "__main__" and len(sys.argv) > 2 and sys.argv[1] == "--peak-rss":
    code = subprocess.run(sys.argv[2:]).returncode
    print(PEAK_RSS + str(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss),
          file=sys.stderr)
    sys.exit(code)
