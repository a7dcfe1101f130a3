#!/usr/bin/env python3
"""The code's own growth with N (issue 32, item 3): a settled default deposit replicated k x k
times in x and y (in.replicate), so that every N holds the same particles with the same
contacts; the CPU time per particle-step of a run at rest then changes with N only through the
code and the machine (caches, lists, communication), not through the protocol (the steps to
rest and the contacts per step, which grow with N in a whole deposit: cost_table.py).

    ./ellipsoid-dep bench replicate --restart DEPOSIT.restart [--k 1 2 4 8] [--np 1]
                                    [--repeats 3] [--warm 1000] [--steps 2000]
                                    [--out runs/replicate] [--results results/cost_curve]

DEPOSIT.restart is a deposit at rest written by examples/deposit/in.deposit -var save 1. The
sizes run one at a time, smallest first, and the round of sizes is repeated (the machine's
speed drifts: a drift reaches every size alike); the table gives per size the medians over
the repeats of the CPU time per particle-step of the measured run (LAMMPS's loop time times its CPU use times the ranks), the
contacts per particle-step, the CPU time per contact-step, the loop's shares (Pair, Neigh,
Comm, Modify, Other) and LAMMPS's memory estimate per particle. Writes table_replicate.md and
rows_replicate.csv to --results.
"""
import argparse
import os
import re
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import _paths  # noqa: E402,F401  (tools/_paths.py: the tools' topic folders on sys.path)
from bench_rows import (CPU_USE, LOOP, MEMORY, append_row, commit, read_counters,  # noqa: E402
                        read_rows)
from deposit_run import lmp_binary  # noqa: E402

INPUT = os.path.join(HERE, "in.replicate")
SECTIONS = ["Pair", "Neigh", "Comm", "Modify", "Output", "Other"]
MEASURES = ["steps", "loop_seconds", "cpu_use", "us_per_particle_step",
            "contacts_per_particle_step", "ns_per_contact_step", "memory_mb_per_rank",
            "kb_per_particle"] + ["share_" + s.lower() for s in SECTIONS]
FIELDS = ["k", "N", "np", "repeat"] + MEASURES + ["commit", "started_utc", "load_start",
                                                  "load_end"]

SECTION = re.compile(r"^(\w+)\s+\|.*\|\s*(\S+)\s*$")    # a section's name and its %total


def read_log(path):
    """the last run of a LAMMPS log: its loop time, ranks, steps, atoms, CPU use, the loop's
    shares per section, the largest memory estimate, and the pair's contacts in that run (its
    counters are cumulative: the last line minus the one before)"""
    runs, memory, counters = [], 0.0, []
    with open(path) as f:
        for line in f:
            m = LOOP.match(line)
            if m:
                runs.append({"loop_seconds": float(m.group(1)), "np": int(m.group(2)),
                             "steps": int(m.group(3)), "N": int(m.group(4)), "shares": {}})
                continue
            m = CPU_USE.match(line)
            if m and runs:
                runs[-1]["cpu_use"] = float(m.group(1)) / 100
                continue
            m = MEMORY.match(line)
            if m:
                memory = max(memory, float(m.group(1)))
                continue
            c = read_counters(line)
            if c is not None:
                counters.append(c["contacts"])
                continue
            m = SECTION.match(line)
            if m and runs and m.group(1) in SECTIONS:
                runs[-1]["shares"][m.group(1)] = float(m.group(2)) / 100
    if not runs or len(counters) < 2:
        raise ValueError("%s: no measured run (Loop time and two counter lines)" % path)
    run = runs[-1]
    run["memory_mb_per_rank"] = memory
    run["contacts"] = counters[-1] - counters[-2]
    return run


def measure(restart, k, np_ranks, warm, steps, out):
    os.makedirs(out, exist_ok=True)
    cmd = (["mpirun", "-np", str(np_ranks)] if np_ranks > 1 else []) + \
        [lmp_binary(), "-in", INPUT, "-log", os.path.join(out, "log.lammps"), "-nocite", "-screen",
         "none", "-var", "restart", restart, "-var", "k", str(k), "-var", "warm", str(warm),
         "-var", "steps", str(steps), "-var", "out", out]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit("run_replicate: k %d failed (%s):\n%s"
                 % (k, out, proc.stdout[-2000:] + proc.stderr[-2000:]))
    os.remove(os.path.join(out, "replicate.data"))
    run = read_log(os.path.join(out, "log.lammps"))
    n, ps = run["N"], run["N"] * run["steps"]
    cpu = run["loop_seconds"] * run["cpu_use"] * run["np"]
    row = {"k": k, "N": n, "np": run["np"], "steps": run["steps"],
           "loop_seconds": run["loop_seconds"], "cpu_use": run["cpu_use"],
           "us_per_particle_step": 1e6 * cpu / ps,
           "contacts_per_particle_step": run["contacts"] / ps,
           "ns_per_contact_step": 1e9 * cpu * run["shares"].get("Pair", 0) / run["contacts"],
           "memory_mb_per_rank": run["memory_mb_per_rank"],
           "kb_per_particle": 1024 * run["memory_mb_per_rank"] * run["np"] / n}
    row.update({"share_" + s.lower(): run["shares"].get(s, 0.0) for s in SECTIONS})
    return row


