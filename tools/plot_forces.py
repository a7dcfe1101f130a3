"""fig_forces.png of the study (tools/plot_figures.py): the contact forces along eta = zeta.

(a) a_n, a_f, a_n + a_f and K0 against a/c with their pooled standard errors (claims.json
`forces`, tools/study_forces.py), and a_n + a_f along the spheroid lines where they have the
force measures; (b) the mean normal force in each direction over the mean
force, fbar(theta) / <f> (compute contact/histo weight force, column 4 over the mean force);
(c) P(f / <f>) of the normal forces (compute force/histo), on a log scale. (b) and (c) per
shape over the deposits that have the force histograms, with the seed SD pooled over the
shapes per bin / sqrt(seeds).
"""
import math
import os

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from deposit_run import read_histo, read_packing  # noqa: E402
from study_forces import MEASURES, NAMES  # noqa: E402
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
        mean_force = read_packing(os.path.join(d["folder"], "packing.dat"))["mean_normal_force"]
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


def figure(claims, deposits, path, tag):
    """the figure, or None (with a note) without the force measures"""
    lines = (claims or {}).get("forces") or {}
    forces = lines.get("diagonal")
    per_shape = curves(deposits)
    if forces is None or not per_shape:
        print("  %s: skipped (no deposit with the force measures)" % os.path.basename(path))
        return None
    fig, axes = plt.subplots(1, 3, figsize=(16, 5))
    ac = [r["a/c"] for r in forces["per_shape"]]
    for q, style in zip(MEASURES, ("o-", "s-", "^-", "D--")):
        axes[0].errorbar(ac, [r[q]["mean"] for r in forces["per_shape"]],
                         yerr=[r[q]["se"] or 0 for r in forces["per_shape"]], fmt=style, ms=4,
                         capsize=3, label=NAMES[q])
    for line, style in (("prolate", "v:"), ("oblate", "<:")):
        if line in lines:
            rows = lines[line]["per_shape"]
            axes[0].errorbar([r["a/c"] for r in rows], [r["a_total"]["mean"] for r in rows],
                             yerr=[r["a_total"]["se"] or 0 for r in rows], fmt=style, ms=4,
                             capsize=3, label="a_n + a_f, %s line" % line)
    axes[0].set_xscale("log")
    axes[0].xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    axes[0].xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    axes[0].set_xlabel("a/c = eta zeta (eta = zeta unless labelled)")
    axes[0].set_title("(a) anisotropies and K0, %d deposits"
                      % sum(f["deposits"] for f in lines.values()), fontsize=9)
    axes[0].axhline(0, color="gray", lw=0.5)
    axes[0].legend(fontsize=8)
    colors = dict(zip(sorted(per_shape), plt.cm.viridis(np.linspace(0, 0.95, len(per_shape)))))
    for s, (theta, m, err) in sorted(mean_and_error(per_shape, "direction").items()):
        axes[1].errorbar(theta, m, yerr=np.nan_to_num(err), fmt="o-", ms=3, capsize=2,
                         color=colors[s], label="eta = zeta = %g (%d)" % (s[0], len(per_shape[s]["direction"][1])))
    axes[1].axhline(1, color="gray", ls=":", lw=1)
    axes[1].set_xticks([0, math.pi / 4, math.pi / 2, 3 * math.pi / 4, math.pi],
                       ["0", "pi/4", "pi/2", "3pi/4", "pi"])
    axes[1].set_xlabel("theta (contact normal vs +z)")
    axes[1].set_ylabel("mean normal force in the direction / <f>")
    axes[1].set_title("(b) force by direction", fontsize=9)
    axes[1].legend(fontsize=7)
    for s, (f, p, err) in sorted(mean_and_error(per_shape, "magnitude").items()):
        keep = p > 0
        axes[2].errorbar(f[keep], p[keep], yerr=np.nan_to_num(err[keep]), fmt="o-", ms=3,
                         color=colors[s], capsize=2, label="eta = zeta = %g" % s[0])
    axes[2].set_yscale("log")
    axes[2].set_xlabel("f / <f>")
    axes[2].set_ylabel("P(f / <f>)")
    axes[2].set_title("(c) normal-force distribution", fontsize=9)
    axes[2].legend(fontsize=7)
    fig.suptitle("contact forces along eta = zeta (a: and the spheroid lines), %s; error bars: "
                 "pooled seed SD / sqrt(seeds)"
                 % tag, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
