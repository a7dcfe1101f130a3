"""The angle of repose of a heap from its surface profile, and a table of runs.

    ./ellipsoid-dep python examples/repose/repose_angle.py --table RUN_DIR... [--figure F]

The heap is a ridge along y (in.repose's slice is periodic in y). Its profile h(x) is the
highest particle top above the ground (the rough floor's top) in each bin of width `bin`
along x; a particle's top is its centre plus
its half-extent along z, sqrt(sum_k (s_k R_zk)^2) for semi-axes s_k and body axes R_k. Each
flank (left and right of the highest bin) is fitted by a straight line over the bins whose
height is within [lo, hi] of the peak's (the rounded top and the toe excluded); the angle is
atan |slope| with the fit's standard error. A run's angle is the mean of its two flanks; a set
of runs (seeds) gives the mean, with the SD of one run pooled over all cases (few seeds per
case) over sqrt(runs); the flanks' difference says whether the two sides agree.
"""
import argparse
import json
import math
import os
import sys

import numpy as np
from scipy.stats import norm, t as student_t

DECIDED = 0.0027       # a difference is decided at the two-sided p of 3 sigma
WINDOW = (0.2, 0.8)    # the part of the flank's height that is fitted
BIN = 1.0              # bin width along x, in d


def particle_tops(z, semi, quat):
    """the highest point of each ellipsoid: semi (n, 3) semi-axes, quat (n, 4) w, i, j, k"""
    w, i, j, k = quat.T
    # the z row of the rotation matrix (body axes in the lab frame)
    rz = np.stack([2 * (i * k - w * j), 2 * (j * k + w * i), 1 - 2 * (i * i + j * j)], axis=1)
    return z + np.sqrt(np.sum((semi * rz) ** 2, axis=1))


def profile(x, top, ground=0.0, bin_width=BIN):
    """(bin centres, highest top per bin above the ground); bins without a particle have 0"""
    lo, hi = np.floor(x.min() / bin_width), np.ceil(x.max() / bin_width) + 1
    edges = np.arange(lo, hi) * bin_width
    which = np.clip(np.digitize(x, edges) - 1, 0, len(edges) - 2)
    height = np.zeros(len(edges) - 1)
    np.maximum.at(height, which, top - ground)
    return 0.5 * (edges[:-1] + edges[1:]), height


def flank_fit(centres, height, side, window=WINDOW):
    """straight-line fit of one flank ('left' or 'right' of the peak): angle and its standard
    error in degrees, the number of bins fitted"""
    peak = int(np.argmax(height))
    top = height[peak]
    idx = np.arange(peak, -1, -1) if side == "left" else np.arange(peak, len(height))
    # walk down the flank from the peak to the first bin below the window's foot
    chosen = []
    for n in idx:
        if height[n] < window[0] * top:
            break
        if height[n] <= window[1] * top:
            chosen.append(n)
    if len(chosen) < 3:
        raise ValueError(f"the {side} flank has {len(chosen)} bins in the window; the heap is "
                         "too small for its bins")
    xs, hs = centres[chosen], height[chosen]
    slope, intercept = np.polyfit(xs, hs, 1)
    residual = hs - (slope * xs + intercept)
    sxx = np.sum((xs - xs.mean()) ** 2)
    slope_se = math.sqrt(np.sum(residual ** 2) / (len(xs) - 2) / sxx)
    angle = math.degrees(math.atan(abs(slope)))
    angle_se = math.degrees(slope_se / (1.0 + slope ** 2))
    return angle, angle_se, len(xs)


def heap_angle(centres, height, window=WINDOW):
    """{left, left_se, right, right_se, angle, angle_se, height, bins} of one heap"""
    left, left_se, nl = flank_fit(centres, height, "left", window)
    right, right_se, nr = flank_fit(centres, height, "right", window)
    return {"left": left, "left_se": left_se, "right": right, "right_se": right_se,
            "angle": 0.5 * (left + right), "angle_se": 0.5 * math.hypot(left_se, right_se),
            "height": float(height.max()), "bins": [nl, nr]}


def pooled_sd(groups):
    """(SD of one run's angle pooled over the cases with two runs or more, its degrees of
    freedom); (None, 0) without such a case"""
    squares, dof = 0.0, 0
    for rs in groups.values():
        if len(rs) > 1:
            angles = np.array([r["angle"] for r in rs])
            squares += np.sum((angles - angles.mean()) ** 2)
            dof += len(rs) - 1
    return (math.sqrt(squares / dof), dof) if dof else (None, 0)


