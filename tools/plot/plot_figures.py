#!/usr/bin/env python3
"""Draw the paper's figures from a study's results folder (tools/study/study_table.py,
study_claims.py).

    ./ellipsoid-dep python tools/plot/plot_figures.py results/study/table.csv [--out DIR]
                                                 [--law NAME] [--N N]

Reads table.csv, the deposits of deposits.csv (their histograms and packing.dat), claims.json
(fitted maxima, crossing angles; optional) and a sizes file (sizes_*.csv, plot_sizes.py;
optional) in the table's folder. The figures use one law and one N (default: those with the
most points), except fig_density_laws.png, which compares the laws at that N. Every error bar
and error map is a standard error from the seed SD pooled per group of shapes
(tools/study/study_stats.py: spheroids, general shapes below and above a/c = 4, per delta_r
and law) / sqrt(the point's seeds); per bin for the histograms. Writes into DIR (default: the
table's folder) PNG files (the paper's figures numbered as in its LaTeX source, whose Fig. 2 is
the contact algorithm's flow chart):
  fig_sizes.png           V(r) and n(r) for several alpha, beta, a deposit's sizes     (Fig. 3)
  fig_density_map.png     phi over (eta, zeta), lowest delta_r, and its error map      (Fig. 5a)
  fig_density_lines.png   phi along eta = zeta, prolate and oblate; the same near the
                          maxima with the fits; eta = zeta for each delta_r             (Fig. 5b)
  fig_z_map.png           Z over (eta, zeta) and its error map                          (Fig. 6)
  fig_z_norattler_map.png the same without rattlers
  fig_contact_shapes.png  P(Omega(theta)) of contact normals for several shapes      (Fig. 7a)
  fig_contact_dr.png      the same for (1.6, 1.8) (else the shape with the most delta_r)
                          at each delta_r                                             (Fig. 7b)
  fig_orient_shapes.png   P(Omega(theta)) of the long axis a for several shapes        (Fig. 8)
  fig_density_laws.png    phi along eta = zeta at the lowest delta_r, one curve per law
  fig_forces.png          the contact forces along eta = zeta: anisotropies and K0 against
                          a/c, force by direction, P(f/<f>) (plot_forces.py)
A figure whose data are missing is skipped with a note.
"""
import argparse
import csv
import glob
import json
import math
import os
import sys
from collections import Counter

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _paths  # noqa: E402,F401  (tools/_paths.py: the topic folders on sys.path)
from plot_forces import figure as forces_figure  # noqa: E402
from plot_maps import groups_text, map_figure  # noqa: E402
from plot_sizes import figure as sizes_figure  # noqa: E402
from study_claims import Selection, load_deposits  # noqa: E402
from study_histograms import FIGURE_SHAPES, ISOTROPIC, binned  # noqa: E402

PI_TICKS = ([0, math.pi / 5, math.pi / 4, math.pi / 3, math.pi / 2, 3 * math.pi / 4, math.pi],
            ["0", r"$\frac{\pi}{5}$", r"$\frac{\pi}{4}$", r"$\frac{\pi}{3}$", r"$\frac{\pi}{2}$",
             r"$\frac{3\pi}{4}$", r"$\pi$"])
LINES = (("eta = zeta (vs eta)", lambda e, z: e == z, 0, "o-"),
         ("prolate, zeta = 1 (vs eta)", lambda e, z: z == 1.0, 0, "s--"),
         ("oblate, eta = 1 (vs zeta)", lambda e, z: e == 1.0, 1, "^-."))
FIG6B = (1.6, 1.8)    # the paper's shape of Fig. 7b (its LaTeX's numbers, as above)


