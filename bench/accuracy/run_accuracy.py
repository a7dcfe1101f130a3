#!/usr/bin/env python3
"""The whole-deposit speed-accuracy trade of pair_style granular/ellipsoid's contact knobs:
the default deposit (examples/deposit/in.deposit, the Fig. 3 scene) from the empty box to rest
under each setting of the knobs, several seeds each; its cost (CPU time, steps to rest, CPU
time per particle-step) against what a user computes from it (phi, Z, the contact-normal
histogram), each setting against the default and the default's own seed spread.

    ./ellipsoid-dep bench accuracy [--N 4000 [N ...]] [--seeds 4928 4929 4930]
                                   [--settings default fast accurate correction5 tolerance1e-6]
                                   [--np 1] [--checkpoint-every 0] [--out runs/accuracy]
                                   [--results results/accuracy] [--table-only]

Runs one deposit at a time (tools/deposit/deposit_run.py, the settings' keywords through in.deposit's
`pairkw` variable), seeds outermost, then N (several: the cost curve, bench/cost_curve), so
that the settings and sizes of one seed run back to back and a drift of the machine's load
reaches them alike. --checkpoint-every keeps restart checkpoints in the run folder (a deposit
that does not come to rest can be inspected). Every (setting, seed, N) already in
OUT/rows.csv is skipped, so an interrupted invocation continues where it stopped. The cost is
the CPU time (user + system, getrusage of the finished children) of the run's processes: on a
shared machine the wall time is mostly the other jobs' share. Then the table (table.md), the
summary (summary.csv), the per-run rows (rows.csv) and the histograms (histograms.png) are
written to --results (accuracy_table.py).
"""
import argparse
import itertools
import os
import shutil
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "bench"))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import _paths  # noqa: E402,F401  (tools/_paths.py: the tools' topic folders on sys.path)
import accuracy_table    # noqa: E402
import deposit_run    # noqa: E402
from bench_rows import append_row, commit, read_counters, read_rows, run_measured  # noqa: E402

# name: pair_style granular/ellipsoid keywords (doc/pair_granular_ellipsoid.rst)
SETTINGS = {
    "default": "",
    "fast": "preset fast",                  # tolerance 1e-8, 20 iterations
    "accurate": "preset accurate",          # tolerance 1e-14, 100 iterations, correction 0
    "correction5": "correction 5",          # the paper's fast mode: no correction below 5 deg
    "tolerance1e-6": "tolerance 1e-6",      # looser than fast, iterations kept at 50
}
COUNTERS = ["contacts", "iterations", "corrections", "not_converged", "spurious_minima"]
FIELDS = ["setting", "keywords", "seed", "N", "np", "cpu_seconds", "peak_rss_mb", "wall_seconds",
          "steps", "at_rest", "phi", "Z", "Nslab", "fabric_anisotropy", "warnings"] + COUNTERS + \
    ["commit", "started_utc", "load_start", "load_end"] + \
    ["F%d" % k for k in range(accuracy_table.BINS)]


def read_log(path):
    """(the pair's counters at the last run's end, summed over the deposit; WARNING lines)"""
    counters, warnings = None, 0
    with open(path) as f:
        for line in f:
            c = read_counters(line)
            if c is not None:
                counters = c
            elif line.startswith("WARNING"):    # not the input's echoed lines
                warnings += 1
    if counters is None:
        raise ValueError("no pair counters line in %s" % path)
    return counters, warnings


def run_deposit(setting, seed, n, np_ranks, out, checkpoint_every=0):
    cmd = ["/usr/bin/python3", os.path.join(ROOT, "tools", "deposit", "deposit_run.py"), "--np",
           str(np_ranks), "--N", str(n), "--seed", str(seed), "--out", out, "--no-image",
           "--no-plots", "--quiet", "--checkpoint-every", str(checkpoint_every)]
    if SETTINGS[setting]:
        cmd += ["--var", "pairkw", SETTINGS[setting]]
    proc, cpu, peak_rss_mb = run_measured(cmd)
    if proc.returncode != 0:
        sys.exit("run_accuracy: %s seed %d failed (folder %s):\n%s"
                 % (setting, seed, out, proc.stdout[-2000:] + proc.stderr[-2000:]))
    pk = deposit_run.read_packing(os.path.join(out, "packing.dat"))
    _, _, fraction = deposit_run.read_histo(os.path.join(out, "contact_histo.dat"))
    counters, warnings = read_log(os.path.join(out, "log.lammps"))
    row = {"setting": setting, "keywords": SETTINGS[setting] or "(none)", "seed": seed, "N": n,
           "np": np_ranks, "cpu_seconds": round(cpu, 2), "peak_rss_mb": round(peak_rss_mb, 1),
           "wall_seconds": pk["wall_seconds"],
           "steps": int(pk["steps"]), "at_rest": int(pk["at_rest"]), "phi": pk["phi"],
           "Z": pk["Z"], "Nslab": int(pk["Nslab"]),
           "fabric_anisotropy": pk["fabric_anisotropy"], "warnings": warnings}
    row.update({k: counters[k] for k in COUNTERS})
    row.update({"F%d" % k: f for k, f in enumerate(fraction)})
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--N", type=int, nargs="+", default=[4000])
    ap.add_argument("--seeds", type=int, nargs="+", default=[4928, 4929, 4930])
    ap.add_argument("--settings", nargs="+", default=list(SETTINGS))
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--checkpoint-every", type=int, default=0)
    ap.add_argument("--out", default=os.path.join(ROOT, "runs", "accuracy"))
    ap.add_argument("--results", default=os.path.join(ROOT, "results", "accuracy"))
    ap.add_argument("--table-only", action="store_true")
    args = ap.parse_args(argv)
    unknown = [s for s in args.settings if s not in SETTINGS]
    if unknown:
        sys.exit("run_accuracy: unknown setting(s) %s; known: %s"
                 % (", ".join(unknown), ", ".join(SETTINGS)))
    if min(args.N) < 1 or args.np < 1 or args.checkpoint_every < 0:
        sys.exit("run_accuracy: --N and --np must be positive, --checkpoint-every not negative")
    os.makedirs(args.out, exist_ok=True)
    rows_path = os.path.join(args.out, "rows.csv")
    if not args.table_only:
        for seed, n, setting in itertools.product(args.seeds, args.N, args.settings):
            done = {(r["setting"], int(r["seed"]), int(r["N"])) for r in read_rows(rows_path)}
            if (setting, seed, n) in done:
                continue
            out = os.path.join(args.out, "%s-N%d-s%d" % (setting, n, seed))
            print("run_accuracy: %s (%s) seed %d N %d ..."
                  % (setting, SETTINGS[setting] or "defaults", seed, n), flush=True)
            meta = {"commit": commit(), "load_start": os.getloadavg()[0],
                    "started_utc": time.strftime("%Y-%m-%d %H:%M", time.gmtime())}
            row = run_deposit(setting, seed, n, args.np, out, args.checkpoint_every)
            row.update(meta, load_end=os.getloadavg()[0])
            append_row(rows_path, row, FIELDS)
            print("  CPU %.0f s, %d steps, phi %.4f, Z %.3f, at_rest %d"
                  % (row["cpu_seconds"], row["steps"], row["phi"], row["Z"], row["at_rest"]),
                  flush=True)
    rows = read_rows(rows_path)
    if not rows:
        sys.exit("run_accuracy: no rows in %s" % rows_path)
    os.makedirs(args.results, exist_ok=True)
    shutil.copy(rows_path, os.path.join(args.results, "rows.csv"))
    accuracy_table.write(rows, args.results)


if __name__ == "__main__":
    main()
