#!/usr/bin/env python3
"""The cost curve of the default deposit against N: from the rows of
bench/accuracy/run_accuracy.py's default setting (rows.csv of one or more run folders, each run's
LAMMPS log beside it) the table per (N, ranks) of the CPU time to deposit, the steps to rest,
the CPU time and the contacts per particle-step, LAMMPS's memory estimate and the peak
resident set per rank, the communication's share of the loop time; per rank count the fitted
exponents in N and whether the time follows the work (pairs tested, contacts) chunk by chunk;
the extrapolation to 10^6 particles (cost_extrapolation.py); and a log-log plot.

    cost_table.py RUNS_DIR [RUNS_DIR ...] --results DIR

The box's edge grows as sqrt(N) (in.deposit), so the deposit's height, and with it the fall and
the steps to rest, do not depend on N: a cost linear in N has the exponent 1.
"""
import argparse
import math
import os
import re
import sys

import numpy as np
from scipy.optimize import nnls

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from bench_rows import CPU_USE, LOOP, MEMORY, read_counters, read_rows  # noqa: E402
from cost_extrapolation import base_size, extrapolation  # noqa: E402
from run_replicate import medians  # noqa: E402

COMM = re.compile(r"^Comm\s+\|\s*\S+\s*\|\s*(\S+)\s*\|")
BOX = re.compile(r"orthogonal box = \(\S+ \S+ \S+\) to \((\S+) (\S+) \S+\)")
GRID = re.compile(r"^\s*(\d+) by (\d+) by (\d+) MPI processor grid")
ATOMS = re.compile(r"^(Nlocal|Nghost):\s+(\S+) ave")
# in.deposit's check after each chunk: the step, the inserted count, KE/particle against ketol
# and the largest v^2/2gd against flytol
PROGRESS = re.compile(r"^PROGRESS step (\d+) inserted (\S+) of (\d+) KE/particle (\S+) "
                      r"target (\S+) flight (\S+) target (\S+)")


def read_log(path):
    """what a deposit's LAMMPS log says of its cost: the largest memory estimate per rank in
    MB ("memory_mb"), the communication's share of the summed loop time ("comm_share"), the
    first checked steps after which all particles were in and KE/particle was below ketol
    ("ke_met") and after which the largest v^2/2gd was below flytol ("flight_met"), the
    CPU time of the runs so far after each run, [(steps, CPU seconds)] ("cpu_by_step": loop
    time x CPU use x ranks), the pair's counters after each run, [(steps, pairs tested,
    contacts)] ("work_by_step", None where a run printed none), the ghosts per owned atom
    after the last run ("ghost_ratio"), the box's edges in x and y ("box") and the ranks along
    them ("grid")"""
    memory, loop, comm = 0.0, 0.0, 0.0
    ke_met, flight_met = math.nan, math.nan
    steps, cpu, cpu_by_step, work_by_step = 0, 0.0, [], []
    atoms, box, grid = {}, None, None
    with open(path) as f:
        for line in f:
            p = PROGRESS.match(line)
            if p:
                step, all_in = int(p.group(1)), float(p.group(2)) >= float(p.group(3))
                if all_in and math.isnan(ke_met) and float(p.group(4)) < float(p.group(5)):
                    ke_met = step
                if all_in and math.isnan(flight_met) and float(p.group(6)) < float(p.group(7)):
                    flight_met = step
                continue
            m = LOOP.match(line)
            if m:
                loop += float(m.group(1))
                steps += int(m.group(3))
                run_cpu = float(m.group(1)) * int(m.group(2))    # wall x ranks until its CPU use
                cpu += run_cpu
                cpu_by_step.append((steps, cpu))
                work_by_step.append(None)
                continue
            c = read_counters(line)
            if c is not None and work_by_step:    # printed after its run's loop time
                work_by_step[-1] = (steps, c["pairs"], c["contacts"])
                continue
            m = CPU_USE.match(line)
            if m and cpu_by_step:    # the last loop's CPU use, printed after its loop time
                cpu -= run_cpu * (1 - float(m.group(1)) / 100)
                cpu_by_step[-1] = (steps, cpu)
                continue
            m = MEMORY.match(line)
            if m:
                memory = max(memory, float(m.group(1)))
                continue
            m = ATOMS.match(line)
            if m:
                atoms[m.group(1)] = float(m.group(2))
                continue
            m = BOX.search(line)
            if m:
                box = (float(m.group(1)), float(m.group(2)))
                continue
            m = GRID.match(line)
            if m:
                grid = (int(m.group(1)), int(m.group(2)))
                continue
            m = COMM.match(line)
            if m:
                comm += float(m.group(1))
    return {"memory_mb": memory, "comm_share": comm / loop if loop > 0 else math.nan,
            "ke_met": ke_met, "flight_met": flight_met,
            "cpu_by_step": cpu_by_step, "work_by_step": work_by_step, "box": box, "grid": grid,
            "ghost_ratio": atoms["Nghost"] / atoms["Nlocal"] if atoms.get("Nlocal") else math.nan}


