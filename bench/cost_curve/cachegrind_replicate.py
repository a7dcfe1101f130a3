#!/usr/bin/env python3
"""Simulated cache misses per particle-step of the replicated deposit (valgrind's cachegrind):
repeatable counts where the timings of run_replicate.py are noisy, to tell whether the
working set leaving the caches makes a larger deposit dearer per particle.

    ./ellipsoid-dep python bench/cost_curve/cachegrind_replicate.py --restart DEPOSIT.restart
        [--k 1 4] [--steps 50] [--out runs/cachegrind] [--results results/cost_curve]

Per k, in.replicate runs twice under cachegrind (cache simulation on, the host's caches as
valgrind reads them), without warm-up, for STEPS and for 2 x STEPS steps: the difference of the
two runs' totals is the cost of STEPS steps at rest, free of the set-up (reading, replicating,
the first neighbour list). The table (table_cachegrind.md in --results) gives per particle-step
the instructions, the first-level data misses and the last-level data misses, and the caches
valgrind simulated.
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "tools"))
import _paths  # noqa: E402,F401  (tools/_paths.py: the tools' topic folders on sys.path)
from deposit_run import lmp_binary  # noqa: E402
from run_replicate import INPUT, read_log  # noqa: E402


def read_counts(path):
    """a cachegrind output file's totals {event: count} and its simulated caches (desc lines)"""
    events, totals, caches = None, None, []
    with open(path) as f:
        for line in f:
            if line.startswith("desc:"):
                caches.append(line[len("desc:"):].strip())
            elif line.startswith("events:"):
                events = line.split()[1:]
            elif line.startswith("summary:"):
                totals = [int(x) for x in line.split()[1:]]
    if events is None or totals is None:
        raise ValueError("%s: no events and summary lines" % path)
    return dict(zip(events, totals)), caches


def count(restart, k, steps, out):
    """cachegrind's totals of in.replicate with k x k copies, no warm-up, `steps` steps"""
    os.makedirs(out, exist_ok=True)
    result = os.path.join(out, "cachegrind.out")
    cmd = ["valgrind", "--tool=cachegrind", "--cache-sim=yes",
           "--cachegrind-out-file=" + result, lmp_binary(), "-in", INPUT, "-log",
           os.path.join(out, "log.lammps"), "-nocite", "-screen", "none", "-var", "restart",
           restart, "-var", "k", str(k), "-var", "warm", "0", "-var", "steps", str(steps),
           "-var", "out", out]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit("cachegrind_replicate: k %d, %d steps failed (%s):\n%s"
                 % (k, steps, out, proc.stderr[-2000:]))
    os.remove(os.path.join(out, "replicate.data"))
    return read_counts(result)


def per_particle_step(short, long, n, steps):
    """the events of `steps` more steps (long minus short) per particle-step: instructions,
    first-level and last-level data misses (reads + writes)"""
    diff = {e: long[e] - short[e] for e in long}
    ps = n * steps
    return {"instructions": diff["Ir"] / ps,
            "d1_misses": (diff["D1mr"] + diff["D1mw"]) / ps,
            "ll_data_misses": (diff["DLmr"] + diff["DLmw"]) / ps}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--restart", required=True, help="a deposit at rest (in.deposit save 1)")
    ap.add_argument("--k", type=int, nargs="+", default=[1, 4])
    ap.add_argument("--steps", type=int, default=50)
    ap.add_argument("--out", default=os.path.join(ROOT, "runs", "cachegrind"))
    ap.add_argument("--results", default=os.path.join(ROOT, "results", "cost_curve"))
    args = ap.parse_args(argv)
    if not os.path.isfile(args.restart):
        sys.exit("cachegrind_replicate: --restart %s: no such file" % args.restart)
    if min(args.k) < 1 or args.steps < 1:
        sys.exit("cachegrind_replicate: --k and --steps must be positive")
    lines = ["| k x k | N | instructions per particle-step | D1 misses per particle-step | "
             "LL data misses per particle-step |", "|---|---|---|---|---|"]
    caches = []
    for k in sorted(args.k):
        print("cachegrind_replicate: %d x %d copies, %d and %d steps ..."
              % (k, k, args.steps, 2 * args.steps), flush=True)
        short, caches = count(os.path.abspath(args.restart), k, args.steps,
                              os.path.join(args.out, "k%d-short" % k))
        long_out = os.path.join(args.out, "k%d-long" % k)
        long, _ = count(os.path.abspath(args.restart), k, 2 * args.steps, long_out)
        n = read_log(os.path.join(long_out, "log.lammps"))["N"]
        c = per_particle_step(short, long, n, args.steps)
        lines.append("| %d x %d | %d | %.0f | %.1f | %.2f |"
                     % (k, k, n, c["instructions"], c["d1_misses"], c["ll_data_misses"]))
        print(lines[-1], flush=True)
    lines.append("")
    lines.append("Simulated caches (valgrind): " + "; ".join(caches) + ".")
    os.makedirs(args.results, exist_ok=True)
    with open(os.path.join(args.results, "table_cachegrind.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
