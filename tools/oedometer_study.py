#!/usr/bin/env python3
"""The oedometer along the diagonal eta = zeta (examples/oedometer): constrained modulus and
K0 against the asphericity a/c = eta zeta, with the seeds' spread.

    ./ellipsoid-dep python tools/oedometer_study.py run [--N 500] [--np 2] [--runs DIR]
    ./ellipsoid-dep python tools/oedometer_study.py report

run:    each case missing from results/oedometer/oedometer.csv through tools/oedometer_run.py
        (a seed through every shape, cheapest first: spheres, then growing asphericity; then
        the next seed), its rows appended to the csv.
report: from the csv alone: results/oedometer/summary.csv (one row per case), the figure
        results/oedometer/modulus_k0.png and examples/oedometer/study_section.md (every
        number in it comes from the csv).

Per case: M_load, the modulus of the last loading step (2 -> 4 sigma_w), M_unload, that of
the first unloading step (4 -> 2 sigma_w), K0 at the largest load and after unloading to the
last load, eps_zz at the largest load. Two seeds: mean and the standard error |x1 - x2| / 2.
"""
import argparse
import csv
import math
import os
import sys

import oedometer_run

ROOT = oedometer_run.deposit_run.ROOT
RESULTS = os.path.join(ROOT, "results", "oedometer")
TABLE = os.path.join(RESULTS, "oedometer.csv")
SUMMARY = os.path.join(RESULTS, "summary.csv")
FIGURE = os.path.join(RESULTS, "modulus_k0.png")
SECTION = os.path.join(ROOT, "examples", "oedometer", "study_section.md")
SHAPES = (1.0, 1.4, 2.0, 3.0)     # eta = zeta, cheapest first
SEEDS = (4928, 4929)
SUMMARY_COLUMNS = ["eta", "zeta", "aspect", "seed", "N", "M_load", "M_unload", "K0_max",
                   "K0_end", "K0_first", "eps_max", "phi_first", "phi_max", "sigma_w",
                   "at_rest"]


def read_table(path=TABLE):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def case_key(row):
    return (float(row["eta"]), float(row["zeta"]), int(row["seed"]), int(row["N"]))


def run(args):
    os.makedirs(RESULTS, exist_ok=True)
    done = {case_key(r) for r in read_table()}
    for seed in args.seeds:
        for shape in args.shapes:
            if (shape, shape, seed, args.N) in done:
                continue
            out = os.path.join(args.runs, "eta%g-seed%d-N%d" % (shape, seed, args.N))
            rows = oedometer_run.main(["--N", str(args.N), "--eta", str(shape), "--zeta",
                                       str(shape), "--dr", "0", "--seed", str(seed),
                                       "--np", str(args.np), "--out", out, "--quiet"])
            new = not os.path.exists(TABLE)
            with open(TABLE, "a", newline="") as f:
                w = csv.DictWriter(f, fieldnames=oedometer_run.COLUMNS)
                if new:
                    w.writeheader()
                for r in rows:
                    w.writerow({k: ("%.8g" % v if isinstance(v, float) else v)
                                for k, v in r.items()})


def summarise(rows):
    """one dict per case from its rows (levels in order)"""
    cases = {}
    for r in rows:
        cases.setdefault(case_key(r), []).append(r)
    out = []
    for key, levels in sorted(cases.items()):
        f = [{k: (float(v) if v not in ("", "load", "unload") else v) for k, v in lv.items()}
             for lv in levels]
        top = max(range(len(f)), key=lambda i: f[i]["load"])
        out.append({"eta": key[0], "zeta": key[1], "aspect": key[0] * key[1], "seed": key[2],
                    "N": key[3], "M_load": f[top]["M"], "M_unload": f[top + 1]["M"],
                    "K0_max": f[top]["K0"], "K0_end": f[-1]["K0"], "K0_first": f[0]["K0"],
                    "eps_max": f[top]["eps_zz"], "phi_first": f[0]["phi_slab"],
                    "phi_max": f[top]["phi_slab"], "sigma_w": f[0]["sigma_w"],
                    "at_rest": int(min(lv["at_rest"] for lv in f)),
                    "loads": [lv["load"] for lv in f]})
    return out


def by_shape(summary, name):
    """{aspect: (mean, standard error, seeds)} of one quantity"""
    groups = {}
    for s in summary:
        groups.setdefault(s["aspect"], []).append(s[name])
    result = {}
    for aspect, xs in sorted(groups.items()):
        mean = sum(xs) / len(xs)
        se = (math.sqrt(sum((x - mean)**2 for x in xs) / (len(xs) - 1) / len(xs))
              if len(xs) > 1 else float("nan"))
        result[aspect] = (mean, se, len(xs))
    return result