def cpu_to_step(cpu_by_step, step):
    """the CPU time of a log's runs up to the step (linear within a run)"""
    before = (0, 0.0)
    for after in cpu_by_step:
        if after[0] >= step:
            if after[0] == before[0]:
                return after[1]
            return before[1] + (after[1] - before[1]) * (step - before[0]) / (after[0] - before[0])
        before = after
    return math.nan


def chunks(row):
    """a run's chunks (its runs of more than 0 steps with counters; a run without joins the
    next): per chunk the size N and the pairs tested, the contacts and the CPU microseconds per
    particle-step. Counters that fall (a pair defined anew) start the next chunk from there."""
    out, before = [], (0, 0.0, 0, 0)
    n = int(row["N"])
    for (steps, cpu), work in zip(row["cpu_by_step"], row["work_by_step"]):
        if work is None:
            continue
        if steps > before[0] and work[1] >= before[2] and work[2] >= before[3]:
            d = steps - before[0]
            out.append((n, (work[1] - before[2]) / (n * d), (work[2] - before[3]) / (n * d),
                        1e6 * (cpu - before[1]) / (n * d)))
        before = (steps, cpu, work[1], work[2])
    return out


def work_fit(rows):
    """whether the time follows the work: the CPU time per particle-step of the smallest N's
    chunks fitted as a x pairs tested + b x contacts + c (per particle-step; non-negative least
    squares), then every N's chunks measured against that prediction. None with fewer than 2
    sizes or 3 chunks of the smallest; else {"fitted_n", "ns_per_pair", "ns_per_contact",
    "ns_per_particle", "ratio": {N: its chunks' measured / predicted time}}. A code whose cost
    follows its work keeps the ratio at 1 at every N; a working set leaving the caches raises
    it with N. Pairs and contacts rise together along a deposit, so the split of the cost
    between a and b is not determined; their prediction is."""
    data = [c for r in rows for c in chunks(r)]
    sizes = sorted({d[0] for d in data})
    if len(sizes) < 2:
        return None
    x = {n: np.array([[p, c, 1.0] for m, p, c, _ in data if m == n]) for n in sizes}
    y = {n: np.array([t for m, _, _, t in data if m == n]) for n in sizes}
    if len(y[sizes[0]]) < 3:
        return None
    coef = nnls(x[sizes[0]], y[sizes[0]])[0]
    return {"fitted_n": sizes[0], "ns_per_pair": 1e3 * coef[0],
            "ns_per_contact": 1e3 * coef[1], "ns_per_particle": 1e3 * coef[2],
            "ratio": {n: float(y[n].sum() / (x[n] @ coef).sum()) for n in sizes}}


def work_words(ranks, fit):
    """work_fit()'s answer in words"""
    return ("Time against work at %d rank%s: the CPU per particle-step of N = %d's chunks "
            "(the runs between checks) fitted as %.2f ns per pair tested + %.0f ns per contact "
            "+ %.0f ns per particle (non-negative least squares; pairs and contacts rise "
            "together, so their split is not determined, their prediction is); each N's chunks "
            "measured against that prediction: %s. A cost that follows the work stays at 1.00."
            % (ranks, "s" if ranks > 1 else "", fit["fitted_n"], fit["ns_per_pair"],
               fit["ns_per_contact"], fit["ns_per_particle"],
               ", ".join("N = %d %.2f" % (n, r) for n, r in fit["ratio"].items())))


