"""The table of run_accuracy.py: per setting of the contact knobs the median cost of a deposit
(CPU time, steps to rest, CPU time per particle-step, each also as a ratio to the default) and
what it computes (phi, Z, the contact-normal histogram) against the default.

* Cost: the medians over the seeds; per particle-step also the median over the seeds of the
  ratio to the default's run of the same seed (the two ran one after the other).
* phi and Z: the difference of the setting's seed mean from the default's in units of the
  pooled seed SD, sqrt(((n_s - 1) SD_s^2 + (n_d - 1) SD_d^2) / (n_s + n_d - 2)). Within the
  seed spread when that is at most 2 sqrt(1/n_s + 1/n_d), i.e. two standard errors of the
  difference (1.63 pooled SD for 3 seeds each).
* The histogram (fraction of the slab's contact normals per polar-angle bin): the L1 distance
  of each seed's histogram to the default's seed mean, the median over the seeds. The default's
  own seeds are measured against the mean of the other default seeds (leave one out), which is
  the spread a setting that changes nothing shows. Within the seed spread when the setting's
  median is at most the largest of the default's leave-one-out distances.
* The pair's counters summed over the seeds: iterations and normal corrections per contact
  evaluation, evaluations that did not converge.
"""
import csv
import math
import os

import numpy as np

BINS = 18


def groups(rows):
    """{setting: its rows}, the default first, the others in the order they first ran"""
    out = {}
    for r in sorted(rows, key=lambda r: r["setting"] != "default"):
        out.setdefault(r["setting"], []).append(r)
    return out


def histograms(rows):
    return np.array([[float(r["F%d" % k]) for k in range(BINS)] for r in rows])


def pooled_sd(a, b):
    """pooled standard deviation of two samples (NaN without a degree of freedom)"""
    dof = len(a) + len(b) - 2
    if dof < 1:
        return float("nan")
    ss = sum(float(np.sum((np.asarray(x) - np.mean(x)) ** 2)) for x in (a, b) if len(x) > 1)
    return math.sqrt(ss / dof)


def leave_one_out_l1(F):
    """L1 distance of each histogram (row) to the mean of the others"""
    n = len(F)
    if n < 2:
        return np.full(n, np.nan)
    total = F.sum(axis=0)
    return np.array([np.abs(F[i] - (total - F[i]) / (n - 1)).sum() for i in range(n)])


def stats(rows):
    f = lambda key: np.array([float(r[key]) for r in rows])
    sd = lambda a: float(a.std(ddof=1)) if len(a) > 1 else float("nan")
    n_particles = f("N")
    counters = {k: float(f(k).sum()) for k in ("contacts", "iterations", "corrections",
                                               "not_converged")}
    return {"n": len(rows), "keywords": rows[0]["keywords"],
            "cpu": float(np.median(f("cpu_seconds"))),
            "steps": float(np.median(f("steps"))),
            "us_per_particle_step": float(np.median(
                1e6 * f("cpu_seconds") / (n_particles * f("steps")))),
            "step_cost_by_seed": dict(zip((r["seed"] for r in rows),
                                          1e6 * f("cpu_seconds") / (n_particles * f("steps")))),
            "phis": f("phi"), "phi": float(f("phi").mean()), "phi_sd": sd(f("phi")),
            "Zs": f("Z"), "Z": float(f("Z").mean()), "Z_sd": sd(f("Z")),
            "F": histograms(rows), "all_at_rest": int(f("at_rest").min()),
            "warnings": int(f("warnings").sum()),
            "iterations_per_contact": counters["iterations"] / max(counters["contacts"], 1.0),
            "corrections_per_contact": counters["corrections"] / max(counters["contacts"], 1.0),
            "not_converged": int(counters["not_converged"])}


def compare(s, d):
    """the setting s against the default d (both from stats())"""
    # per step: the ratio to the default's run of the same seed, which ran just before it
    # (a drift of the machine's load reaches both alike), the median over the seeds
    seeds = [k for k in s["step_cost_by_seed"] if k in d["step_cost_by_seed"]]
    res = {"cpu_ratio": s["cpu"] / d["cpu"],
           "step_cost_ratio": float(np.median([s["step_cost_by_seed"][k] /
                                               d["step_cost_by_seed"][k] for k in seeds]))
           if seeds else float("nan"),
           "steps_ratio": s["steps"] / d["steps"]}
    limit = 2 * math.sqrt(1 / s["n"] + 1 / d["n"])
    if s["n"] < 2 or d["n"] < 2:    # no seed spread to compare with
        limit = float("nan")
    for key in ("phi", "Z"):
        sd = pooled_sd(s[key + "s"], d[key + "s"])
        res["d_" + key] = (s[key] - d[key]) / sd if sd > 0 else float("nan")
        res["agree_" + key] = bool(abs(res["d_" + key]) <= limit)
    own = leave_one_out_l1(d["F"])
    mean_d = d["F"].mean(axis=0)
    dist = own if s is d else np.abs(s["F"] - mean_d).sum(axis=1)
    res["hist_l1"] = float(np.median(dist))
    res["hist_l1_ratio"] = res["hist_l1"] / float(np.median(own))
    res["agree_hist"] = bool(res["hist_l1"] <= float(np.max(own)))
    res["agree"] = res["agree_phi"] and res["agree_Z"] and res["agree_hist"]
    res["limit_pooled_sd"] = limit
    return res


