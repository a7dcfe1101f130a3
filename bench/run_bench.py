#!/usr/bin/python3
"""ELLIPSOID_DEP benchmarks: peers side by side, speed-accuracy trade, scaling.

  ./ellipsoid-dep bench            quick (N ~ 1000, M = 500, 3 repeats; a few minutes)
  ./ellipsoid-dep bench --full     N ~ 4000 side by side, scaling 1e3..1e5
  ./ellipsoid-dep bench kernel     the kernel micro-benchmarks (build/bench/bench_kernel)
  ./ellipsoid-dep bench clumps     multi-sphere clumps against the ellipsoids, whole deposits
                                   (bench/clumps/run_clumps.py; hours on 2 shared cores)
  ./ellipsoid-dep bench accuracy   the contact knobs' cost against phi, Z and the contact
                                   normals of whole default deposits (bench/accuracy/
                                   run_accuracy.py; hours on 2 shared cores)
  ./ellipsoid-dep bench replicate  a settled deposit copied k x k times: the code's own cost
                                   growth with N (bench/cost_curve/run_replicate.py; minutes)

Needs the environment set by ./ellipsoid-dep (LAMMPS_BUILD, LAMMPS_PLUGIN_PATH).  Every number
comes from this one invocation; timings are medians over interleaved repeats.  Output (logs,
data files, tables as JSON and markdown, the Pareto plot) goes to --out (default
runs/bench/quick or runs/bench/full).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
# the tables, one module each in bench/tables/ (deposits: 0 and 5, peers: 1, knobs: 2,
# scaling: 3, spheres: 4), with the LAMMPS runs and scenes they share in lmp_runs
from bench_rows import commit  # noqa: E402
from tables.deposits import bench_clumps, bench_deposit, clumps_markdown, \
    deposit_markdown  # noqa: E402
from tables.knobs import bench_knobs, knobs_markdown, plot_knobs  # noqa: E402
from tables.lmp_runs import make_scenes, replicate  # noqa: E402
from tables.peers import bench_peers, liggghts_note, peers_markdown  # noqa: E402
from tables.scaling import bench_scaling, scaling_markdown  # noqa: E402
from tables.spheres import bench_spheres, spheres_markdown  # noqa: E402

# the benchmarks of their own (bench/<folder>/), run instead of the tables
WHOLE_DEPOSITS = {"clumps": os.path.join("clumps", "run_clumps.py"),
                  "accuracy": os.path.join("accuracy", "run_accuracy.py"),
                  "replicate": os.path.join("cost_curve", "run_replicate.py")}
SUBCOMMANDS = ["kernel"] + list(WHOLE_DEPOSITS)
# the tables (--only); the peers table holds the LIGGGHTS rows
PARTS = ["peers", "knobs", "scaling", "spheres", "deposit", "clumps"]


def run_kernel():
    exe = os.path.join(ROOT, "build", "bench", "bench_kernel")
    if not os.access(exe, os.X_OK):
        subprocess.run(["cmake", "--build", os.path.join(ROOT, "build"), "--target",
                        "bench_kernel", "-j1"], check=True)
    os.execv(exe, [exe] + sys.argv[2:])


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "kernel":
        run_kernel()
    if len(sys.argv) > 1 and sys.argv[1] in WHOLE_DEPOSITS:
        script = os.path.join(ROOT, "bench", WHOLE_DEPOSITS[sys.argv[1]])
        os.execv(sys.executable, [sys.executable, script] + sys.argv[2:])
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--full", action="store_true", help="bigger N, M, repeats; N up to 1e5")
    ap.add_argument("--out", help="output folder (default runs/bench/quick or runs/bench/full)")
    ap.add_argument("--only", choices=PARTS, action="append",
                    help="run only these parts (repeatable); deposit (the time to deposit "
                    "N = 4000 on 2 and 1 ranks, minutes) and clumps (the ellipsoids against "
                    "k = 15 clumps, N = 2000, one seed, minutes) run by default only with "
                    "--full")
    ap.add_argument("--repeats", type=int)
    args = ap.parse_args()
    mode = "full" if args.full else "quick"
    out = os.path.abspath(args.out or os.path.join(ROOT, "runs", "bench", mode))
    if os.path.isdir(out):
        shutil.rmtree(out)
    os.makedirs(out)
    parts = args.only or ["peers", "knobs", "scaling", "spheres"] + \
        (["deposit", "clumps"] if args.full else [])
    if args.full:
        cfg = {"n": 1000, "peer_k": 2, "M": 1000, "rep": args.repeats or 5, "knob_M": 500,
               "ks": [1, 2, 4, 8, 10], "nps": [1, 2]}
    else:
        cfg = {"n": 1000, "peer_k": 1, "M": 500, "rep": args.repeats or 3, "knob_M": 300,
               "ks": [1, 2], "nps": [1, 2]}
    meta = {"commit": commit(),
            "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
            "nproc": os.cpu_count(), "mode": mode,
            "load": os.getloadavg()[0]}
    t0 = time.time()
    print(f"[bench] {mode}: output in {out}", flush=True)
    report = {"meta": meta}
    md = [f"commit {meta['commit']}, {meta['date']}, nproc {meta['nproc']}, "
          f"load average at start {meta['load']:.1f}, mode {mode}"]
    if "deposit" in parts:
        print("[bench] 0. time to deposit: the default deposit, N = 4000, empty box to rest",
              flush=True)
        rows = bench_deposit(out, 4000, [2, 1], 4928)
        report["deposit"] = rows
        m = deposit_markdown(rows)
        md += ["\n### 0. Time to deposit (examples/deposit/in.deposit defaults, N = 4000, "
               "from the empty box to rest)\n", m]
        print(m, flush=True)
    if set(parts) & {"peers", "knobs", "scaling"}:
        g = make_scenes(out, cfg["n"])
        report["scene"] = g
    if "peers" in parts:
        data_e, data_s = replicate(out, g, cfg["peer_k"])
        nmob = g["nmobile"] * cfg["peer_k"] ** 2
        nfl = g["nfloor"] * cfg["peer_k"] ** 2
        print(f"[bench] 1. peers: N = {nmob} (+{nfl} frozen floor), M = {cfg['M']}, "
              f"{cfg['rep']} repeats", flush=True)
        tab = bench_peers(out, g, data_e, data_s, cfg["M"], cfg["rep"], nmob, nfl)
        report["peers"] = tab
        m = peers_markdown(tab, nmob, nfl, cfg["M"])
        md += [f"\n### 1. Peers side by side (N = {nmob} mobile + {nfl} frozen floor, "
               f"M = {cfg['M']}, median of {cfg['rep']})\n", m]
        if any("LIGGGHTS" in r["code"] for r in tab):
            note = liggghts_note()
            md.append(note)
            print(note, flush=True)
        print(m, flush=True)
        for r in tab:
            if "counters" in r:
                print(f"  {r['code']} counters (last repeat): {r['counters']}")
    if "knobs" in parts:
        nmob, nfl = g["nmobile"], g["nfloor"]
        print(f"[bench] 2. knobs: N = {nmob}, M = {cfg['knob_M']}, {cfg['rep']} repeats",
              flush=True)
        tab = bench_knobs(out, "ellipsoid.data", cfg["knob_M"], cfg["rep"], nmob, nfl)
        report["knobs"] = tab
        m = knobs_markdown(tab)
        plotted = plot_knobs(tab, os.path.join(out, "knobs_pareto.png"))
        md += [f"\n### 2. Speed-accuracy trade (N = {nmob}, M = {cfg['knob_M']}, median of "
               f"{cfg['rep']}; errors on {tab[0]['n'] + tab[0]['missed']} contacts vs "
               f"`preset accurate`, run 0 on the settled configuration)\n", m]
        if plotted:
            md.append(f"\nplot: {os.path.join(out, 'knobs_pareto.png')}")
        print(m, flush=True)
    if "scaling" in parts:
        print(f"[bench] 3. scaling: replicas {cfg['ks']}, ranks {cfg['nps']}", flush=True)

        def nsteps_for(n):
            return max(50, min(cfg["M"], int(4e6 / n))) if args.full else \
                max(100, min(300, int(1.2e6 / n)))
        rows = bench_scaling(out, g, cfg["ks"], nsteps_for, cfg["rep"], cfg["nps"])
        report["scaling"] = rows
        m = scaling_markdown(rows)
        md += [f"\n### 3. Scaling (granular/ellipsoid, median of {cfg['rep']})\n", m]
        print(m, flush=True)
    if "spheres" in parts:
        print(f"[bench] 4. sphere path: 1024 spheres on a wall, M = {4 * cfg['M']}, "
              f"{cfg['rep']} repeats", flush=True)
        rows = bench_spheres(out, 4 * cfg["M"], cfg["rep"])
        report["spheres"] = rows
        m = spheres_markdown(rows)
        md += [f"\n### 4. Sphere path (1024 unit spheres on a wall, 1 rank, "
               f"M = {4 * cfg['M']}, median of {cfg['rep']})\n", m]
        print(m, flush=True)
    if "clumps" in parts:
        print("[bench] 5. multi-sphere clumps: the ellipsoids against k = 15, N = 2000",
              flush=True)
        rows = bench_clumps(out, 2000, 4928)
        report["clumps"] = rows
        m = clumps_markdown(rows)
        md += ["\n### 5. Multi-sphere clumps (the Fig. 3 shape at delta_r 0, N = 2000, one seed, "
               "2 ranks each; whether they agree: `./ellipsoid-dep bench clumps`, 3 seeds)\n", m]
        print(m, flush=True)
    meta["seconds"] = time.time() - t0
    json.dump(report, open(os.path.join(out, "results.json"), "w"), indent=1, default=str)
    open(os.path.join(out, "results.md"), "w").write("\n".join(md) + "\n")
    print(f"[bench] done in {meta['seconds']:.0f} s; tables in {out}/results.md", flush=True)


if __name__ == "__main__":
    main()