def plot(summary, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(9, 3.8))
    for name, label, mark in (("M_load", "loading 2 to 4 $\\sigma_w$", "o-"),
                              ("M_unload", "unloading 4 to 2 $\\sigma_w$", "s--")):
        g = by_shape(summary, name)
        ax.errorbar(list(g), [v[0] for v in g.values()], yerr=[v[1] for v in g.values()],
                    fmt=mark, capsize=3, label=label)
    for name, label, mark in (("K0_max", "at 4 $\\sigma_w$ (loading)", "o-"),
                              ("K0_end", "after unloading", "s--")):
        g = by_shape(summary, name)
        bx.errorbar(list(g), [v[0] for v in g.values()], yerr=[v[1] for v in g.values()],
                    fmt=mark, capsize=3, label=label)
    ax.set_ylabel(r"constrained modulus $M$ ($\rho g d$)")
    bx.set_ylabel(r"$K_0 = \sigma_{xx}/\sigma_{zz}$ (slab)")
    for a in (ax, bx):
        a.set_xlabel(r"asphericity $a/c = \eta\zeta$ ($\eta = \zeta$, $\delta_r = 0$)")
        a.set_xscale("log")
        a.minorticks_off()
        a.set_xticks(sorted({s["aspect"] for s in summary}))
        a.set_xticklabels(["%g" % x for x in sorted({s["aspect"] for s in summary})])
        a.legend(fontsize=8)
        a.grid(alpha=0.3)
    n = summary[0]["N"]
    fig.suptitle("oedometer along the diagonal, N = %d, mean and seed error" % n)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def span(groups, digits):
    """'x' when every group's mean prints alike, else 'x to y'"""
    means = ["%.*f" % (digits, v[0]) for v in groups.values()]
    lo, hi = min(groups.values())[0], max(groups.values())[0]
    return means[0] if len(set(means)) == 1 else "%.*f to %.*f" % (digits, lo, digits, hi)


def fmt(value, se, digits):
    return "%.*f +- %.*f" % (digits, value, digits, se)


def section(summary):
    """the text of the doc/study.md section, numbers from the summary"""
    n = summary[0]["N"]
    seeds = sorted({s["seed"] for s in summary})
    loads = " ".join("%g" % x for x in summary[0]["loads"])
    sigw = by_shape(summary, "sigma_w")
    quantities = [("M_load", 0), ("M_unload", 0), ("K0_first", 3), ("K0_max", 3),
                  ("K0_end", 3), ("eps_max", 4), ("phi_max", 3)]
    table = {q: by_shape(summary, q) for q, _ in quantities}
    lines = [
        "## Oedometric compression along the diagonal (issue 30)",
        "",
        "<!-- generated by tools/oedometer_study.py report from results/oedometer/"
        "oedometer.csv; do not edit by hand -->",
        "",
        "A deposit of in.deposit's protocol (N = %d, delta_r = 0, eta = zeta, seeds %s), "
        "laterally periodic, loaded by a frictionless servo piston (examples/oedometer/"
        "in.oedometer) in steps of %s sigma_w and unloaded; sigma_w = (the deposit's weight) / "
        "(Lx Ly) = %s rho g d. The strain is eps_zz = (H0 - z_p) / H0 with "
        "H0 the piston's height under the first load; M = d sigma / d eps_zz over one step, "
        "with the piston's stress; K0 = sigma_xx / sigma_zz of the slab (per-atom virial); "
        "examples/oedometer/README.md defines them and the rest criterion. "
        "Errors: standard error over the %d seeds (|x1 - x2| / 2 for two). N = %d, not the "
        "study's 1000: the runs shared 2 cores with the study and other jobs and had to fit "
        "in about an hour; in.deposit's box grows as sqrt(N), so the deposit's height and sigma_w are "
        "those of N = 1000, and its edge stays wider than two neighbour cut-offs of the "
        "longest particles (eta = zeta = 3). Not in the paper; no peer reports it for "
        "ellipsoids. Figure: results/oedometer/modulus_k0.png; data: "
        "results/oedometer/oedometer.csv (every step) and summary.csv (every run)."
        % (n, ", ".join(str(s) for s in seeds), loads, span(sigw, 3), len(seeds), n),
        "",
        "| a/c | M loading 2-4 sigma_w | M unloading 4-2 sigma_w | K0 at %g sigma_w | "
        "K0 at %g sigma_w | K0 after unloading | eps_zz at %g sigma_w | phi at %g sigma_w |"
        % (summary[0]["loads"][0], max(summary[0]["loads"]), max(summary[0]["loads"]),
           max(summary[0]["loads"])),
        "|---|---|---|---|---|---|---|---|",
    ]
    for aspect in sorted(table["M_load"]):
        cells = [fmt(table[q][aspect][0], table[q][aspect][1], d)
                 for q, d in (("M_load", 0), ("M_unload", 0), ("K0_first", 3), ("K0_max", 3),
                              ("K0_end", 3), ("eps_max", 4), ("phi_max", 3))]
        lines.append("| %g | %s |" % (aspect, " | ".join(cells)))
    missing = [x for x in SHAPES if x * x not in table["M_load"]]
    if missing:
        lines += ["", "Not in the table: eta = zeta = %s (planned; examples/oedometer/README.md, "
                  "\"Limits\", says why)." % ", ".join("%g" % x for x in missing)]
    lines += ["", "![modulus and K0 against a/c](../results/oedometer/modulus_k0.png)", ""]
    lines += verdicts(summary, table)
    return "\n".join(lines) + "\n"