def fmt_row(name, s, c):
    agree = "yes" if c["agree"] else "n/a (< 2 seeds)" if math.isnan(c["limit_pooled_sd"]) \
        else "no (%s)" % ", ".join(
        m for m in ("phi", "Z", "hist") if not c["agree_" + m])
    return ("| %s | %s | %d | %.0f | %.2f | %.0f | %.3f | %.2f | %.4f +- %.4f | %+.2f | "
            "%.3f +- %.3f | %+.2f | %.4f | %.2f | %.3f | %.3f | %d | %s |"
            % (name, s["keywords"], s["n"], s["cpu"], c["cpu_ratio"], s["steps"],
               s["us_per_particle_step"], c["step_cost_ratio"], s["phi"], s["phi_sd"],
               c["d_phi"], s["Z"], s["Z_sd"], c["d_Z"], c["hist_l1"], c["hist_l1_ratio"],
               s["iterations_per_contact"], s["corrections_per_contact"], s["not_converged"],
               "(reference)" if name == "default" else agree))


HEADER = ["| setting | pair_style keywords | seeds | CPU time (s, median) | CPU / default "
          "| steps to rest (median) | CPU us per particle-step (median) | per step / default "
          "(same seed, median) "
          "| phi (mean +- SD) | d phi (pooled SD) | Z (mean +- SD) | d Z (pooled SD) "
          "| histogram L1 to default mean (median) | L1 / default's own | iterations per "
          "contact | corrections per contact | not converged | within the seed spread |",
          "|" + "---|" * 18]


def write(rows, out_dir):
    g = {name: stats(rs) for name, rs in groups(rows).items()}
    if "default" not in g:
        raise SystemExit("accuracy_table: no default rows: nothing to compare against")
    d = g["default"]
    lines = list(HEADER)
    summary = []
    for name, s in g.items():
        c = compare(s, d)
        lines.append(fmt_row(name, s, c))
        row = {"setting": name, "keywords": s["keywords"], "seeds": s["n"],
               "cpu_median": s["cpu"], "steps_median": s["steps"],
               "us_per_particle_step": s["us_per_particle_step"], "phi": s["phi"],
               "phi_sd": s["phi_sd"], "Z": s["Z"], "Z_sd": s["Z_sd"],
               "all_at_rest": s["all_at_rest"], "warnings": s["warnings"],
               "iterations_per_contact": s["iterations_per_contact"],
               "corrections_per_contact": s["corrections_per_contact"],
               "not_converged": s["not_converged"]}
        row.update(c)
        summary.append(row)
    commits = sorted({r["commit"] for r in rows})
    dates = sorted(r["started_utc"] for r in rows)
    loads = [float(r[k]) for r in rows for k in ("load_start", "load_end")]
    head = ("N = %s, %s MPI rank(s), one deposit at a time; commit %s; runs started %s to %s "
            "UTC; load average %.1f-%.1f. Within the seed spread: |d| <= %.2f pooled SD for "
            "phi and Z, histogram L1 <= the default's largest leave-one-out L1 (%.4f)."
            % (rows[0]["N"], rows[0]["np"], ", ".join(commits), dates[0], dates[-1],
               min(loads), max(loads), summary[0]["limit_pooled_sd"],
               float(np.max(leave_one_out_l1(d["F"])))))
    agreeing = sorted((r for r in summary if r["setting"] != "default" and r["agree"]),
                      key=lambda r: r["cpu_median"])
    if agreeing:
        best = agreeing[0]
        verdict = ("Cheapest setting within the seed spread of the default in phi, Z and the "
                   "histogram: %s (%s), %.2fx the default's CPU time to deposit, %.2fx per "
                   "particle-step." % (best["setting"], best["keywords"], best["cpu_ratio"],
                                       best["step_cost_ratio"]))
    else:
        verdict = "No setting other than the default measured within the seed spread."
    with open(os.path.join(out_dir, "table.md"), "w") as f:
        f.write(head + "\n\n" + "\n".join(lines) + "\n\n" + verdict + "\n")
    keys = list(summary[0])
    with open(os.path.join(out_dir, "summary.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in summary:
            w.writerow(r)
    plot(g, rows[0]["N"], os.path.join(out_dir, "histograms.png"))
    print(head + "\n\n" + "\n".join(lines) + "\n\n" + verdict)


def plot(g, n, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    theta = (np.arange(BINS) + 0.5) * 180.0 / BINS    # bins of [0, pi]
    fig, (ax, dx) = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True,
                                 gridspec_kw={"height_ratios": [2, 1]})
    mean_d = g["default"]["F"].mean(axis=0)
    for k, (name, s) in enumerate(g.items()):
        mean = s["F"].mean(axis=0)
        sd = s["F"].std(axis=0, ddof=1) if s["n"] > 1 else None
        shift = (k - (len(g) - 1) / 2) * 1.2    # side by side within a bin
        ax.errorbar(theta + shift, mean, yerr=sd, marker="o", ms=3, capsize=2, lw=1,
                    label="%s (%d seeds)" % (name, s["n"]))
        dx.errorbar(theta + shift, mean - mean_d, yerr=sd, marker="o", ms=3, capsize=2, lw=1)
    ax.set_ylabel("fraction of contact normals")
    ax.set_title("contact normals, default deposit N = %s (bars: seed SD)" % n)
    ax.legend(fontsize=8)
    dx.axhline(0, color="grey", lw=0.8)
    dx.set_ylabel("minus the default's mean")
    dx.set_xlabel(r"$\theta$ (degrees from vertical)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
