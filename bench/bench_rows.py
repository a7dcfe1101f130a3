"""The bookkeeping the whole-deposit benchmarks share (bench/clumps, bench/accuracy,
bench/cost_curve): a run's CPU time and commit, and the rows.csv of the runs done so far,
which lets an interrupted invocation continue where it stopped."""
import csv
import os
import resource
import subprocess

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def children_cpu():
    """User + system CPU seconds of the finished child processes (and theirs): the cost of a
    run without the share of the cores that other jobs took (wall time on a loaded machine)."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


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
    """one run's row, the header first in a new file"""
    new = not os.path.exists(path)
    with open(path, "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        if new:
            w.writeheader()
        w.writerow({k: row[k] for k in fields})