def load(run_dirs):
    """the default setting's rows of the run folders, each with its log's memory and comm"""
    rows = []
    for folder in run_dirs:
        for r in read_rows(os.path.join(folder, "rows.csv")):
            if r["setting"] != "default":
                continue
            log = os.path.join(folder, "default-N%d-s%d" % (int(r["N"]), int(r["seed"])),
                               "log.lammps")
            if not os.path.exists(log):
                continue
            r.update(read_log(log))
            rows.append(r)
    return rows


def per_size(rows, common_steps):
    """{(N, ranks): medians over seeds}; "cpu_to_common": the CPU time to common_steps, the
    same physical time at every N"""
    groups = {}
    for r in rows:
        groups.setdefault((int(r["N"]), int(r["np"])), []).append(r)
    out = {}
    for (n, ranks), g in sorted(groups.items()):
        cpu = np.array([float(r["cpu_seconds"]) for r in g])
        steps = np.array([float(r["steps"]) for r in g])
        out[(n, ranks)] = {
            "seeds": len(g), "cpu_seconds": float(np.median(cpu)),
            "steps": float(np.median(steps)),
            "cpu_to_common": float(np.median([cpu_to_step(r["cpu_by_step"], common_steps)
                                              for r in g])),
            "us_per_particle_step": float(np.median(1e6 * cpu / (n * steps))),
            "contacts_per_particle_step": float(np.median(
                [float(r["contacts"]) / (n * float(r["steps"])) for r in g])),
            "ke_met": float(np.median([r["ke_met"] for r in g])),
            "flight_met": float(np.median([r["flight_met"] for r in g])),
            "memory_mb_per_rank": max(r["memory_mb"] for r in g),
            "peak_rss_mb": max((float(r["peak_rss_mb"]) for r in g if r.get("peak_rss_mb")),
                               default=math.nan),    # rows before the column have none
            "kb_per_particle": 1024 * max(r["memory_mb"] for r in g) * ranks / n,
            "comm_share": float(np.median([r["comm_share"] for r in g])),
            "ghost_ratio": float(np.median([r["ghost_ratio"] for r in g])),
            "box": g[0]["box"], "grid": g[0]["grid"],
            "cpu_by_step": g[0]["cpu_by_step"]}    # the first seed's, for the plot
    return out


def exponent(sizes, key):
    """the least-squares slope of log(key) against log(N) over the sizes of one rank count"""
    n = np.array([s[0] for s in sizes])
    y = np.array([sizes[s][key] for s in sizes])
    if len(n) < 2:
        return None
    return float(np.polyfit(np.log(n), np.log(y), 1)[0])


