"""Fit Janssen's law to silo.dat files of run_silo.py and plot them.

    ./ellipsoid-dep python examples/silo/plot_silo.py --R 2.5 --mu_w 0.5 \
        --run "ellipsoids eta 1.4 zeta 1.8" DIR1 --run spheres DIR2 --figure silo.png

Janssen: sigma(H) = rho_b g lambda (1 - exp(-H / lambda)), lambda = R / (2 K mu_w), rho_b g
the bulk weight density (the weight over pi R^2 H at the last stage). Two fits (scipy's
curve_fit, standard errors from its covariance): Janssen's own, lambda alone with rho_b g
measured; and a free amplitude, sigma = A (1 - exp(-H / lambda)), whose A / (rho_b g lambda)
would be 1 if the data followed Janssen's form. K mu_w = R / (2 lambda) is the product the
floor's stress measures; K = R / (2 lambda mu_w) assumes the wall friction fully mobilised (a
lower bound otherwise). The rms residuals say how well each form fits.
"""
import argparse
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt    # noqa: E402
import numpy as np                 # noqa: E402
from scipy.optimize import curve_fit    # noqa: E402


def janssen(h, a, lam):
    return a * (1.0 - np.exp(-h / lam))


def fit(path, radius, mu_w):
    """path: a run folder (its silo.dat) or a silo.dat file"""
    path = os.path.join(path, "silo.dat") if os.path.isdir(path) else path
    if not os.path.isfile(path):
        sys.exit(f"plot_silo.py: no {path} (run run_silo.py --out DIR first)")
    data = np.loadtxt(path, ndmin=2)
    h, sigma, weight = data[:, 2], data[:, 3], data[:, 6]
    if len(h) < 3:
        sys.exit(f"plot_silo.py: {path} has {len(h)} stages; the fit needs 3")
    rho_g = weight[-1] / (math.pi * radius**2 * h[-1])
    (lam1,), cov1 = curve_fit(lambda x, lam: janssen(x, rho_g * lam, lam), h, sigma,
                              p0=(radius,))
    dlam1 = math.sqrt(cov1[0, 0])
    (a, lam), cov = curve_fit(janssen, h, sigma, p0=(rho_g * radius, radius))
    da, dlam = np.sqrt(np.diag(cov))
    k_mu = radius / (2.0 * lam1)
    return dict(h=h, sigma=sigma, rho_g=rho_g, lam1=lam1, dlam1=dlam1, k_mu=k_mu,
                dk_mu=k_mu * dlam1 / lam1, k=k_mu / mu_w, dk=k_mu / mu_w * dlam1 / lam1,
                rms1=np.sqrt(np.mean((janssen(h, rho_g * lam1, lam1) - sigma) ** 2)),
                a=a, da=da, lam=lam, dlam=dlam, k_mu_free=radius / (2.0 * lam),
                rms=np.sqrt(np.mean((janssen(h, a, lam) - sigma) ** 2)),
                check=a / (rho_g * lam), stages=len(h), side=data[-1, 5] / weight[-1])


SATURATED = 5    # the stages from this one on hold the saturated floor stress (H > 16 d)


def table(fits, radius):
    """the README's table (markdown rows) of fits {label: fit(...)}"""
    rows = [("bulk rho_b g / (rho g), last stage (= packing fraction)",
             lambda r: "%.3f" % r["rho_g"]),
            ("saturated floor stress sigma_inf (stages %d-%d, mean +- SD)",
             lambda r: "%.4f +- %.4f" % saturated(r)),
            ("K mu_w = rho_b g R / (2 sigma_inf)",
             lambda r: "%.3f" % (r["rho_g"] * radius / (2 * saturated(r)[0]))),
            ("weight carried by the side at H = %s d",
             lambda r: "%.0f %%" % (100 * r["side"])),
            ("Janssen fit (lambda alone): lambda, K mu_w, rms residual",
             lambda r: "%.1f +- %.1f d, %.3f, %.2f" % (r["lam1"], r["dlam1"], r["k_mu"],
                                                       r["rms1"])),
            ("free amplitude fit: lambda, A / (rho_b g lambda), rms",
             lambda r: "%.1f +- %.1f d, %.2f, %.2f" % (r["lam"], r["dlam"], r["check"],
                                                       r["rms"]))]
    first = next(iter(fits.values()))
    heights = "-".join("%.0f" % r["h"][-1] for r in fits.values())
    lines = ["| | " + " | ".join(fits) + " |", "|---" * (len(fits) + 1) + "|"]
    for label, value in rows:
        label = label % ((SATURATED, first["stages"]) if "stages" in label else
                         (heights,) if "%s" in label else ())
        lines.append("| %s | %s |" % (label, " | ".join(value(r) for r in fits.values())))
    return "\n".join(lines)


def saturated(r):
    """mean and sample SD of the floor stress over the saturated stages"""
    tail = r["sigma"][SATURATED - 1:]
    return float(np.mean(tail)), float(np.std(tail, ddof=1))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--R", type=float, required=True)
    p.add_argument("--mu_w", type=float, required=True)
    p.add_argument("--run", nargs=2, action="append", metavar=("LABEL", "DIR"), required=True)
    p.add_argument("--figure", required=True)
    p.add_argument("--table", action="store_true",
                   help="also print the README's table of the runs (markdown)")
    a = p.parse_args()
    if a.table:
        print(table({label: fit(path, a.R, a.mu_w) for label, path in a.run}, a.R))
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for (label, path), colour in zip(a.run, ("C0", "C1", "C2", "C3")):
        r = fit(path, a.R, a.mu_w)
        print(f"{label}: rho_b g {r['rho_g']:.4f}; Janssen: lambda {r['lam1']:.2f} +- "
              f"{r['dlam1']:.2f} d, K mu_w {r['k_mu']:.3f} +- {r['dk_mu']:.3f}, K (mu_w "
              f"{a.mu_w} mobilised) {r['k']:.2f} +- {r['dk']:.2f}, rms {r['rms1']:.3f}; free "
              f"amplitude: A {r['a']:.3f} +- {r['da']:.3f}, lambda {r['lam']:.2f} +- "
              f"{r['dlam']:.2f} d, K mu_w {r['k_mu_free']:.3f}, A / (rho_b g lambda) "
              f"{r['check']:.2f}, rms {r['rms']:.3f}")
        ax.plot(r["h"], r["sigma"], "o", color=colour, label=label)
        hh = np.linspace(0.0, r["h"].max() * 1.05, 200)
        ax.plot(hh, janssen(hh, r["rho_g"] * r["lam1"], r["lam1"]), "-", color=colour,
                label=f"Janssen, $\\lambda$ = {r['lam1']:.1f} d, K$\\mu_w$ = {r['k_mu']:.2f}")
        ax.plot(hh, janssen(hh, r["a"], r["lam"]), "--", color=colour, lw=1,
                label=f"free amplitude, $\\lambda$ = {r['lam']:.1f} d")
        ax.plot(hh, r["rho_g"] * hh, ":", color=colour, lw=1)
    ax.set_xlabel("fill height H / d")
    ax.set_ylabel(r"floor stress $\sigma_{zz}$ / ($\rho g d$)")
    ax.set_title(f"silo R = {a.R} d, wall friction {a.mu_w} (dotted: hydrostatic)", fontsize=9)
    ax.set_ylim(bottom=0.0)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(a.figure, dpi=150)


if __name__ == "__main__":
    main()
