"""Whole deposits from the empty box to rest: table 0, the time to deposit (the default
deposit on 2 and 1 ranks), and table 5, the ellipsoids against multi-sphere clumps
(bench/clumps/run_clumps.py at one seed)."""
import os
import re
import subprocess
import sys
import time

from bench_rows import read_rows

from .lmp_runs import ROOT, fmt_table, lmp_path

DEPOSIT_INPUT = os.path.join(ROOT, "examples", "deposit", "in.deposit")


def run_deposit(out, n, np, seed):
    """The default deposit (eta 1.4, zeta 1.8, delta_r 0.6) of n particles from the empty box
    to rest on np ranks: wall time, steps, phi, Z from its log."""
    work = os.path.join(out, f"deposit_N{n}_np{np}_s{seed}")
    os.makedirs(work, exist_ok=True)
    cmd = [lmp_path(), "-in", DEPOSIT_INPUT, "-log", "log.lammps", "-screen", "none", "-nocite",
           "-var", "N", str(n), "-var", "seed", str(seed), "-var", "out", work,
           "-var", "image", "0", "-var", "tangential", "history 2.0e3 0.5"]    # the runner's
    # as `./ellipsoid-dep run` launches it (Open MPI binds 2 ranks to cores); the other rows run
    # unbound and oversubscribed (run_lmp), as their earlier tables did
    if np > 1:
        cmd = ["mpirun", "-np", str(np)] + cmd
    t0 = time.time()
    subprocess.run(cmd, cwd=work, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    wall = time.time() - t0
    text = open(os.path.join(work, "log.lammps")).read()
    steps = re.search(r"^ELLIPSOID_DEP: at rest after (\d+) steps", text, re.M)
    res = re.search(r"^RESULT phi ([\d.eE+-]+) Z ([\d.eE+-]+)", text, re.M)
    if not (steps and res):
        raise RuntimeError(f"deposit did not finish: {work}/log.lammps")
    return {"N": n, "ranks": np, "seed": seed, "wall_s": wall, "steps": int(steps.group(1)),
            "phi": float(res.group(1)), "Z": float(res.group(2)),
            "warnings": len(re.findall(r"^WARNING", text, re.M))}


def bench_deposit(out, n, nps, seed):
    rows = []
    for np in nps:
        print(f"  deposit N = {n} on {np} rank(s), seed {seed}", flush=True)
        rows.append(run_deposit(out, n, np, seed))
    one = next((r["wall_s"] for r in rows if r["ranks"] == 1), None)
    for r in rows:
        r["speedup"] = one / r["wall_s"] if one else float("nan")
    return rows


def deposit_markdown(rows):
    return fmt_table(["N", "MPI ranks", "seed", "wall time (s)", "steps", "phi", "Z",
                      "WARNINGs", "speed-up vs 1 rank"],
                     [[r["N"], r["ranks"], r["seed"], f"{r['wall_s']:.0f}", r["steps"],
                       f"{r['phi']:.5f}", f"{r['Z']:.4f}", r["warnings"],
                       f"{r['speedup']:.2f}"] for r in rows])


def bench_clumps(out, n, seed):
    """the ellipsoids against the closest clump (k = 15) at one seed, as `bench clumps` runs
    them (2 ranks each, CPU time of the run)"""
    sub = os.path.join(out, "clumps")
    subprocess.run([sys.executable, os.path.join(ROOT, "bench", "clumps", "run_clumps.py"),
                    "--N", str(n), "--seeds", str(seed), "--runs", "e", "15", "--out", sub,
                    "--results", os.path.join(sub, "results")], check=True)
    rows = {r["run"]: r for r in read_rows(os.path.join(sub, "rows.csv"))}
    return [{"run": name, "N": n, "seed": seed,
             **{k: float(rows[name][k]) for k in ("cpu_seconds", "steps", "phi", "Z")}}
            for name in ("e", "k15")]


def clumps_markdown(rows):
    base = rows[0]["cpu_seconds"]
    names = {"e": "ellipsoids (granular/ellipsoid)", "k15": "clumps k = 15 (rigid/small)"}
    return fmt_table(["run", "N", "seed", "CPU time (s)", "CPU time / ellipsoids", "steps",
                      "phi", "Z"],
                     [[names[r["run"]], r["N"], r["seed"], f"{r['cpu_seconds']:.0f}",
                       f"{r['cpu_seconds'] / base:.2f}", f"{r['steps']:.0f}", f"{r['phi']:.4f}",
                       f"{r['Z']:.3f}"] for r in rows])
