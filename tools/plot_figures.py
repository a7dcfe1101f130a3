#!/usr/bin/env python3
"""Draw the paper's figures from a sweep's results.csv (tools/sweep.py).

    ./ellipsoid-dep python tools/plot_figures.py runs/sweep/results.csv [--out DIR]

Writes into DIR (default: the CSV's folder) PNG files:
  fig_density_map.png     phi over (eta, zeta), lowest delta_r, mean over seeds   (paper Fig. 4a)
  fig_density_lines.png   phi along eta = zeta, prolate (zeta = 1, vs eta) and oblate
                          (eta = 1, vs zeta); right panel: eta = zeta for each delta_r (Fig. 4b)
  fig_z_map.png           Z over (eta, zeta) (and the rattler-free Z)                   (Fig. 5)
  fig_contact_shapes.png  P(Omega(theta)) of contact normals for several shapes     (Fig. 6a)
  fig_contact_dr.png      the same for one shape and several delta_r                 (Fig. 6b)
  fig_orient_shapes.png   P(Omega(theta)) of the long axis a for several shapes       (Fig. 7)
Points with several seeds are averaged; error bars are the standard error over seeds.
A figure whose data are missing (e.g. a single delta_r) is skipped with a note.
"""
import argparse
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from deposit_run import read_histo  # noqa: E402

PI_TICKS = ([0, math.pi / 4, math.pi / 2, 3 * math.pi / 4, math.pi],
            ["0", r"$\pi/4$", r"$\pi/2$", r"$3\pi/4$", r"$\pi$"])


def load(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("eta", "zeta", "delta_r", "phi", "Z", "Z_no_rattlers", "run_seconds"):
            r[k] = float(r[k])
        r["N"] = int(r["N"])
        r["seed"] = int(r["seed"])
    return rows


def grouped(rows, key):
    g = defaultdict(list)
    for r in rows:
        g[tuple(r[k] for k in key)].append(r)
    return g


def mean_err(vals):
    a = np.asarray(vals, float)
    return a.mean(), (a.std(ddof=1) / math.sqrt(len(a)) if len(a) > 1 else 0.0)


def shape_map(rows, dr, value, out, fname, label, title):
    sel = [r for r in rows if r["delta_r"] == dr]
    etas = sorted({r["eta"] for r in sel})
    zetas = sorted({r["zeta"] for r in sel})
    if len(etas) < 2 or len(zetas) < 2:
        print("  %s: skipped (needs >= 2 values of eta and of zeta at delta_r %g)" % (fname, dr))
        return None
    grid = np.full((len(zetas), len(etas)), np.nan)
    for (eta, zeta), rs in grouped(sel, ("eta", "zeta")).items():
        grid[zetas.index(zeta), etas.index(eta)] = mean_err([r[value] for r in rs])[0]
    fig, ax = plt.subplots(figsize=(5.2, 4.3))

    def edges(v):
        v = np.asarray(v, float)
        mid = (v[1:] + v[:-1]) / 2
        return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])

    m = ax.pcolormesh(edges(etas), edges(zetas), np.ma.masked_invalid(grid), shading="flat",
                      cmap="viridis")
    for i, z in enumerate(zetas):
        for j, e in enumerate(etas):
            if not np.isnan(grid[i, j]):
                ax.text(e, z, ("%.3f" if value == "phi" else "%.2f") % grid[i, j], ha="center",
                        va="center", fontsize=7, color="w")
    lo = max(min(etas), min(zetas))
    hi = min(max(etas), max(zetas))
    ax.plot([lo, hi], [lo, hi], "w--", lw=0.8)
    fig.colorbar(m, ax=ax, label=label)
    ax.set_xlabel(r"$\eta = a/b$")
    ax.set_ylabel(r"$\zeta = b/c$")
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    p = os.path.join(out, fname)
    fig.savefig(p, dpi=130)
    plt.close(fig)
    return p


def density_lines(rows, out, dr0):
    fig, axs = plt.subplots(1, 2, figsize=(9.5, 3.8))
    sel = [r for r in rows if r["delta_r"] == dr0]
    lines = [("eta = zeta (vs eta)", lambda r: r["eta"] == r["zeta"], "eta", "o-"),
             ("prolate, zeta = 1 (vs eta)", lambda r: r["zeta"] == 1.0, "eta", "s--"),
             ("oblate, eta = 1 (vs zeta)", lambda r: r["eta"] == 1.0, "zeta", "^-.")]
    drawn = 0
    for lab, cond, xkey, style in lines:
        g = grouped([r for r in sel if cond(r)], (xkey,))
        if len(g) < 2:
            continue
        xs = sorted(g)
        m = [mean_err([r["phi"] for r in g[x]]) for x in xs]
        axs[0].errorbar([x[0] for x in xs], [v[0] for v in m], yerr=[v[1] for v in m], fmt=style,
                        capsize=2, label=lab)
        drawn += 1
    axs[0].set_xlabel(r"$\eta$ or $\zeta$ (the parameter that varies)")
    axs[0].set_ylabel(r"volume fraction $\phi$")
    axs[0].set_title(r"$\delta_r$ = %g" % dr0, fontsize=9)
    if drawn:
        axs[0].legend(fontsize=8)
    drs = sorted({r["delta_r"] for r in rows})
    for dr in drs:
        g = grouped([r for r in rows if r["delta_r"] == dr and r["eta"] == r["zeta"]], ("eta",))
        if len(g) < 1:
            continue
        xs = sorted(g)
        m = [mean_err([r["phi"] for r in g[x]]) for x in xs]
        axs[1].errorbar([x[0] for x in xs], [v[0] for v in m], yerr=[v[1] for v in m], fmt="o-",
                        capsize=2, label=r"$\delta_r$ = %g" % dr)
    axs[1].set_xlabel(r"$\eta = \zeta$")
    axs[1].set_ylabel(r"$\phi$")
    axs[1].set_title("eta = zeta for each size polydispersity", fontsize=9)
    axs[1].legend(fontsize=8)
    fig.tight_layout()
    p = os.path.join(out, "fig_density_lines.png")
    fig.savefig(p, dpi=130)
    plt.close(fig)
    return p


