#!/usr/bin/env python3
"""Draw the paper's figures from a study's results table (tools/study_table.py).

    ./ellipsoid-dep python tools/plot_figures.py results/study/table.csv [--out DIR]
                                                 [--law NAME] [--N N]

The table holds one row per point (eta, zeta, delta_r, N, tangential law) with the mean and
standard error over seeds of every quantity and the files of its seed-mean histograms.
The figures use one law and one N (default: those with the most points), except
fig_density_laws.png, which compares the laws at that N. Writes into DIR (default: the
table's folder) PNG files:
  fig_density_map.png     phi over (eta, zeta), lowest delta_r                         (Fig. 4a)
  fig_density_lines.png   phi along eta = zeta, prolate (zeta = 1, vs eta) and oblate
                          (eta = 1, vs zeta); right panel: eta = zeta for each delta_r (Fig. 4b)
  fig_z_map.png           Z over (eta, zeta) (and the rattler-free Z)                   (Fig. 5)
  fig_contact_shapes.png  P(Omega(theta)) of contact normals for several shapes     (Fig. 6a)
  fig_contact_dr.png      the same for one shape and several delta_r                 (Fig. 6b)
  fig_orient_shapes.png   P(Omega(theta)) of the long axis a for several shapes       (Fig. 7)
  fig_density_laws.png    phi along eta = zeta at the lowest delta_r, one curve per
                          tangential law (only when the table holds more than one)
Error bars are standard errors over seeds (none for a single seed). A figure whose data are
missing (e.g. a single delta_r) is skipped with a note.
"""
import argparse
import csv
import math
import os
import sys
from collections import Counter

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PI_TICKS = ([0, math.pi / 4, math.pi / 2, 3 * math.pi / 4, math.pi],
            ["0", r"$\pi/4$", r"$\pi/2$", r"$3\pi/4$", r"$\pi$"])


