#!/usr/bin/env python3
"""Parameter sweep of the deposit over (eta, zeta, delta_r) x seeds; one tidy CSV.

    ./ellipsoid-dep python tools/sweep.py --eta 1 1.4 2 --zeta 1 1.4 2 --dr 0 --seeds 1 2 \
        --N 300 --out runs/sweep

Every point (eta, zeta, delta_r, seed) runs examples/deposit/in.deposit serially (one MPI
rank, no picture) in OUT/points/<name>/; up to --jobs points run side by side (default: the
number of cores). A point whose packing.dat holds a result is skipped, so an interrupted sweep
resumes where it stopped (delete a point's folder to redo it). At the end, and after every
finished point, OUT/results.csv is rewritten from all finished points with the columns
    eta, zeta, delta_r, seed, N, phi, Z, Z_no_rattlers, Nslab, rattlers, steps,
    fabric_anisotropy, nematic_S, contact_histo, orient_histo, run_seconds
(histogram files relative to OUT). Draw the figures with tools/plot_figures.py OUT/results.csv.
"""
import argparse
import concurrent.futures as cf
import csv
import os
import subprocess
import sys
import threading
import time

ROOT = os.environ.get("ELLIPSOID_DEP_ROOT",
                      os.path.abspath(os.path.join(os.path.dirname(__file__), "..")))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from deposit_run import DEFAULT_INPUT, lmp_binary, read_packing  # noqa: E402

COLUMNS = ["eta", "zeta", "delta_r", "seed", "N", "phi", "Z", "Z_no_rattlers", "Nslab",
           "rattlers", "steps", "fabric_anisotropy", "nematic_S", "contact_histo",
           "orient_histo", "run_seconds"]
LOCK = threading.Lock()


def point_name(eta, zeta, dr, seed):
    return "eta%g_zeta%g_dr%g_s%d" % (eta, zeta, dr, seed)


def finished(folder):
    f = os.path.join(folder, "packing.dat")
    if not os.path.exists(f):
        return False
    try:
        return "phi" in read_packing(f) and os.path.exists(os.path.join(folder, "run_seconds"))
    except (OSError, ValueError):
        return False


def run_point(args, out, eta, zeta, dr, seed):
    folder = os.path.join(out, "points", point_name(eta, zeta, dr, seed))
    if finished(folder):
        return folder, "skipped (done)"
    os.makedirs(folder, exist_ok=True)
    for stale in ("packing.dat", "run_seconds"):
        if os.path.exists(os.path.join(folder, stale)):
            os.remove(os.path.join(folder, stale))
    cmd = [lmp_binary(), "-in", os.path.abspath(args.input), "-log", "log.lammps", "-screen",
           "none", "-nocite", "-var", "N", str(args.N), "-var", "eta", str(eta), "-var", "zeta",
           str(zeta), "-var", "dr", str(dr), "-var", "seed", str(seed), "-var", "ketol",
           str(args.ketol), "-var", "out", folder, "-var", "image", "0", "-var", "tangential", args.tangential]
    if args.np > 1:
        cmd = ["mpirun", "-np", str(args.np)] + cmd
    t0 = time.time()
    r = subprocess.run(cmd, cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                       text=True)
    dt = time.time() - t0
    if r.returncode != 0 or not os.path.exists(os.path.join(folder, "packing.dat")):
        return folder, "FAILED (exit %d; see %s/log.lammps) %s" % (r.returncode, folder,
                                                                    r.stderr[-300:])
    with open(os.path.join(folder, "run_seconds"), "w") as f:
        f.write("%.2f\n" % dt)
    return folder, "done in %.0f s" % dt


def collect(out):
    rows = []
    pdir = os.path.join(out, "points")
    for name in sorted(os.listdir(pdir)) if os.path.isdir(pdir) else []:
        folder = os.path.join(pdir, name)
        if not finished(folder):
            continue
        pk = read_packing(os.path.join(folder, "packing.dat"))
        row = {k: pk.get(k, "") for k in COLUMNS}
        row["delta_r"] = pk.get("delta_r", "")
        row["contact_histo"] = os.path.relpath(os.path.join(folder, "contact_histo.dat"), out)
        row["orient_histo"] = os.path.relpath(os.path.join(folder, "orient_histo.dat"), out)
        row["run_seconds"] = open(os.path.join(folder, "run_seconds")).read().strip()
        for k in ("N", "seed", "Nslab", "rattlers", "steps"):
            if row[k] != "":
                row[k] = int(row[k])
        rows.append(row)
    rows.sort(key=lambda r: (float(r["delta_r"]), float(r["eta"]), float(r["zeta"]), r["seed"]))
    path = os.path.join(out, "results.csv")
    with LOCK:
        with open(path + ".tmp", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=COLUMNS)
            w.writeheader()
            for row in rows:
                w.writerow(row)
        os.replace(path + ".tmp", path)
    return path, len(rows)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--eta", type=float, nargs="+", default=[1.0, 1.4, 2.0])
    ap.add_argument("--zeta", type=float, nargs="+", default=[1.0, 1.4, 2.0])
    ap.add_argument("--dr", type=float, nargs="+", default=[0.0])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1])
    ap.add_argument("--N", type=int, default=300)
    ap.add_argument("--tangential", default="history 2.0e3 0.5",
                    help='tangential law words (default "history 2.0e3 0.5"; the paper\'s '
                         'viscous law: "viscous 0.5")')
    ap.add_argument("--ketol", type=float, default=1e-4)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                    help="points run side by side (default: number of cores)")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per point (default 1)")
    ap.add_argument("--out", default=os.path.join("runs", "sweep"))
    ap.add_argument("--input", default=DEFAULT_INPUT)
    ap.add_argument("--diagonal-only", action="store_true",
                    help="only eta == zeta plus the prolate (zeta=1) and oblate (eta=1) lines")
    args = ap.parse_args(argv)

    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    points = []
    for dr in args.dr:
        for eta in args.eta:
            for zeta in args.zeta:
                if args.diagonal_only and not (eta == zeta or eta == 1.0 or zeta == 1.0):
                    continue
                for seed in args.seeds:
                    points.append((eta, zeta, dr, seed))
    todo = [p for p in points
            if not finished(os.path.join(out, "points", point_name(*p)))]
    print("sweep: %d points (%d finished, %d to run) with N %d, %d at a time -> %s"
          % (len(points), len(points) - len(todo), len(todo), args.N, args.jobs, out), flush=True)
    failed = 0
    t0 = time.time()
    with cf.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as ex:
        futs = {ex.submit(run_point, args, out, *p): p for p in todo}
        for k, fut in enumerate(cf.as_completed(futs), 1):
            folder, status = fut.result()
            failed += status.startswith("FAILED")
            el = time.time() - t0
            left = el / k * (len(todo) - k)
            print("  [%d/%d] %s: %s  (elapsed %.0f s, left ~%.0f s)"
                  % (k, len(todo), os.path.basename(folder), status, el, left), flush=True)
            collect(out)
    path, n = collect(out)
    print("sweep: %s holds %d finished points%s" % (path, n,
                                                   "; %d FAILED" % failed if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
