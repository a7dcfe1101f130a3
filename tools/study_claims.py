#!/usr/bin/python3
"""The numbers behind the paper's claims, from a study's results folder (doc/study.md).

    ./ellipsoid-dep python tools/study_claims.py examples/study/results [--law coulomb] [--N 3000]

Reads deposits.csv (tools/study_table.py) and the histograms of every deposit and writes
claims.json into the results folder (and prints it as markdown):

* `maxima`: for the diagonal eta = zeta and the prolate (zeta = 1, vs eta) and oblate
  (eta = 1, vs zeta) lines at delta_r = 0, the position and height of the density maximum:
  a parabola through the highest point and its neighbours (five points where there are
  five), with its uncertainty from a parametric bootstrap: every point's mean is redrawn
  from a normal distribution with the seed-to-seed standard deviation pooled over all shapes
  at delta_r = 0 with two seeds or more, divided by sqrt(its seeds) (no uncertainty while no
  shape has two seeds; fits whose vertex leaves the window are dropped and counted);
* `symmetry`: phi(eta, zeta) - phi(zeta, eta) over the map's pairs, its mean, and chi^2 per
  pair against the standard errors (about 1 when the map is symmetric within its errors);
* `crossings`: the angle theta in (0, pi/2) at which a shape's P(Omega(theta)) of contact
  normals (and of long axes) crosses the isotropic value 1/(4 pi), per shape at delta_r = 0,
  with the standard error over its seeds; the paper reports contact-normal curves crossing
  "slightly above pi/5" and long-axis curves with an invariant near pi/3.
"""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from deposit_run import read_histo  # noqa: E402

ISOTROPIC = 1.0 / (4.0 * math.pi)
LINES = {"diagonal": (lambda e, z: e == z, "eta"),
         "prolate": (lambda e, z: z == 1.0 and e > 1.0, "eta"),
         "oblate": (lambda e, z: e == 1.0 and z > 1.0, "zeta")}
BOOTSTRAP = 2000


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def fit_maximum(x, y):
    """vertex of the least-squares parabola through (x, y); None if it opens upwards"""
    c2, c1, c0 = np.polyfit(x, y, 2)
    if c2 >= 0:
        return None
    xm = -c1 / (2 * c2)
    return xm, c0 + c1 * xm + c2 * xm * xm


def pooled_sd(samples):
    """seed-to-seed standard deviation pooled over the points that have two seeds or more"""
    num = sum((len(v) - 1) * np.var(v, ddof=1) for v in samples if len(v) > 1)
    dof = sum(len(v) - 1 for v in samples if len(v) > 1)
    return math.sqrt(num / dof) if dof else None


def line_maximum(points, sd, rng):
    """points: [(x, [phi per seed])] sorted by x; sd: the seed-to-seed standard deviation of
    one deposit (None: unknown). The maximum's position and height."""
    means = [float(np.mean(v)) for _, v in points]
    k = int(np.argmax(means))
    lo = max(0, min(k - 2, len(points) - 5))
    window = points[lo:lo + 5]
    if len(window) < 3 or k in (0, len(points) - 1):
        return {"at_edge": True, "x_highest": points[k][0], "phi_highest": means[k]}
    x = np.array([p[0] for p in window])
    best = fit_maximum(x, [float(np.mean(v)) for _, v in window])
    if best is None:
        return {"at_edge": False, "x_highest": points[k][0], "phi_highest": means[k],
                "fit": None}
    means_w = np.array([float(np.mean(v)) for _, v in window])
    errors_w = np.array([sd / math.sqrt(len(v)) for _, v in window]) if sd is not None else None
    draws = []
    for _ in range(BOOTSTRAP if sd is not None else 0):
        fit = fit_maximum(x, means_w + rng.normal(0.0, errors_w))
        if fit is not None and x[0] <= fit[0] <= x[-1]:
            draws.append(fit)
    out = {"at_edge": False, "x_highest": points[k][0], "phi_highest": means[k],
           "x_max": float(best[0]), "phi_max": float(best[1]), "window": x.tolist(),
           "seed_sd": sd, "bootstrap_draws": BOOTSTRAP if sd is not None else 0,
           "bootstrap_kept": len(draws)}
    if draws:
        d = np.array(draws)
        out["x_max_sd"] = float(d[:, 0].std(ddof=1))
        out["phi_max_sd"] = float(d[:, 1].std(ddof=1))
    return out


def crossing(theta, p, rising):
    """first theta in (0, pi/2) where p crosses the isotropic value, linear in between bins"""
    f = np.asarray(p) - ISOTROPIC
    for k in range(len(theta) - 1):
        if theta[k + 1] > math.pi / 2 + 1e-9:
            break
        if (f[k] < 0 <= f[k + 1]) if rising else (f[k] > 0 >= f[k + 1]):
            return float(theta[k] + (theta[k + 1] - theta[k]) * f[k] / (f[k] - f[k + 1]))
    return None