def seed_values(summary, name):
    """{aspect: [the quantity of each seed]}"""
    groups = {}
    for s in summary:
        groups.setdefault(s["aspect"], []).append(s[name])
    return groups


def verdicts(summary, table):
    """per quantity, each shape against the spheres: the difference, its standard error and
    Welch's t-test over the seeds (two seeds a shape: about 2 degrees of freedom, so only a
    large difference is significant at 5 %)"""
    from scipy import stats
    out = ["Each shape against the spheres (difference +- its standard error; p of Welch's "
           "t-test over the seeds; significant: p < 0.05):", ""]
    for q, name, digits in (("M_load", "M loading", 0), ("M_unload", "M unloading", 0),
                            ("K0_max", "K0 at the largest load", 3),
                            ("K0_end", "K0 after unloading", 3)):
        values = seed_values(summary, q)
        ref = min(values)
        parts = []
        for aspect in sorted(values):
            if aspect == ref:
                continue
            diff = table[q][aspect][0] - table[q][ref][0]
            err = math.hypot(table[q][aspect][1], table[q][ref][1])
            p = stats.ttest_ind(values[aspect], values[ref], equal_var=False).pvalue
            parts.append("a/c %g: %+.*f +- %.*f (p %.2f%s)"
                         % (aspect, digits, diff, digits, err, p,
                            ", significant" if p < 0.05 else ""))
        out.append("* %s: %s." % (name, "; ".join(parts)))
    stiff = max(table["M_load"], key=lambda a: table["M_load"][a][0])
    dense = max(table["phi_max"], key=lambda a: table["phi_max"][a][0])
    out.append("* The stiffest shape in loading is a/c %g; the densest at the largest load is "
               "a/c %g (phi %.3f against %s)."
               % (stiff, dense, table["phi_max"][dense][0],
                  ", ".join("%.3f" % table["phi_max"][a][0] for a in sorted(table["phi_max"])
                            if a != dense)))
    ratios = {a: table["M_unload"][a][0] / table["M_load"][a][0] for a in table["M_load"]}
    out.append("* M unloading / M loading: %s (unloading is %s at every shape)."
               % (", ".join("%.2f at a/c %g" % (ratios[a], a) for a in sorted(ratios)),
                  "stiffer" if all(r > 1 for r in ratios.values()) else "not stiffer"))
    return out


def report():
    rows = read_table()
    if not rows:
        sys.exit("oedometer_study: %s holds no run; run first" % TABLE)
    summary = summarise(rows)
    with open(SUMMARY, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=SUMMARY_COLUMNS)
        w.writeheader()
        for s in summary:
            w.writerow({k: ("%.8g" % s[k] if isinstance(s[k], float) else s[k])
                        for k in SUMMARY_COLUMNS})
    plot(summary, FIGURE)
    with open(SECTION, "w") as f:
        f.write(section(summary))
    print("oedometer_study: wrote %s, %s, %s" % (SUMMARY, FIGURE, SECTION))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mode", choices=("run", "report"))
    ap.add_argument("--N", type=int, default=500, help="particles (default 500)")
    ap.add_argument("--np", type=int, default=2, help="MPI ranks (default 2)")
    ap.add_argument("--seeds", type=int, nargs="+", default=list(SEEDS),
                    help="seeds, each through every shape (default %s)" % " ".join(map(str, SEEDS)))
    ap.add_argument("--shapes", type=float, nargs="+", default=list(SHAPES),
                    help="eta = zeta of the cases (default %s)" % " ".join("%g" % x for x in SHAPES))
    ap.add_argument("--runs", default=os.path.join(ROOT, "runs", "oedometer"),
                    help="folder of the runs (default runs/oedometer)")
    args = ap.parse_args(argv)
    if args.mode == "run":
        run(args)
    report()


if __name__ == "__main__":
    main()