def load(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("eta", "zeta", "delta_r"):
            r[k] = float(r[k])
        r["N"] = int(r["N"])
    return rows


def most_common(rows, key):
    counts = Counter(r[key] for r in rows)
    return max(counts, key=lambda v: (counts[v], str(v)))


def save(fig, out, fname):
    fig.tight_layout()
    p = os.path.join(out, fname)
    fig.savefig(p, dpi=100)
    plt.close(fig)
    return p


def draw_line(ax, pooled, on_line, axis, style, label, color=None):
    """a line's means with their pooled standard errors; returns the points [(x, shape)]"""
    points = sorted((s[axis], s) for s in pooled.values if on_line(*s) or s == (1.0, 1.0))
    if len(points) < 2:
        return []
    err = [pooled.se(s) or 0.0 for _, s in points]
    ax.errorbar([x for x, _ in points], [pooled.mean(s) for _, s in points], yerr=err,
                fmt=style, ms=4, capsize=3, elinewidth=1.2, label=label, color=color)
    return points


def draw_fit(ax, pooled, points, m, color):
    """the nominal parabola of a claims.json maximum over its window, and the maximum with
    its errors (bootstrap and fit window in quadrature)"""
    lo, hi = m["window"]
    win = [(x, s) for x, s in points if lo <= x <= hi]
    c = np.polyfit([x for x, _ in win], [pooled.mean(s) for _, s in win], 2)
    xs = np.linspace(lo, hi, 60)
    ax.plot(xs, np.polyval(c, xs), "-", lw=0.8, color=color, alpha=0.7)
    ax.errorbar([m["x_max"]], [m["phi_max"]],
                xerr=[math.hypot(m.get("x_max_sd") or 0, m["x_max_sys"])],
                yerr=[math.hypot(m.get("phi_max_sd") or 0, m["phi_max_sys"])], fmt="D", ms=5,
                color=color, mfc="w", capsize=3)


def density_lines(sels, law, dr0, claims, out):
    fig, axs = plt.subplots(1, 3, figsize=(15, 4.6))
    pooled = sels[(dr0, law)].pooled
    colors = ("C0", "C1", "C2")
    for (label, on_line, axis, style), color, name in zip(LINES, colors, ("diagonal", "prolate",
                                                                         "oblate")):
        draw_line(axs[0], pooled, on_line, axis, style, label, color)
        points = draw_line(axs[1], pooled, on_line, axis, style, label, color)
        m = (claims or {}).get("maxima", {}).get(name)
        if points and m and "x_max" in m:
            draw_fit(axs[1], pooled, points, m, color)
    axs[1].set_xlim(0.95, 2.25)
    axs[1].set_ylim(0.615, 0.645)
    axs[1].set_title("near the maxima: 5-point parabolas, maxima (diamonds) with bootstrap\n"
                     "and fit-window errors", fontsize=8)
    axs[0].set_title(r"$\delta_r$ = %g, %s; error bars: pooled seed SD / sqrt(seeds)"
                     % (dr0, law), fontsize=8)
    axs[0].text(0.03, 0.03, groups_text(pooled, "%.3f", "\n"), transform=axs[0].transAxes,
                fontsize=6.5, va="bottom")
    for dr in sorted(d for d, name in sels if name == law):
        draw_line(axs[2], sels[(dr, law)].pooled, LINES[0][1], 0, "o-", r"$\delta_r$ = %g" % dr)
    axs[2].set_title("eta = zeta for each size polydispersity (%s)" % law, fontsize=8)
    for ax in axs:
        ax.set_xlabel(r"$\eta$ or $\zeta$ (the parameter that varies)" if ax is not axs[2]
                      else r"$\eta = \zeta$")
        ax.set_ylabel(r"volume fraction $\phi$")
        ax.legend(fontsize=7)
    return save(fig, out, "fig_density_lines.png")


def density_laws(sels, dr0, out):
    fname = "fig_density_laws.png"
    laws = sorted({name for d, name in sels if d == dr0})
    if len(laws) < 2:
        print("  %s: skipped (one tangential law)" % fname)
        return None
    fig, ax = plt.subplots(figsize=(5.6, 4.0))
    for law in laws:
        draw_line(ax, sels[(dr0, law)].pooled, LINES[0][1], 0, "o-", law)
    ax.set_xlabel(r"$\eta = \zeta$")
    ax.set_ylabel(r"volume fraction $\phi$")
    ax.set_title(r"eta = zeta for each tangential law, $\delta_r$ = %g (pooled errors)" % dr0,
                 fontsize=8)
    ax.legend(fontsize=8)
    return save(fig, out, fname)


def histo_figure(curves, path, title, xlabel, marks=()):
    """curves: [(theta, P, its standard error, label)]; marks: [(angle, label, style)]"""
    fig, ax = plt.subplots(figsize=(6.6, 5.8))
    for theta, p, err, label in curves:
        ax.errorbar(theta, p, yerr=np.nan_to_num(err), fmt="o-", ms=3, capsize=2,
                    elinewidth=1, label=label)
    ax.axhline(ISOTROPIC, color="gray", ls=":", lw=1, label=r"isotropic $1/4\pi$")
    for angle, label, style in marks:
        ax.axvline(angle, color="k", ls=style, lw=0.8, label=label)
    ax.set_xticks(*PI_TICKS)
    ax.set_xlim(0, math.pi)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"$P(\Omega(\theta))$")
    ax.set_title(title, fontsize=8)
    ax.legend(fontsize=7, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.14))
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def crossing_marks(claims, histogram):
    """vertical lines: the paper's angle, and the medians of the two readings"""
    c = (claims or {}).get("verdicts", {}).get("crossings", {}).get(histogram)
    if not c:
        return []
    marks = [(c["paper"], "the paper's angle", "-")]
    if "median" in c["each_other"]:
        marks.append((c["each_other"]["median"], "curves cross each other (median of %d pairs)"
                      % c["each_other"]["pairs"], "--"))
    if c["isotropic_level"].get("shapes"):
        marks.append((c["isotropic_level"]["median"], "curves cross 1/4pi (median of %d shapes)"
                      % len(c["isotropic_level"]["shapes"]), "-."))
    return marks