def shape_crossings(deposits, histo, rising):
    """{(eta, zeta): (mean crossing, standard error, seeds)} over the deposits at delta_r 0"""
    by_shape = {}
    for d in deposits:
        theta, p, _ = read_histo(os.path.join(d["folder"], histo + ".dat"))
        by_shape.setdefault((float(d["eta"]), float(d["zeta"])), []).append(
            crossing(theta, p, rising))
    out = {}
    for shape, values in sorted(by_shape.items()):
        v = [x for x in values if x is not None]
        if v:
            sem = float(np.std(v, ddof=1) / math.sqrt(len(v))) if len(v) > 1 else None
            out[shape] = (float(np.mean(v)), sem, len(v))
    return out


def claims(results, law, n):
    rng = np.random.default_rng(20261201)
    deposits = [d for d in read_csv(os.path.join(results, "deposits.csv"))
                if d["law"] == law and int(d["N"]) == n and float(d["delta_r"]) == 0.0]
    for d in deposits:
        d["folder"] = os.path.join(results, "points", d["point"], "s%s" % d["seed"])
    phi = {}
    for d in deposits:
        phi.setdefault((float(d["eta"]), float(d["zeta"])), []).append(float(d["phi"]))

    sd = pooled_sd(list(phi.values()))    # over every shape at delta_r 0
    maxima = {}
    for name, (on_line, axis) in LINES.items():
        pts = sorted(((e if axis == "eta" else z), v) for (e, z), v in phi.items()
                     if on_line(e, z) or (e == z == 1.0))
        if len(pts) >= 3:
            maxima[name] = line_maximum(pts, sd, rng)

    diffs, chi2 = [], []
    for (e, z), v in phi.items():
        if e < z and (z, e) in phi:
            w = phi[(z, e)]
            diffs.append(float(np.mean(v) - np.mean(w)))
            if len(v) > 1 and len(w) > 1:
                var = np.var(v, ddof=1) / len(v) + np.var(w, ddof=1) / len(w)
                chi2.append(diffs[-1] ** 2 / var)
    symmetry = {"pairs": len(diffs),
                "mean_difference": float(np.mean(diffs)) if diffs else None,
                "rms_difference": float(np.sqrt(np.mean(np.square(diffs)))) if diffs else None,
                "chi2_per_pair": float(np.mean(chi2)) if chi2 else None,
                "pairs_with_errors": len(chi2)}

    def listed(table):
        return [{"eta": e, "zeta": z, "theta": t, "sem": s, "seeds": k}
                for (e, z), (t, s, k) in table.items()]

    contact = shape_crossings(deposits, "contact_histo", rising=False)
    orient = shape_crossings(deposits, "orient_histo", rising=True)
    aspherical = lambda table: [t for (e, z), (t, _, _) in table.items() if (e, z) != (1.0, 1.0)]  # noqa: E731
    summary = {}
    for name, table in (("contact", contact), ("orient", orient)):
        v = aspherical(table)
        summary[name] = {"shapes": len(v), "mean": float(np.mean(v)) if v else None,
                         "sd_over_shapes": float(np.std(v, ddof=1)) if len(v) > 1 else None}
    return {"law": law, "N": n, "deposits": len(deposits), "maxima": maxima,
            "symmetry": symmetry,
            "crossings": {"contact_normals": listed(contact), "long_axes": listed(orient),
                          "summary": summary}}


def markdown(c):
    lines = ["| line | highest point | fitted maximum (x, phi) | +- (bootstrap SD) |",
             "|---|---|---|---|"]
    for name, m in c["maxima"].items():
        fit = ("%.3f, %.4f" % (m["x_max"], m["phi_max"])) if "x_max" in m else (
            "at the line's edge" if m["at_edge"] else "no maximum in the window")
        err = ("%.3f, %.4f" % (m["x_max_sd"], m["phi_max_sd"])) if "x_max_sd" in m else "-"
        lines.append("| %s | %g, %.4f | %s | %s |" % (name, m["x_highest"], m["phi_highest"],
                                                     fit, err))
    s = c["symmetry"]
    lines.append("")
    lines.append("symmetry: %d pairs, mean phi(eta<zeta) - phi(eta>zeta) %s, rms %s, chi2/pair %s"
                 % (s["pairs"], s["mean_difference"], s["rms_difference"], s["chi2_per_pair"]))
    for key, label in (("contact", "contact normals"), ("orient", "long axes")):
        m = c["crossings"]["summary"][key]
        if m["mean"] is not None:
            lines.append("%s cross 1/(4 pi) at %.3f rad = %.3f pi (SD over %d shapes %s)"
                         % (label, m["mean"], m["mean"] / math.pi, m["shapes"],
                            "%.3f" % m["sd_over_shapes"] if m["sd_over_shapes"] else "-"))
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results", help="the study's results folder (table.csv, deposits.csv)")
    ap.add_argument("--law", default="coulomb")
    ap.add_argument("--N", type=int, default=3000)
    args = ap.parse_args(argv)
    c = claims(args.results, args.law, args.N)
    path = os.path.join(args.results, "claims.json")
    with open(path + ".tmp", "w") as f:
        json.dump(c, f, indent=1)
    os.replace(path + ".tmp", path)
    print(markdown(c))
    print("study_claims: wrote %s" % path)


if __name__ == "__main__":
    main()
