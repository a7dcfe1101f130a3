"""The silo study's wall stress: Janssen fitted per run, K and the mobilised wall friction over
seeds, the README's table and the figure.

    ./ellipsoid-dep python examples/silo/plot_silo.py [--table] [--figure silo.png]

Reads the runs of silo_runs.py (results/R<R>/<shape>/seed<k>/: wall.dat, run.json). Per run
(tools/containers/silo_wall.py), over the bins of the fit (FIT: at least FLOOR d above the
floor and TOP d below the fill height H, depth h = H - z of the bin's middle):
* Janssen's profile fitted to the wall's normal stress sigma_w(h): A, lambda, and from them
  with the bulk weight density rho_b g = weight / (pi R^2 H) the mobilised friction
  mu = rho_b g R / (2 A) and K = A / (rho_b g lambda);
* the same read directly off the data: mu_mob = sum tau_w / sum sigma_w and
  K = sum sigma_w / sum sigma_v, sigma_v the bulk's vertical stress from the force balance of
  the particles above each bin's middle (the weight less the wall's support).
Over the seeds: mean +- standard error (SD / sqrt(n)), n given.
"""
import argparse
import glob
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt    # noqa: E402
import numpy as np                 # noqa: E402

import silo_runs                   # noqa: E402
import silo_wall                   # noqa: E402

FLOOR, TOP = 1.0, 1.0
LABELS = {"spheres": "spheres", "eta1.4_zeta1.8": "eta 1.4 zeta 1.8",
          "eta2_zeta2": "eta 2 zeta 2"}


def load(folder):
    """one run: its run.json with the wall table (columns of run_silo.WALL_COLUMNS)"""
    run = json.load(open(os.path.join(folder, "run.json")))
    names = open(os.path.join(folder, "wall.dat")).readline().lstrip("# ").split()
    table = np.loadtxt(os.path.join(folder, "wall.dat"), ndmin=2)
    run["wall"] = {name: table[:, k] for k, name in enumerate(names)}
    return run


def analyse(run):
    """the fit and the direct ratios of one run over the bins of the fit"""
    w = run["wall"]
    keep = (w["z_lo"] >= FLOOR) & (w["h"] >= TOP)
    fit = silo_wall.fit_janssen(w["h"][keep], w["sigma_w"][keep], run["rho_g"], run["R"])
    _, _, k_data, mu_data = silo_wall.profile_ratios(w["sigma_w"][keep], w["tau_w"][keep],
                                                     w["sigma_v"][keep])
    halves = {}
    for name, part in (("upper", keep & (w["h"] < run["H"] / 2)),
                       ("lower", keep & (w["h"] >= run["H"] / 2))):
        _, _, halves["K_" + name], halves["mu_" + name] = silo_wall.profile_ratios(
            w["sigma_w"][part], w["tau_w"][part], w["sigma_v"][part])
    window = np.median(w["sd_sigma_w"][keep] / w["sigma_w"][keep])
    return dict(fit, K_data=k_data, mu_data=mu_data, window=window, **halves,
                side=run["side"] / run["weight"], bins=int(keep.sum()))


def runs(results=silo_runs.RESULTS):
    """{(R, shape): [run, ...]} of the finished runs, silo_runs's order"""
    out = {}
    for radius in silo_runs.SILOS:
        for shape in silo_runs.SHAPES:
            found = sorted(glob.glob(os.path.join(results, "R%g" % radius, shape, "seed*",
                                                  "run.json")))
            if found:
                out[(radius, shape)] = [load(os.path.dirname(path)) for path in found]
    return out


def summary(group):
    """mean +- SE over the seeds of each quantity, and n"""
    fits = [dict(analyse(r), rho_g=r["rho_g"], H=r["H"], N=r["N"],
                 balance=abs(r["balance_mean"])) for r in group]
    return {key: silo_wall.over_seeds([f[key] for f in fits]) for key in fits[0]}, len(fits)


def pm(stat, digits):
    mean, _, se = stat
    return "%.*f" % (digits, mean) if math.isnan(se) else "%.*f +- %.*f" % (digits, mean,
                                                                             digits, se)