def mean_histo(csv_dir, rs, col):
    ps = []
    th = None
    for r in rs:
        th, p, _ = read_histo(os.path.join(csv_dir, r[col]))
        ps.append(p)
    return np.asarray(th), np.mean(ps, axis=0)


def histo_figure(rows, csv_dir, groups, col, out, fname, title, xlabel, labeller, max_lines=6):
    if not groups:
        print("  %s: skipped (no data)" % fname)
        return None
    if len(groups) > max_lines:    # keep a readable spread
        idx = np.unique(np.linspace(0, len(groups) - 1, max_lines).round().astype(int))
        groups = [groups[i] for i in idx]
    fig, ax = plt.subplots(figsize=(5.4, 3.9))
    for key, rs in groups:
        th, p = mean_histo(csv_dir, rs, col)
        ax.plot(th, p, "o-", ms=3, label=labeller(key) + (" (%d seeds)" % len(rs)
                                                          if len(rs) > 1 else ""))
    ax.axhline(1 / (4 * math.pi), color="gray", ls=":", lw=1, label=r"isotropic $1/4\pi$")
    ax.set_xticks(*PI_TICKS)
    ax.set_xlim(0, math.pi)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"$P(\Omega(\theta))$")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    p = os.path.join(out, fname)
    fig.savefig(p, dpi=130)
    plt.close(fig)
    return p


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("--out", default=None)
    args = ap.parse_args(argv)
    rows = load(args.csv)
    if not rows:
        sys.exit("plot_figures: %s has no rows" % args.csv)
    csv_dir = os.path.dirname(os.path.abspath(args.csv))
    out = os.path.abspath(args.out or csv_dir)
    os.makedirs(out, exist_ok=True)
    drs = sorted({r["delta_r"] for r in rows})
    dr0 = drs[0]
    ns = sorted({r["N"] for r in rows})
    tag = "N %s" % "/".join(str(n) for n in ns)
    written = [
        shape_map(rows, dr0, "phi", out, "fig_density_map.png", r"$\phi$",
                  r"volume fraction, $\delta_r$ = %g, %s" % (dr0, tag)),
        density_lines(rows, out, dr0),
        shape_map(rows, dr0, "Z", out, "fig_z_map.png", r"$Z$",
                  r"coordination number, $\delta_r$ = %g, %s" % (dr0, tag)),
        shape_map(rows, dr0, "Z_no_rattlers", out, "fig_z_norattler_map.png", r"$Z$",
                  r"Z without rattlers, $\delta_r$ = %g, %s" % (dr0, tag)),
    ]
    shape_groups = sorted(grouped([r for r in rows if r["delta_r"] == dr0],
                                  ("eta", "zeta")).items(),
                          key=lambda kv: (kv[0][0] * kv[0][1], kv[0]))
    shape_label = lambda k: r"$\eta$=%g $\zeta$=%g" % k  # noqa: E731
    written.append(histo_figure(rows, csv_dir, shape_groups, "contact_histo", out,
                                "fig_contact_shapes.png",
                                r"contact normals, $\delta_r$ = %g, %s" % (dr0, tag),
                                r"$\theta$ (contact normal vs +z)", shape_label))
    # the shape with the most delta_r values
    by_shape = grouped(rows, ("eta", "zeta"))
    best = max(by_shape, key=lambda k: (len({r["delta_r"] for r in by_shape[k]}), k[0] * k[1]))
    dr_groups = sorted(grouped(by_shape[best], ("delta_r",)).items())
    if len(dr_groups) >= 2:
        written.append(histo_figure(rows, csv_dir, dr_groups, "contact_histo", out,
                                    "fig_contact_dr.png",
                                    r"contact normals, $\eta$=%g $\zeta$=%g, %s" % (best + (tag,)),
                                    r"$\theta$ (contact normal vs +z)",
                                    lambda k: r"$\delta_r$=%g" % k))
    else:
        print("  fig_contact_dr.png: skipped (no shape with >= 2 values of delta_r)")
    written.append(histo_figure(rows, csv_dir, shape_groups, "orient_histo", out,
                                "fig_orient_shapes.png",
                                r"long axis $a$, $\delta_r$ = %g, %s" % (dr0, tag),
                                r"$\theta$ (long axis vs +z)", shape_label))
    written = [w for w in written if w]
    print("plot_figures: wrote\n  " + "\n  ".join(written))
    return written


if __name__ == "__main__":
    main()