def medians(rows):
    """the rows' medians per (ranks, k), with the number of repeats and the spread (largest
    over smallest) of the time per particle-step"""
    groups = {}
    for r in rows:
        groups.setdefault((int(r["np"]), int(r["k"])), []).append(r)
    out = []
    for (ranks, k), g in sorted(groups.items()):
        m = {f: float(np.median([float(r[f]) for r in g])) for f in MEASURES}
        times = [float(r["us_per_particle_step"]) for r in g]
        m.update(k=k, np=ranks, N=int(g[0]["N"]), repeats=len(g),
                 spread=max(times) / min(times))
        out.append(m)
    return out


def write_table(rows, results):
    lines = ["| k x k | N | ranks | repeats | CPU us per particle-step (median) | largest / "
             "smallest | contacts per particle-step | pair CPU ns per contact-step | Pair | "
             "Neigh | Comm | Modify | Other | memory per particle (kB) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    sizes = medians(rows)
    for m in sizes:
        lines.append("| %d x %d | %d | %d | %d | %.3f | %.2f | %.3f | %.0f | %.3f | %.3f | %.3f | "
                     "%.3f | %.3f | %.1f |"
                     % (m["k"], m["k"], m["N"], m["np"], m["repeats"],
                        m["us_per_particle_step"], m["spread"],
                        m["contacts_per_particle_step"], m["ns_per_contact_step"],
                        m["share_pair"], m["share_neigh"], m["share_comm"],
                        m["share_modify"], m["share_other"], m["kb_per_particle"]))
    for ranks in sorted({m["np"] for m in sizes}):
        sub = [m for m in sizes if m["np"] == ranks]
        if len(sub) > 1:
            slope = np.polyfit(np.log([m["N"] for m in sub]),
                               np.log([m["us_per_particle_step"] for m in sub]), 1)[0]
            lines.append("\nExponent of the time per particle-step in N at %d rank%s "
                         "(log-log least squares over %d sizes' medians): %.3f."
                         % (ranks, "s" if ranks > 1 else "", len(sub), slope))
    with open(os.path.join(results, "table_replicate.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--restart", required=True, help="a deposit at rest (in.deposit save 1)")
    ap.add_argument("--k", type=int, nargs="+", default=[1, 2, 4, 8])
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--warm", type=int, default=1000)
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--out", default=os.path.join(ROOT, "runs", "replicate"))
    ap.add_argument("--results", default=os.path.join(ROOT, "results", "cost_curve"))
    args = ap.parse_args(argv)
    if not os.path.isfile(args.restart):
        sys.exit("run_replicate: --restart %s: no such file (a deposit written by "
                 "examples/deposit/in.deposit -var save 1)" % args.restart)
    if min(args.k) < 1 or args.np < 1 or args.repeats < 1 or args.warm < 0 or args.steps < 1:
        sys.exit("run_replicate: --k, --np, --repeats and --steps must be positive, --warm not "
                 "negative")
    os.makedirs(args.results, exist_ok=True)
    rows_path = os.path.join(args.out, "rows.csv")
    os.makedirs(args.out, exist_ok=True)
    for repeat in range(args.repeats):
        for k in sorted(args.k):
            done = {(int(r["k"]), int(r["np"]), int(r["repeat"])) for r in read_rows(rows_path)}
            if (k, args.np, repeat) in done:
                continue
            print("run_replicate: %d x %d copies on %d rank(s), repeat %d of %d ..."
                  % (k, k, args.np, repeat + 1, args.repeats), flush=True)
            meta = {"commit": commit(), "load_start": os.getloadavg()[0], "repeat": repeat,
                    "started_utc": time.strftime("%Y-%m-%d %H:%M", time.gmtime())}
            row = measure(os.path.abspath(args.restart), k, args.np, args.warm, args.steps,
                          os.path.join(args.out, "k%d-np%d" % (k, args.np)))
            row.update(meta, load_end=os.getloadavg()[0])
            append_row(rows_path, row, FIELDS)
            print("  N %d: %.3f us per particle-step, %.3f contacts per particle-step"
                  % (row["N"], row["us_per_particle_step"], row["contacts_per_particle_step"]),
                  flush=True)
    rows = sorted(read_rows(rows_path), key=lambda r: (int(r["np"]), int(r["N"])))
    with open(os.path.join(args.results, "rows_replicate.csv"), "w") as f:
        f.write(open(rows_path).read())
    print(write_table(rows, args.results))


if __name__ == "__main__":
    main()
