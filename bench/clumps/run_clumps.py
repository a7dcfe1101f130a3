#!/usr/bin/env python3
"""Multi-sphere clumps against the true ellipsoids: the Fig. 3 deposit (eta 1.4, zeta 1.8,
delta_r 0) poured as rigid clumps of k spheres with LAMMPS's own styles and as ellipsoids with
this package, the same protocol (in.deposit's), N particles, several seeds.

    ./ellipsoid-dep bench clumps [--N 2000] [--seeds 4928 4929 4930] [--runs 3 e 7 15]
                                 [--np 2] [--out runs/clumps] [--results results/clumps]
                                 [--table-only]

--runs: what to run, in order (a clump size k, or e for the ellipsoids); every (run, seed)
already in DIR/rows.csv is skipped, so an interrupted invocation continues where it stopped.
Per run: the wall time of the whole LAMMPS process (from the empty box to rest), the steps,
phi, Z and the contact-normal histogram (clumps: clump_analysis.py; ellipsoids: in.deposit's
packing.dat and contact_histo.dat). Then the table (table.md), the summary (summary.csv), the
per-run rows (rows.csv), the histograms (histograms.png) and the fitted clumps (.json, .mol)
are written to --results.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "bench"))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import _paths  # noqa: E402,F401  (tools/_paths.py: the tools' topic folders on sys.path)
from bench_rows import append_row, children_cpu, read_rows    # noqa: E402
import clump_analysis    # noqa: E402
import clump_table    # noqa: E402
import fit_clumps    # noqa: E402

ETA, ZETA = 1.4, 1.8
FIELDS = ["run", "seed", "N", "np", "wall_seconds", "cpu_seconds", "steps", "at_rest", "phi",
          "Z", "Nslab", "load_start", "load_end"] + \
    ["P%d" % k for k in range(clump_analysis.BINS)]


def lmp():
    exe = os.environ.get("ELLIPSOID_DEP_LMP")
    if not exe or not os.path.exists(exe):
        sys.exit("run_clumps: LAMMPS not found: run through ./ellipsoid-dep bench clumps")
    return exe


def mpi(np_ranks):
    return ["mpirun", "-np", str(np_ranks)] if np_ranks > 1 else []


COMMITTED_FITS = os.path.join(ROOT, "results", "clumps")


def fitted(k, fit_dir):
    """the fit of k spheres: fit_dir's, else the committed one (the fit is deterministic and
    takes minutes), else fitted now"""
    path = os.path.join(fit_dir, "clump_k%d.json" % k)
    committed = os.path.join(COMMITTED_FITS, os.path.basename(path))
    if not os.path.exists(path) and os.path.exists(committed):
        with open(committed) as f:
            fit = json.load(f)
        if (fit["k"], fit["eta"], fit["zeta"]) == (k, ETA, ZETA):    # not a stale shape
            os.makedirs(fit_dir, exist_ok=True)
            shutil.copy(committed, path)
    if not os.path.exists(path):
        fit_clumps.main(["--k", str(k), "--eta", str(ETA), "--zeta", str(ZETA), "--out", fit_dir])
    with open(path) as f:
        clump = json.load(f)
    fit_clumps.write_files(path[:-len(".json")], clump)    # the input files from the fit
    return clump


def deposit_timestep(n, work):
    """in.deposit's own time step for this N at delta_r 0: its probe, then one step."""
    os.makedirs(work, exist_ok=True)
    out = subprocess.run([lmp(), "-in", os.path.join(ROOT, "examples", "deposit", "in.deposit"),
                          "-log", "none", "-nocite", "-var", "N", str(n), "-var", "dr", "0",
                          "-var", "eta", str(ETA), "-var", "zeta", str(ZETA), "-var", "chunk",
                          "1", "-var", "maxchunks", "1", "-var", "image", "0", "-var", "out",
                          work], capture_output=True, text=True, cwd=work)
    m = re.search(r"^time step rule (\S+) = ", out.stdout, re.M)
    if out.returncode != 0 or not m:
        sys.exit("run_clumps: in.deposit's time step probe failed:\n" + out.stdout[-2000:])
    return float(m.group(1))


def run_clump(k, seed, n, np_ranks, out, fit_dir, dt):
    clump = fitted(k, fit_dir)
    base = os.path.join(fit_dir, "clump_k%d" % k)
    centres, radii = np.array(clump["centres"]), np.array(clump["radii"])
    molradius = float(np.max(np.linalg.norm(centres, axis=1) + radii))
    os.makedirs(out, exist_ok=True)
    cmd = mpi(np_ranks) + [lmp(), "-in", os.path.join(HERE, "in.clump_deposit"), "-log",
                           os.path.join(out, "log.lammps"), "-nocite", "-screen", "none"]
    for name, value in (("N", n), ("mol", base + ".mol"), ("coeff", base + ".coeff"),
                        ("walls", base + ".walls"), ("groups", base + ".groups"),
                        ("ntypes", max(clump["orbit"]) + 1),
                        ("molradius", "%.10g" % molradius), ("mbody", "%.10g" % clump["mass"]),
                        ("dt", "%.10g" % dt), ("seed", seed), ("out", out),
                        ("eta", ETA), ("zeta", ZETA)):
        cmd += ["-var", name, str(value)]
    t0 = time.time()
    proc = subprocess.run(cmd, cwd=out, capture_output=True, text=True)
    wall = time.time() - t0
    if proc.returncode != 0:
        sys.exit("run_clumps: clump deposit k %d seed %d failed (log %s):\n%s"
                 % (k, seed, out, proc.stdout[-2000:] + proc.stderr[-2000:]))
    res = dict(line.split(None, 1) for line in open(os.path.join(out, "clump_result.dat")))
    m = clump_analysis.measure(os.path.join(out, "final.txt"), float(res["Lx"]), clump["mass"])
    row = {"run": "k%d" % k, "seed": seed, "N": n, "np": np_ranks, "wall_seconds": round(wall, 2),
           "steps": int(res["steps"]), "at_rest": int(res["at_rest"]), "phi": m["phi"],
           "Z": m["Z"], "Nslab": m["Nslab"]}
    row.update({"P%d" % i: p for i, p in enumerate(m["P"])})
    return row


