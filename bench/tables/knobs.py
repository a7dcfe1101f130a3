"""Table 2, the speed-accuracy trade of pair_style granular/ellipsoid's knobs: per-contact
normal and overlap errors against `preset accurate` on a settled configuration, the cost of
each setting, and the Pareto front over both (with its plot)."""
import math
import re

from .lmp_runs import NWARM, contacts_per_particle, fmt_table, med, parse_log, run_lmp

# Knob grid of pair_style granular/ellipsoid (label, pair_style arguments).
KNOBS = [
    ("default", "planes yes"),
    ("preset accurate", "preset accurate"),
    ("preset fast", "preset fast"),
    ("tolerance 1e-6", "tolerance 1e-6"),
    ("tolerance 1e-8", "tolerance 1e-8"),
    ("tolerance 1e-10", "tolerance 1e-10"),
    ("iterations 3", "iterations 3"),
    ("iterations 5", "iterations 5"),
    ("iterations 10", "iterations 10"),
    ("correction 1", "correction 1.0"),
    ("correction 5", "correction 5.0"),
    ("correction 15", "correction 15.0"),
    ("planes no", "planes no"),
    ("wang no", "wang no"),
    ("planes no wang no", "planes no wang no"),
    ("fast + correction 5", "preset fast correction 5.0"),
]


def bench_knobs(out, data_e, nsteps, repeats, nmobile, nfloor):
    # accuracy: per-contact overlap and normal against `preset accurate`, same configuration
    ref = None
    acc = {}
    for label, knobs in [KNOBS[1]] + [k for k in KNOBS if k[0] != "preset accurate"]:
        tag = "k_" + re.sub(r"\W+", "_", label)
        _, pairs = contacts_per_particle(out, data_e, nfloor, nmobile, knobs=knobs, tag=tag)
        if ref is None:
            ref = pairs
        nerr, oerr, nmiss = [], [], 0
        for key, rr in ref.items():
            if rr[2] <= 0.0:
                continue
            r = pairs.get(key)
            if r is None or r[2] <= 0.0:
                nmiss += 1
                continue
            dot = max(-1.0, min(1.0, sum(a * b for a, b in zip(rr[3:6], r[3:6]))))
            nerr.append(math.degrees(math.acos(abs(dot))))
            oerr.append(abs(r[2] - rr[2]) / rr[2])
        acc[label] = {"n": len(nerr), "missed": nmiss,
                      "normal_max_deg": max(nerr) if nerr else 0.0,
                      "normal_med_deg": med(nerr) if nerr else 0.0,
                      "overlap_max_rel": max(oerr) if oerr else 0.0,
                      "overlap_med_rel": med(oerr) if oerr else 0.0}
    # cost: interleaved timing repeats
    times = {k[0]: [] for k in KNOBS}
    pairs_pct = {k[0]: [] for k in KNOBS}
    counters = {}
    for r in range(repeats):
        for label, knobs in KNOBS:
            tag = "kt_" + re.sub(r"\W+", "_", label) + f"_{r}"
            x = parse_log(run_lmp(out, "in.run_ours", f"log.{tag}",
                                  {"data": data_e, "knobs": knobs, "nsteps": nsteps,
                                   "nwarm": NWARM}))
            times[label].append(1e9 * x["loop"] / (nmobile * x["steps"]))
            pairs_pct[label].append(x["pair_pct"])
            counters[label] = x.get("counters", "")
        print(f"  knob repeat {r + 1}/{repeats} done", flush=True)
    table = []
    for label, knobs in KNOBS:
        row = {"label": label, "knobs": knobs, "ns": med(times[label]),
               "pair_pct": med(pairs_pct[label]), "counters": counters[label]}
        row.update(acc[label])
        table.append(row)
    # Pareto front over (cost, max normal error, max overlap error, contacts missed)
    for row in table:
        row["pareto"] = not any(
            (o["ns"] <= row["ns"] and o["normal_max_deg"] <= row["normal_max_deg"]
             and o["overlap_max_rel"] <= row["overlap_max_rel"] and o["missed"] <= row["missed"])
            and (o["ns"] < row["ns"] or o["normal_max_deg"] < row["normal_max_deg"]
                 or o["overlap_max_rel"] < row["overlap_max_rel"] or o["missed"] < row["missed"])
            for o in table)
    return table


def knobs_markdown(table):
    base = next(r["ns"] for r in table if r["label"] == "default")
    rows = [[r["label"], f"{r['ns']:.0f}", f"{r['ns'] / base:.2f}", f"{r['pair_pct']:.1f}",
             f"{r['normal_max_deg']:.2e}", f"{r['overlap_max_rel']:.2e}",
             f"{r['overlap_med_rel']:.1e}", f"{r['missed']}/{r['n'] + r['missed']}",
             "yes" if r["pareto"] else ""] for r in table]
    return fmt_table(["pair_style knobs", "ns/particle-step", "cost / default", "Pair %",
                      "max normal err (deg)", "max overlap err (rel)", "median overlap err",
                      "contacts missed", "Pareto"], rows)


def plot_knobs(table, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("  (matplotlib missing: no plot)")
        return False
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for ax, key, name in ((axes[0], "normal_max_deg", "max normal error vs accurate (deg)"),
                          (axes[1], "overlap_max_rel", "max relative overlap error vs accurate")):
        floor = 1e-17
        for r in table:
            y = max(r[key], floor)
            ax.scatter(r["ns"], y, c="C3" if r["pareto"] else "C0", s=30)
            ax.annotate(r["label"], (r["ns"], y), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")
        front = sorted([r for r in table if r["pareto"]], key=lambda r: r["ns"])
        ax.plot([r["ns"] for r in front], [max(r[key], floor) for r in front], "C3--",
                lw=1, label="Pareto front (cost, normal, overlap, missed)")
        ax.set_yscale("log")
        ax.set_xlabel("ns per particle-step (whole step)")
        ax.set_ylabel(name)
        ax.legend(fontsize=7)
    fig.suptitle("granular/ellipsoid knobs: error vs cost (settled deposit)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    return True