def runs_summary(results, sd=None):
    """mean angle over runs and its standard error: sd / sqrt(n) with the pooled sd (seeds per
    case are few); without one, one run's fit error"""
    angles = np.array([r["angle"] for r in results])
    if sd is None:
        return float(angles.mean()), results[0]["angle_se"] / math.sqrt(len(angles)), len(angles)
    return float(angles.mean()), sd / math.sqrt(len(angles)), len(angles)


def read_runs(folders):
    """{(eta, zeta, mu): [repose.json of each run]} of run folders"""
    groups = {}
    for d in folders:
        path = os.path.join(d, "repose.json") if os.path.isdir(d) else d
        if not os.path.isfile(path):
            sys.exit(f"repose_angle.py: no {path} (run run_repose.py --out DIR first)")
        r = json.load(open(path))
        groups.setdefault((r["eta"], r["zeta"], r["mu"]), []).append(r)
    return groups


def table(groups):
    """the markdown tables of the README: each case, then each shape against spheres"""
    sd, dof = pooled_sd(groups)
    rows = ["| eta | zeta | mu | runs | angle (deg) | left - right (deg) | heap height (d) |",
            "|---|---|---|---|---|---|---|"]
    summary = {}
    for (eta, zeta, mu), rs in sorted(groups.items()):
        mean, se, n = runs_summary(rs, sd)
        summary[(eta, zeta, mu)] = (mean, se, n)
        diff = np.array([r["left"] - r["right"] for r in rs])
        dse = (diff.std(ddof=1) / math.sqrt(n) if n > 1
               else math.hypot(rs[0]["left_se"], rs[0]["right_se"]))
        rows.append(f"| {eta:g} | {zeta:g} | {mu:g} | {n} | {mean:.1f} +- {se:.1f} | "
                    f"{diff.mean():+.1f} +- {dse:.1f} | {np.mean([r['height'] for r in rs]):.1f} |")
    rows += ["", (f"Errors: the SD of one run's angle pooled over the cases, {sd:.2f} deg on {dof} "
                  "degrees of freedom, over sqrt(runs)." if sd else
                  "Errors: each run's fit error (no case has two runs yet)."),
             "", "| shape against spheres | mu | difference (deg) | t | p (two-sided) | verdict |",
             "|---|---|---|---|---|---|"]
    for (eta, zeta, mu), (mean, se, _) in sorted(summary.items()):
        if (eta, zeta) == (1.0, 1.0) or (1.0, 1.0, mu) not in summary:
            continue
        ref, ref_se, _ = summary[(1.0, 1.0, mu)]
        err = math.hypot(se, ref_se)
        t = abs(mean - ref) / err
        # the t distribution of the pooled SD's degrees of freedom (normal with fit errors)
        p = 2 * (student_t.sf(t, dof) if dof else norm.sf(t))
        verdict = "decided" if p < DECIDED else "undecided"
        rows.append(f"| eta {eta:g} zeta {zeta:g} | {mu:g} | {mean - ref:+.1f} +- {err:.1f} | "
                    f"{t:.1f} | {p:.2g} | {verdict} |")
    return "\n".join(rows)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--table", nargs="+", required=True, metavar="RUN",
                   help="run folders of run_repose.py (or their repose.json files)")
    p.add_argument("--figure", help="write the profiles and fitted flanks here")
    a = p.parse_args()
    groups = read_runs(a.table)
    print(table(groups))
    if a.figure:
        figure(groups, a.figure)


def figure(groups, path):
    """left: each case's first heap (profile and the fitted window); right: the angle against
    the particles' aspect ratio a/c, per friction, with the standard errors"""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 3.8), gridspec_kw={"width_ratios": [2, 1]})
    top_mu = max(m for _, _, m in groups)
    sd = pooled_sd(groups)[0]
    for (eta, zeta, mu), rs in sorted(groups.items()):
        if mu != top_mu:
            continue
        r = rs[0]
        left.plot(r["profile_x"], r["profile_h"], drawstyle="steps-mid",
                  label=f"eta {eta:g} zeta {zeta:g} (seed {r['seed']}): {r['angle']:.1f} deg")
    left.set_xlabel("x / d")
    left.set_ylabel("heap surface above the floor / d")
    left.set_aspect("equal")
    left.set_title(f"one heap per shape, mu {top_mu:g}", fontsize=9)
    left.legend(fontsize=7)
    for mu in sorted({m for _, _, m in groups}):
        cases = sorted((eta * zeta, runs_summary(rs, sd))
                       for (eta, zeta, m), rs in groups.items() if m == mu)
        right.errorbar([c for c, _ in cases], [s[0] for _, s in cases],
                       yerr=[s[1] for _, s in cases], marker="o", capsize=3, label=f"mu {mu:g}")
    right.set_xlabel("aspect ratio a/c = eta zeta")
    right.set_ylabel("angle of repose (deg)")
    right.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)


if __name__ == "__main__":
    main()