def shape_figures(sels, law, dr0, claims, out, tag):
    written = []
    sel = sels[(dr0, law)]
    for histogram, fname, what, title in (
            ("contact_normals", "fig_contact_shapes.png", "contact normal", "contact normals"),
            ("long_axes", "fig_orient_shapes.png", "long axis a", "long axes a")):
        curves = binned(sel.shapes, histogram)
        shown = [s for s in FIGURE_SHAPES if s in curves]
        if not shown:
            print("  %s: skipped (no data)" % fname)
            continue
        written.append(histo_figure(
            [curves[s] + (r"$\eta$=%g $\zeta$=%g (%d seeds)" % (s[0], s[1], len(sel.phi[s])),)
             for s in shown], os.path.join(out, fname),
            r"%s, $\delta_r$ = %g, %s; error bars: pooled seed SD per bin" % (title, dr0, tag),
            r"$\theta$ (%s vs +z)" % what, crossing_marks(claims, histogram)))
    by_shape = Counter(s for (d, name), v in sels.items() if name == law for s in v.shapes)
    shape = FIG6B if by_shape.get(FIG6B, 0) >= 2 else max(by_shape, key=lambda s: (by_shape[s],
                                                                                    s))
    if shape != FIG6B:
        print("  fig_contact_dr.png: (1.6, 1.8) lacks several delta_r; shows %s" % (shape,))
    drs = sorted(d for (d, name), v in sels.items() if name == law and shape in v.shapes)
    if len(drs) >= 2:
        curves = [binned(sels[(d, law)].shapes, "contact_normals")[shape]
                  + (r"$\delta_r$ = %g (%d seeds)" % (d, len(sels[(d, law)].phi[shape])),)
                  for d in drs]
        written.append(histo_figure(
            curves, os.path.join(out, "fig_contact_dr.png"),
            r"contact normals, $\eta$=%g $\zeta$=%g, %s; error bars: pooled seed SD per bin"
            % (shape[0], shape[1], tag), r"$\theta$ (contact normal vs +z)"))
    return written


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
    results = os.path.dirname(os.path.abspath(args.table))
    groups = {}
    for d in load_deposits(results, n):
        groups.setdefault((float(d["delta_r"]), d["law"]), []).append(d)
    sels = {k: Selection(v) for k, v in sorted(groups.items())}
    if not any(name == law for _, name in sels):
        sys.exit("plot_figures: no deposit with law %s and N %d in %s" % (law, n, results))
    out = os.path.abspath(args.out or results)
    os.makedirs(out, exist_ok=True)
    claims_path = os.path.join(results, "claims.json")
    claims = json.load(open(claims_path)) if os.path.exists(claims_path) else None
    dr0 = min(d for d, name in sels if name == law)
    tag = "N %d, %s" % (n, law)
    base = sels[(dr0, law)]
    written = []
    for q, fname, label, fmt in (("phi", "fig_density_map.png", r"$\phi$", "%.3f"),
                                 ("Z", "fig_z_map.png", "Z", "%.2f"),
                                 ("Z_no_rattlers", "fig_z_norattler_map.png",
                                  "Z without rattlers", "%.2f")):
        if base.has(q):
            written.append(map_figure(base.quantity(q), os.path.join(out, fname), label,
                                      r"%s, $\delta_r$ = %g, %s" % (label, dr0, tag), fmt))
    written.append(density_lines(sels, law, dr0, claims, out))
    written += shape_figures(sels, law, dr0, claims, out, tag)
    written.append(density_laws(sels, dr0, out))
    written.append(forces_figure(claims, base.deposits, os.path.join(out, "fig_forces.png"), tag))
    for sizes in sorted(glob.glob(os.path.join(results, "sizes_*.csv")))[:1]:
        written.append(sizes_figure(sizes, os.path.join(out, "fig_sizes.png"))[0])
    written = [w for w in written if w]
    print("plot_figures: wrote\n  " + "\n  ".join(written))
    return written


if __name__ == "__main__":
    main()