def load(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k, v in r.items():
            if k.endswith("_mean") or k.endswith("_sem") or k in ("eta", "zeta", "delta_r"):
                r[k] = float(v)
        r["N"] = int(r["N"])
        r["seeds"] = int(r["seeds"])
    return rows


def most_common(rows, key):
    counts = Counter(r[key] for r in rows)
    return max(counts, key=lambda v: (counts[v], str(v)))


def err(r, q):
    """standard error of quantity q of a point, 0 when unknown (one seed)"""
    e = r[q + "_sem"]
    return 0.0 if math.isnan(e) else e


def save(fig, out, fname):
    fig.tight_layout()
    p = os.path.join(out, fname)
    fig.savefig(p, dpi=130)
    plt.close(fig)
    return p


def diagonal_curve(ax, rows, label):
    """phi with its error bars along eta = zeta of rows (one delta_r, one law)"""
    line = sorted((r for r in rows if r["eta"] == r["zeta"]), key=lambda r: r["eta"])
    if line:
        ax.errorbar([r["eta"] for r in line], [r["phi_mean"] for r in line],
                    yerr=[err(r, "phi") for r in line], fmt="o-", capsize=2, label=label)


def shape_map(rows, dr, value, out, fname, label, title):
    sel = [r for r in rows if r["delta_r"] == dr]
    etas = sorted({r["eta"] for r in sel})
    zetas = sorted({r["zeta"] for r in sel})
    if len(etas) < 2 or len(zetas) < 2:
        print("  %s: skipped (needs >= 2 values of eta and of zeta at delta_r %g)" % (fname, dr))
        return None
    grid = np.full((len(zetas), len(etas)), np.nan)
    for r in sel:
        grid[zetas.index(r["zeta"]), etas.index(r["eta"])] = r[value + "_mean"]
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
    return save(fig, out, fname)


def density_lines(rows, out, dr0):
    fig, axs = plt.subplots(1, 2, figsize=(9.5, 3.8))
    sel = [r for r in rows if r["delta_r"] == dr0]
    lines = [("eta = zeta (vs eta)", lambda r: r["eta"] == r["zeta"], "eta", "o-"),
             ("prolate, zeta = 1 (vs eta)", lambda r: r["zeta"] == 1.0, "eta", "s--"),
             ("oblate, eta = 1 (vs zeta)", lambda r: r["eta"] == 1.0, "zeta", "^-.")]
    drawn = 0
    for lab, cond, xkey, style in lines:
        line = sorted((r for r in sel if cond(r)), key=lambda r: r[xkey])
        if len(line) < 2:
            continue
        axs[0].errorbar([r[xkey] for r in line], [r["phi_mean"] for r in line],
                        yerr=[err(r, "phi") for r in line], fmt=style, capsize=2, label=lab)
        drawn += 1
    axs[0].set_xlabel(r"$\eta$ or $\zeta$ (the parameter that varies)")
    axs[0].set_ylabel(r"volume fraction $\phi$")
    axs[0].set_title(r"$\delta_r$ = %g" % dr0, fontsize=9)
    if drawn:
        axs[0].legend(fontsize=8)
    for dr in sorted({r["delta_r"] for r in rows}):
        diagonal_curve(axs[1], [r for r in rows if r["delta_r"] == dr], r"$\delta_r$ = %g" % dr)
    axs[1].set_xlabel(r"$\eta = \zeta$")
    axs[1].set_ylabel(r"$\phi$")
    axs[1].set_title("eta = zeta for each size polydispersity", fontsize=9)
    axs[1].legend(fontsize=8)
    return save(fig, out, "fig_density_lines.png")


def density_laws(rows, out):
    """phi along eta = zeta at the lowest delta_r of rows (one N), one curve per law"""
    fname = "fig_density_laws.png"
    laws = sorted({r["law"] for r in rows})
    if len(laws) < 2:
        print("  %s: skipped (one tangential law)" % fname)
        return None
    dr = min(r["delta_r"] for r in rows)
    fig, ax = plt.subplots(figsize=(5.2, 3.8))
    for law in laws:
        diagonal_curve(ax, [r for r in rows if r["law"] == law and r["delta_r"] == dr], law)
    ax.set_xlabel(r"$\eta = \zeta$")
    ax.set_ylabel(r"volume fraction $\phi$")
    ax.set_title(r"eta = zeta for each tangential law, $\delta_r$ = %g, N %d"
                 % (dr, rows[0]["N"]), fontsize=9)
    ax.legend(fontsize=8)
    return save(fig, out, fname)


def read_mean_histo(path):
    """theta, P mean, P standard error (study_table.py's seed-mean histogram)"""
    a = np.loadtxt(path, ndmin=2)
    return a[:, 0], a[:, 1], np.nan_to_num(a[:, 2])


def histo_figure(table_dir, points, col, out, fname, title, xlabel, labeller, max_lines=6):
    if not points:
        print("  %s: skipped (no data)" % fname)
        return None
    if len(points) > max_lines:    # keep a readable spread
        idx = np.unique(np.linspace(0, len(points) - 1, max_lines).round().astype(int))
        points = [points[i] for i in idx]
    fig, ax = plt.subplots(figsize=(5.4, 3.9))
    for r in points:
        th, p, e = read_mean_histo(os.path.join(table_dir, r[col]))
        ax.errorbar(th, p, yerr=e, fmt="o-", ms=3, capsize=2,
                    label=labeller(r) + (" (%d seeds)" % r["seeds"] if r["seeds"] > 1 else ""))
    ax.axhline(1 / (4 * math.pi), color="gray", ls=":", lw=1, label=r"isotropic $1/4\pi$")
    ax.set_xticks(*PI_TICKS)
    ax.set_xlim(0, math.pi)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"$P(\Omega(\theta))$")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7)
    return save(fig, out, fname)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("table")
    ap.add_argument("--out", default=None)
    ap.add_argument("--law", default=None, help="tangential law (default: the most points)")
    ap.add_argument("--N", type=int, default=None, help="particles (default: the most points)")
    args = ap.parse_args(argv)
    rows = load(args.table)
    if not rows:
        sys.exit("plot_figures: %s has no rows" % args.table)
    law = args.law or most_common(rows, "law")
    n = args.N or most_common([r for r in rows if r["law"] == law], "N")
    all_laws = [r for r in rows if r["N"] == n]
    rows = [r for r in all_laws if r["law"] == law]
    if not rows:
        sys.exit("plot_figures: no point with law %s and N %d in %s" % (law, n, args.table))
    table_dir = os.path.dirname(os.path.abspath(args.table))
    out = os.path.abspath(args.out or table_dir)
    os.makedirs(out, exist_ok=True)
    dr0 = min(r["delta_r"] for r in rows)
    tag = "N %d, %s" % (n, law)
    written = [
        shape_map(rows, dr0, "phi", out, "fig_density_map.png", r"$\phi$",
                  r"volume fraction, $\delta_r$ = %g, %s" % (dr0, tag)),
        density_lines(rows, out, dr0),
        shape_map(rows, dr0, "Z", out, "fig_z_map.png", r"$Z$",
                  r"coordination number, $\delta_r$ = %g, %s" % (dr0, tag)),
        shape_map(rows, dr0, "Z_no_rattlers", out, "fig_z_norattler_map.png", r"$Z$",
                  r"Z without rattlers, $\delta_r$ = %g, %s" % (dr0, tag)),
    ]
    shapes = sorted((r for r in rows if r["delta_r"] == dr0),
                    key=lambda r: (r["eta"] * r["zeta"], r["eta"], r["zeta"]))
    shape_label = lambda r: r"$\eta$=%g $\zeta$=%g" % (r["eta"], r["zeta"])  # noqa: E731
    written.append(histo_figure(table_dir, shapes, "contact_histo", out, "fig_contact_shapes.png",
                                r"contact normals, $\delta_r$ = %g, %s" % (dr0, tag),
                                r"$\theta$ (contact normal vs +z)", shape_label))
    # the shape with the most delta_r values
    by_shape = {}
    for r in rows:
        by_shape.setdefault((r["eta"], r["zeta"]), []).append(r)
    best = max(by_shape, key=lambda k: (len(by_shape[k]), k[0] * k[1]))
    if len(by_shape[best]) >= 2:
        written.append(histo_figure(table_dir, sorted(by_shape[best], key=lambda r: r["delta_r"]),
                                    "contact_histo", out, "fig_contact_dr.png",
                                    r"contact normals, $\eta$=%g $\zeta$=%g, %s" % (best + (tag,)),
                                    r"$\theta$ (contact normal vs +z)",
                                    lambda r: r"$\delta_r$=%g" % r["delta_r"]))
    else:
        print("  fig_contact_dr.png: skipped (no shape with >= 2 values of delta_r)")
    written.append(histo_figure(table_dir, shapes, "orient_histo", out, "fig_orient_shapes.png",
                                r"long axis $a$, $\delta_r$ = %g, %s" % (dr0, tag),
                                r"$\theta$ (long axis vs +z)", shape_label))
    written.append(density_laws(all_laws, out))
    written = [w for w in written if w]
    print("plot_figures: wrote\n  " + "\n  ".join(written))
    return written


if __name__ == "__main__":
    main()