def write(rows, results, at_rest=None):
    """table.md and cost_curve.png in results; at_rest: run_replicate.medians() of the
    replicated deposit, drawn beside the whole deposits' time per particle-step"""
    common = int(min(float(r["steps"]) for r in rows))
    sizes = per_size(rows, common)
    lines = ["| N | ranks | seeds | CPU to deposit (s) | steps to rest | KE below ketol at step | "
             "flight below flytol at step | CPU to step %d (s) | us per particle-step | "
             "contacts per particle-step | memory per rank (MB, LAMMPS's estimate) | "
             "kB per particle | peak resident set of the largest rank (MB) | comm share |"
             % common,
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for (n, ranks), v in sizes.items():
        lines.append("| %d | %d | %d | %.0f | %.0f | %.0f | %.0f | %.0f | %.2f | %.2f | %.1f | "
                     "%.2f | %s | %.3f |"
                     % (n, ranks, v["seeds"], v["cpu_seconds"], v["steps"], v["ke_met"],
                        v["flight_met"], v["cpu_to_common"], v["us_per_particle_step"],
                        v["contacts_per_particle_step"], v["memory_mb_per_rank"],
                        v["kb_per_particle"],
                        "-" if math.isnan(v["peak_rss_mb"]) else "%.0f" % v["peak_rss_mb"],
                        v["comm_share"]))
    keys = ("cpu_seconds", "steps", "us_per_particle_step", "cpu_to_common",
            "contacts_per_particle_step")
    fits = {}    # {ranks: {key: exponent}}, one fit per rank count
    for ranks in sorted({s[1] for s in sizes}):
        same = {s: v for s, v in sizes.items() if s[1] == ranks}
        fits[ranks] = {k: exponent(same, k) for k in keys}
        shown = {k: "-" if fits[ranks][k] is None else "%.3f" % fits[ranks][k] for k in keys}
        lines.append("")
        lines.append("Exponents in N at %d rank%s (log-log least squares over %d sizes): CPU to "
                     "deposit %s = 1 + steps to rest %s + time per particle-step %s; CPU to "
                     "step %d (the same physical time at every N) %s; contacts per "
                     "particle-step %s."
                     % (ranks, "s" if ranks > 1 else "", len(same), shown["cpu_seconds"],
                        shown["steps"], shown["us_per_particle_step"], common,
                        shown["cpu_to_common"], shown["contacts_per_particle_step"]))
        fit = work_fit([r for r in rows if int(r["np"]) == ranks])
        if fit:
            lines.append("")
            lines.append(work_words(ranks, fit))
    lines.append("")
    lines.append(extrapolation(sizes, fits[base_size(sizes)[1]]["steps"]))
    os.makedirs(results, exist_ok=True)
    with open(os.path.join(results, "table.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    plot(sizes, os.path.join(results, "cost_curve.png"), at_rest)
    return sizes, fits


def plot(sizes, path, at_rest=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(15, 4))
    for ranks in sorted({s[1] for s in sizes}):
        pts = sorted(s for s in sizes if s[1] == ranks)
        n = [s[0] for s in pts]
        axes[0].loglog(n, [sizes[s]["cpu_seconds"] for s in pts], "o-",
                       label="%d rank%s" % (ranks, "s" if ranks > 1 else ""))
        axes[1].semilogx(n, [sizes[s]["us_per_particle_step"] for s in pts], "o-",
                         label="whole deposit, %d rank%s" % (ranks, "s" if ranks > 1 else ""))
    for ranks in sorted({m["np"] for m in at_rest or []}):
        pts = sorted((m["N"], m["us_per_particle_step"]) for m in at_rest if m["np"] == ranks)
        axes[1].semilogx(*zip(*pts), "s--", label="at rest, one deposit copied k x k, %d rank%s"
                         % (ranks, "s" if ranks > 1 else ""))
    n = np.array(sorted({s[0] for s in sizes}), float)
    first = sizes[min(sizes)]
    axes[0].loglog(n, first["cpu_seconds"] * n / n[0], "k:", label="linear in N")
    axes[0].set_xlabel("N")
    axes[0].set_ylabel("CPU time to deposit (s)")
    axes[0].legend(fontsize=8)
    axes[1].set_xlabel("N")
    axes[1].set_ylabel("CPU per particle-step (us)")
    axes[1].set_ylim(bottom=0)
    axes[1].legend(fontsize=8)
    for (n, ranks), v in sizes.items():    # CPU per particle-step of each run (chunk)
        steps, cpu = zip(*[(0, 0.0)] + list(v["cpu_by_step"]))
        per = [1e6 * (cpu[i] - cpu[i - 1]) / (n * (steps[i] - steps[i - 1]))
               for i in range(1, len(steps)) if steps[i] > steps[i - 1]]
        at = [steps[i] for i in range(1, len(steps)) if steps[i] > steps[i - 1]]
        axes[2].plot(at, per, "-", lw=1, label="N = %d, %d rank%s"
                     % (n, ranks, "s" if ranks > 1 else ""))
    axes[2].set_xlabel("step")
    axes[2].set_ylabel("CPU per particle-step in each chunk (us)")
    axes[2].set_ylim(bottom=0)
    axes[2].legend(fontsize=8)
    fig.suptitle("the default deposit (eta 1.4, zeta 1.8, delta_r 0.6) against N; medians over "
                 "seeds", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="run folders of run_accuracy.py (rows.csv, logs)")
    ap.add_argument("--results", required=True)
    ap.add_argument("--replicate", help="rows.csv of run_replicate.py: the time per "
                    "particle-step at rest drawn beside the whole deposits'")
    args = ap.parse_args(argv)
    rows = load(args.runs)
    if not rows:
        sys.exit("cost_table: no default-setting rows with their logs in %s" % args.runs)
    at_rest = None
    if args.replicate:
        if not os.path.isfile(args.replicate):
            sys.exit("cost_table: --replicate %s: no such file" % args.replicate)
        at_rest = medians(read_rows(args.replicate))
    write(rows, args.results, at_rest)
    print(open(os.path.join(args.results, "table.md")).read())


if __name__ == "__main__":
    main()