def run_ellipsoids(seed, n, np_ranks, out):
    cmd = ["/usr/bin/python3", os.path.join(ROOT, "tools", "deposit", "deposit_run.py"), "--np",
           str(np_ranks), "--N", str(n), "--eta", str(ETA), "--zeta", str(ZETA), "--dr", "0",
           "--seed", str(seed), "--out", out, "--no-image", "--no-plots", "--quiet",
           "--checkpoint-every", "0"]
    import deposit_run
    if not os.path.exists(os.path.join(out, "packing.dat")):    # a finished run is kept
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode != 0:
            sys.exit("run_clumps: ellipsoid deposit seed %d failed:\n%s"
                     % (seed, proc.stdout[-2000:] + proc.stderr[-2000:]))
    pk = deposit_run.read_packing(os.path.join(out, "packing.dat"))
    _, P, _ = deposit_run.read_histo(os.path.join(out, "contact_histo.dat"))
    row = {"run": "e", "seed": seed, "N": n, "np": np_ranks, "wall_seconds": pk["wall_seconds"],
           "steps": int(pk["steps"]), "at_rest": int(pk["at_rest"]), "phi": pk["phi"],
           "Z": pk["Z"], "Nslab": int(pk["Nslab"])}
    row.update({"P%d" % i: p for i, p in enumerate(P)})
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--N", type=int, default=2000)
    ap.add_argument("--seeds", type=int, nargs="+", default=[4928, 4929, 4930])
    ap.add_argument("--runs", nargs="+", default=["3", "e", "7", "15"])
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--out", default=os.path.join(ROOT, "runs", "clumps"))
    ap.add_argument("--results", default=os.path.join(ROOT, "results", "clumps"))
    ap.add_argument("--table-only", action="store_true")
    args = ap.parse_args(argv)
    for r in args.runs:
        if r != "e" and (not r.isdigit() or int(r) not in fit_clumps.LAYOUTS):
            sys.exit("run_clumps: --runs takes e or a clump size of %s, not '%s'"
                     % (sorted(fit_clumps.LAYOUTS), r))
    if args.N < 1 or args.np < 1:
        sys.exit("run_clumps: --N and --np must be positive")
    os.makedirs(args.out, exist_ok=True)
    rows_path = os.path.join(args.out, "rows.csv")
    fit_dir = os.path.join(args.out, "fit")
    if not args.table_only:
        dt = None
        for r in args.runs:
            for seed in args.seeds:
                name = "e" if r == "e" else "k" + r
                done = {(x["run"], int(x["seed"]), int(x["N"])) for x in read_rows(rows_path)}
                if (name, seed, args.N) in done:
                    continue
                out = os.path.join(args.out, "%s-N%d-s%d" % (name, args.N, seed))
                print("run_clumps: %s seed %d N %d ..." % (name, seed, args.N), flush=True)
                if r != "e" and dt is None:
                    dt = deposit_timestep(args.N, os.path.join(args.out, "dt-probe"))
                load_start = os.getloadavg()[0]
                cpu0 = children_cpu()
                if r == "e":
                    row = run_ellipsoids(seed, args.N, args.np, out)
                else:
                    row = run_clump(int(r), seed, args.N, args.np, out, fit_dir, dt)
                row.update(load_start=load_start, load_end=os.getloadavg()[0],
                           cpu_seconds=round(children_cpu() - cpu0, 2))
                append_row(rows_path, row, FIELDS)
                print("  %.0f s, %d steps, phi %.4f, Z %.3f, at_rest %d"
                      % (row["wall_seconds"], row["steps"], row["phi"], row["Z"],
                         row["at_rest"]), flush=True)
    os.makedirs(args.results, exist_ok=True)
    shutil.copy(rows_path, os.path.join(args.results, "rows.csv"))
    clumps = {}
    for k in fit_clumps.LAYOUTS:
        path = os.path.join(fit_dir, "clump_k%d.json" % k)
        if os.path.exists(path):
            with open(path) as f:
                clumps["k%d" % k] = json.load(f)
            for ext in (".json", ".mol"):    # the fits, small and reusable
                shutil.copy(path[:-len(".json")] + ext, args.results)
    clump_table.write(read_rows(rows_path), clumps, args.results)


if __name__ == "__main__":
    main()