def table(groups):
    """the README's table (markdown) of {(R, shape): [run, ...]}"""
    lines = ["| R / d | shape | seeds | N | H / R | rho_b g | Janssen fit: K | mu | lambda / R "
             "| rms / A | data: K = sigma_w / sigma_v | mu_mob = tau_w / sigma_w "
             "| upper half: K, mu_mob | lower half: K, mu_mob | side's share of the weight |",
             "|---" * 15 + "|"]
    for (radius, shape), group in groups.items():
        s, n = summary(group)
        lam_r = (s["lambda"][0] / radius, math.nan, s["lambda"][2] / radius)
        rms = (s["rms"][0] / s["A"][0], math.nan, math.nan)
        lines.append("| %g | %s | %d | %.0f | %.1f | %s | %s | %s | %s | %.3f | %s | %s "
                     "| %s, %s | %s, %s | %s |" % (
                         radius, LABELS[shape], n, s["N"][0], s["H"][0] / radius,
                         pm(s["rho_g"], 3), pm(s["K"], 2), pm(s["mu"], 3), pm(lam_r, 2), rms[0],
                         pm(s["K_data"], 3), pm(s["mu_data"], 3), pm(s["K_upper"], 2),
                         pm(s["mu_upper"], 2), pm(s["K_lower"], 2), pm(s["mu_lower"], 2),
                         pm(s["side"], 3)))
    return "\n".join(lines)


def seed_mean(group):
    """the seeds' mean wall table over the bins all have (the same z bins from the floor)"""
    n = min(len(run["wall"]["h"]) for run in group)
    return {key: np.mean([run["wall"][key][:n] for run in group], axis=0)
            for key in ("h", "sigma_w", "tau_w", "sigma_v")}


def figure(groups, path):
    radii = list(silo_runs.SILOS)
    fig, axes = plt.subplots(2, len(radii), figsize=(5 * len(radii), 7.5), squeeze=False)
    for col, radius in enumerate(radii):
        top, bottom = axes[0, col], axes[1, col]
        for (r, shape), colour in zip([k for k in groups if k[0] == radius], ("C0", "C1", "C2")):
            s, n = summary(groups[(r, shape)])
            for run in groups[(r, shape)]:
                w = run["wall"]
                top.plot(w["h"], w["sigma_w"], "o", ms=3, color=colour, alpha=0.6)
                top.plot(w["h"], w["tau_w"], "^", ms=3, mfc="none", color=colour, alpha=0.6)
                top.plot(w["h"], w["sigma_v"], ":", lw=0.8, color=colour)
            m = seed_mean(groups[(r, shape)])
            k, mob, _, _ = silo_wall.profile_ratios(m["sigma_w"], m["tau_w"], m["sigma_v"])
            bottom.plot(m["h"], k, "o-", ms=3, color=colour, label=LABELS[shape])
            bottom.plot(m["h"], mob, "^--", ms=3, mfc="none", color=colour)
            hh = np.linspace(0.0, max(run["H"] for run in groups[(r, shape)]), 100)
            top.plot(hh, silo_wall.janssen(hh, s["A"][0], s["lambda"][0]), "-", color=colour,
                     label="%s (%d seeds): K %.2f, $\\mu$ %.2f" % (LABELS[shape], n, s["K"][0],
                                                                   s["mu"][0]))
        top.set_title("R = %g d: wall stress (o normal, triangles shear), Janssen fit\n"
                      "(lines), the bulk's vertical stress (dotted); each seed" % radius,
                      fontsize=9)
        top.set_ylabel(r"stress / ($\rho g d$)")
        top.legend(fontsize=7)
        bottom.set_title(r"K = $\sigma_w / \sigma_v$ (o), $\mu_{mob} = \tau_w / \sigma_w$ "
                         r"(triangles) of the seeds' mean stresses", fontsize=9)
        bottom.legend(fontsize=7)
        bottom.set_ylim(0.0, 1.0)
        bottom.axhline(0.5, color="grey", lw=0.5, ls=":")
        for ax in (top, bottom):
            ax.set_xlabel("depth h / d below the fill height")
    fig.tight_layout()
    fig.savefig(path, dpi=130)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--table", action="store_true", help="print the README's table")
    p.add_argument("--figure", help="write the figure here (e.g. examples/silo/silo.png)")
    a = p.parse_args()
    groups = runs()
    if not groups:
        p.error("no finished runs in %s (run silo_runs.py first)" % silo_runs.RESULTS)
    for (radius, shape), group in groups.items():
        s, n = summary(group)
        print("R %g %s: %d seeds; " % (radius, LABELS[shape], n) +
              ", ".join("%s %s" % (k, pm(v, 4)) for k, v in s.items()), flush=True)
    if a.table:
        print(table(groups))
    if a.figure:
        figure(groups, a.figure)


if __name__ == "__main__":
    main()
