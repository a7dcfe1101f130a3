"""fig_forces.png of the study (tools/plot/plot_figures.py): the contact forces along eta = zeta.

(a) a_n, a_f and a_n + a_f against a/c with their pooled standard errors (claims.json
`forces`, tools/study/study_forces.py), and a_n + a_f along the spheroid lines where they have the
force measures; (b) K0 against a/c on each line; (c) the mean normal force in each direction
over the mean force, fbar(theta) / <f> (compute contact/histo weight force, column 4 over the
mean force); (d) P(f / <f>) of the normal forces (compute force/histo), on a log scale. (c) and
(d) per shape over the deposits with window means (packing.dat's window_steps > 0; their
histograms are those of the window's last step), with the seed SD pooled over the shapes per
bin / sqrt(seeds).
"""
import math
import os

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from deposit_run import read_histo, read_packing  # noqa: E402
from study_forces import NAMES  # noqa: E402
from study_stats import Pooled  # noqa: E402

FILES = {"direction": "contact_force_histo.dat", "magnitude": "force_histo.dat"}


def curves(deposits):
    """{shape: {kind: (x, [y per deposit])}} over the diagonal deposits with both files:
    direction -> fbar(theta) / <f>, magnitude -> P(f / <f>)"""
    out = {}
    for d in deposits:
        e, z = float(d["eta"]), float(d["zeta"])
        paths = {k: os.path.join(d["folder"], f) for k, f in FILES.items()}
        if e != z or not all(os.path.exists(p) for p in paths.values()):
            continue
        pk = read_packing(os.path.join(d["folder"], "packing.dat"))
        if not pk.get("window_steps", 0) > 0:    # a snapshot of a ringing bed
            continue
        mean_force = pk["mean_normal_force"]
        cols = read_histo(paths["direction"], columns=4)
        theta, fbar = np.asarray(cols[0]), np.asarray(cols[3]) / mean_force
        f, p = read_histo(paths["magnitude"], columns=2)
        entry = out.setdefault((e, z), {"direction": (theta, []), "magnitude": (np.asarray(f),
                                                                                 [])})
        entry["direction"][1].append(fbar)
        entry["magnitude"][1].append(np.asarray(p))
    return out


def mean_and_error(per_shape, kind):
    """{shape: (x, mean, pooled per-bin standard error)} of shapes with two deposits or more"""
    shapes = {s: c[kind] for s, c in per_shape.items() if len(c[kind][1]) >= 2}
    if not shapes:
        return {}
    x = next(iter(shapes.values()))[0]
    ys = {s: np.asarray(v[1]) for s, v in shapes.items()}
    err = {s: np.zeros(len(x)) for s in ys}
    for k in range(len(x)):
        pooled = Pooled({s: y[:, k] for s, y in ys.items()})
        for s in ys:
            se = pooled.se(s)
            err[s][k] = se if se is not None else np.nan
    return {s: (x, y.mean(axis=0), err[s]) for s, y in ys.items()}


AC_TICKS = [1, 1.5, 2, 3, 4, 6, 9, 16]
LINE_STYLES = {"diagonal": "o-", "prolate": "v--", "oblate": "<:"}


def ac_axis(ax):
    """a/c on a log scale with plain numbers at readable steps"""
    ax.set_xscale("log")
    ax.set_xticks(AC_TICKS)
    ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: "%g" % v))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("total aspect ratio a/c = eta zeta")
    ax.grid(alpha=0.3)


def errorbars(ax, rows, q, style, label, color=None):
    ax.errorbar([r["a/c"] for r in rows], [r[q]["mean"] for r in rows],
                yerr=[r[q]["se"] or 0 for r in rows], fmt=style, ms=5, capsize=3, label=label,
                color=color)


def figure(claims, deposits, path, tag):
    """the figure, or None (with a note) without the force measures"""
    lines = (claims or {}).get("forces") or {}
    forces = lines.get("diagonal")
    per_shape = curves(deposits)
    if forces is None or not per_shape:
        print("  %s: skipped (no deposit with window means of the force measures)"
              % os.path.basename(path))
        return None
    plt.rcParams.update({"font.size": 11})
    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    (a, k0), (direction, magnitude) = axes
    for q, style in zip(("a_n", "a_f", "a_total"), ("o-", "s-", "^-")):
        errorbars(a, forces["per_shape"], q, style, NAMES[q] + ", eta = zeta")
    for line in ("prolate", "oblate"):
        if line in lines:
            errorbars(a, lines[line]["per_shape"], "a_total", LINE_STYLES[line],
                      "a_n + a_f, %s line" % line)
    ac_axis(a)
    a.axhline(0, color="gray", lw=0.5)
    a.set_ylabel("anisotropy coefficient")
    a.set_title("(a) contact normals a_n, forces a_f and their sum, %d deposits"
                % sum(f["deposits"] for f in lines.values()))
    a.legend(fontsize=9)
    for line, f in lines.items():
        errorbars(k0, f["per_shape"], "K0", LINE_STYLES[line], "%s line" % line)
    ac_axis(k0)
    k0.set_ylabel("K0 = (sigma_xx + sigma_yy) / (2 sigma_zz)")
    k0.set_title("(b) lateral stress ratio K0")
    k0.legend(fontsize=9)
    colors = dict(zip(sorted(per_shape), plt.cm.viridis(np.linspace(0, 0.95, len(per_shape)))))
    for s, (theta, m, err) in sorted(mean_and_error(per_shape, "direction").items()):
        direction.errorbar(theta, m, yerr=np.nan_to_num(err), fmt="o-", ms=3, capsize=2,
                           color=colors[s], label="eta = zeta = %g (%d deposits)"
                           % (s[0], len(per_shape[s]["direction"][1])))
    direction.axhline(1, color="gray", ls=":", lw=1)
    direction.set_xticks([0, math.pi / 4, math.pi / 2, 3 * math.pi / 4, math.pi],
                         ["0", "pi/4", "pi/2", "3pi/4", "pi"])
    direction.set_xlabel("theta, contact normal against +z (rad)")
    direction.set_ylabel("mean normal force in the direction / <f>")
    direction.set_title("(c) force by direction")
    direction.legend(fontsize=9)
    for s, (f, p, err) in sorted(mean_and_error(per_shape, "magnitude").items()):
        keep = p > 0
        magnitude.errorbar(f[keep], p[keep], yerr=np.nan_to_num(err[keep]), fmt="o-", ms=3,
                           color=colors[s], capsize=2, label="eta = zeta = %g" % s[0])
    magnitude.set_yscale("log")
    magnitude.set_xlabel("normal force over its mean, f / <f>")
    magnitude.set_ylabel("probability density P(f / <f>)")
    magnitude.set_title("(d) normal-force distribution")
    magnitude.legend(fontsize=9)
    fig.suptitle("contact forces, window means at rest, %s; error bars: pooled seed SD / "
                 "sqrt(seeds)" % tag)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
