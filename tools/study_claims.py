#!/usr/bin/python3
"""The numbers behind the paper's claims, from a study's results folder (doc/study.md).

    ./ellipsoid-dep python tools/study_claims.py results/study [--law coulomb] [--N 3000]

Reads deposits.csv (tools/study_table.py) and the histograms of every deposit at N and writes
claims.json into the results folder (and prints it as markdown). The deposits are taken one
selection at a time: those of one delta_r and one tangential law. `--law` names the default
law (the study's); the first three keys are its deposits at delta_r = 0:

* `maxima`: for the diagonal eta = zeta and the prolate (zeta = 1, vs eta) and oblate
  (eta = 1, vs zeta) lines, the position and height of the density maximum: a parabola
  through the highest point and its neighbours (five points where there are five), with its
  uncertainty from a parametric bootstrap: every point's mean is redrawn from a normal
  distribution with the seed-to-seed standard deviation pooled over all shapes of the
  selection with two seeds or more, divided by sqrt(its seeds) (no uncertainty while no shape
  has two seeds; fits whose vertex leaves the window are dropped and counted);
* `symmetry`: phi(eta, zeta) - phi(zeta, eta) over the map's pairs, its mean, and chi^2 per
  pair against the standard errors from the pooled seed SD (about 1 when the map is
  symmetric within the seed scatter);
* `crossings`: the angle theta in (0, pi/2) at which a shape's P(Omega(theta)) of contact
  normals (and of long axes) crosses the isotropic value 1/(4 pi), per shape, with the
  standard error over its seeds; the paper reports contact-normal curves crossing "slightly
  above pi/5" and long-axis curves with an invariant near pi/3;
* `constant_eta`: for each eta with three values of zeta or more, the maximum of phi over
  zeta (the same fit and bootstrap), to compare zeta_max with eta;
* `polydispersity`: `density`, for each delta_r > 0 of the default law: per shape present at
  that delta_r and at 0, phi(delta_r) - phi(0) with its standard error (each side's pooled
  seed SD of its selection / sqrt(its seeds)), grouped by line (diagonal
  with the spheres, prolate, oblate, other), the mean difference over the shapes of each
  line and of all (standard error from the shapes' standard errors), and the diagonal's
  fitted maximum at that delta_r; `histograms`, for each shape present at several
  delta_r: its crossing angles per delta_r, and per delta_r > 0 the rms over the bins of the
  difference between its seed-mean histograms at delta_r and at 0, against the rms
  difference that the seed scatter alone gives (the rms of the difference's standard
  error; null with one seed);
* `laws`: for each other tangential law and each delta_r it was run at: its diagonal
  maximum, per shape phi(law) - phi(default law) grouped as above, and its crossings.
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
OTHER = "other"    # the group of shapes on none of the lines
HISTOGRAMS = {"contact_normals": ("contact_histo", False, "contact"),    # name: (file, rising
              "long_axes": ("orient_histo", True, "orient")}             # crossing, summary)
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


def line_of(eta, zeta):
    """the line of LINES a shape lies on (spheres: the diagonal), else OTHER"""
    return next((name for name, (on_line, _) in LINES.items() if on_line(eta, zeta)), OTHER)


class Selection:
    """the deposits of one delta_r and one tangential law: per shape its deposits and phi
    per seed, and the seed-to-seed SD of phi pooled over the shapes"""

    def __init__(self, deposits):
        self.deposits = deposits
        self.shapes = {}
        for d in deposits:
            self.shapes.setdefault((float(d["eta"]), float(d["zeta"])), []).append(d)
        self.phi = {s: [float(d["phi"]) for d in v] for s, v in sorted(self.shapes.items())}
        self.sd = pooled_sd(list(self.phi.values()))

    def line(self, name):
        """[(x, [phi per seed])] along a line of LINES, spheres included, sorted by x"""
        on_line, axis = LINES[name]
        return sorted(((e if axis == "eta" else z), v) for (e, z), v in self.phi.items()
                      if on_line(e, z) or (e == z == 1.0))

    def line_maximum(self, name, rng):
        """the fitted maximum along a line; None with fewer than three points on it"""
        points = self.line(name)
        return line_maximum(points, self.sd, rng) if len(points) >= 3 else None

    def standard_error(self, shape):
        """of the shape's mean phi: the pooled seed SD / sqrt(its seeds). With 2-3 seeds a
        point's own SD has 1-2 degrees of freedom: ratios to it scatter far more than
        chi^2 does; the bootstrap uses the same model. None while no shape has two seeds."""
        return self.sd / math.sqrt(len(self.phi[shape])) if self.sd is not None else None


def crossing(theta, p, rising):
    """first theta in (0, pi/2) where p crosses the isotropic value, linear in between bins"""
    f = np.asarray(p) - ISOTROPIC
    for k in range(len(theta) - 1):
        if theta[k + 1] > math.pi / 2 + 1e-9:
            break
        if (f[k] < 0 <= f[k + 1]) if rising else (f[k] > 0 >= f[k + 1]):
            return float(theta[k] + (theta[k + 1] - theta[k]) * f[k] / (f[k] - f[k + 1]))
    return None


def mean_crossing(deposits, histogram):
    """{theta, sem, seeds} over the deposits (of one shape) whose curve crosses; None if none"""
    name, rising, _ = HISTOGRAMS[histogram]
    v = [x for x in (crossing(*d[name], rising) for d in deposits) if x is not None]
    if not v:
        return None
    sem = float(np.std(v, ddof=1) / math.sqrt(len(v))) if len(v) > 1 else None
    return {"theta": float(np.mean(v)), "sem": sem, "seeds": len(v)}


def crossings(selection):
    """per histogram the crossing of each shape, and their summary over the aspherical ones"""
    out, summary = {}, {}
    for histogram, (_, _, summary_key) in HISTOGRAMS.items():
        rows = []
        for (e, z), deposits in sorted(selection.shapes.items()):
            c = mean_crossing(deposits, histogram)
            if c is not None:
                rows.append(dict({"eta": e, "zeta": z}, **c))
        out[histogram] = rows
        v = [r["theta"] for r in rows if (r["eta"], r["zeta"]) != (1.0, 1.0)]
        summary[summary_key] = {
            "shapes": len(v), "mean": float(np.mean(v)) if v else None,
            "sd_over_shapes": float(np.std(v, ddof=1)) if len(v) > 1 else None}
    out["summary"] = summary
    return out


def symmetry(selection):
    phi = selection.phi
    diffs, chi2 = [], []
    for (e, z), v in phi.items():
        if e < z and (z, e) in phi:
            w = phi[(z, e)]
            diffs.append(float(np.mean(v) - np.mean(w)))
            if selection.sd:
                se_v, se_w = selection.standard_error((e, z)), selection.standard_error((z, e))
                var = se_v ** 2 + se_w ** 2
                chi2.append(diffs[-1] ** 2 / var)
    return {"pairs": len(diffs),
            "mean_difference": float(np.mean(diffs)) if diffs else None,
            "rms_difference": float(np.sqrt(np.mean(np.square(diffs)))) if diffs else None,
            "chi2_per_pair": float(np.mean(chi2)) if chi2 else None,
            "pairs_with_errors": len(chi2)}


def constant_eta(selection, rng):
    """the maximum over zeta along each eta with three values of zeta or more"""
    out = []
    for eta in sorted({e for e, _ in selection.phi}):
        points = sorted((z, v) for (e, z), v in selection.phi.items() if e == eta)
        if len(points) >= 3:
            out.append(dict({"eta": eta, "zetas": len(points)},
                            **line_maximum(points, selection.sd, rng)))
    return out


def mean_over_shapes(rows):
    """mean of the shapes' differences; its standard error from theirs (null if one is
    unknown), and their spread"""
    d = [r["difference"] for r in rows]
    sems = [r["sem"] for r in rows]
    known = bool(d) and all(s is not None for s in sems)
    return {"shapes": len(d), "mean": float(np.mean(d)) if d else None,
            "sem": float(math.sqrt(sum(s * s for s in sems)) / len(d)) if known else None,
            "sd_over_shapes": float(np.std(d, ddof=1)) if len(d) > 1 else None}


def phi_differences(selection, reference):
    """phi(selection) - phi(reference) per shape present in both, grouped by line"""
    per_line = {name: [] for name in list(LINES) + [OTHER]}
    for shape in sorted(set(selection.phi) & set(reference.phi)):
        a, b = selection.standard_error(shape), reference.standard_error(shape)
        per_line[line_of(*shape)].append({
            "eta": shape[0], "zeta": shape[1],
            "difference": float(np.mean(selection.phi[shape]) - np.mean(reference.phi[shape])),
            "sem": math.hypot(a, b) if a is not None and b is not None else None,
            "seeds": [len(selection.phi[shape]), len(reference.phi[shape])]})
    means = {name: mean_over_shapes(rows) for name, rows in per_line.items()}
    means["all"] = mean_over_shapes([r for rows in per_line.values() for r in rows])
    return {"per_shape": per_line, "mean": means}


def seed_mean_histogram(deposits, name):
    """theta, the mean P over the deposits, and its standard error per bin (None: one seed)"""
    curves = [d[name] for d in deposits]
    theta = np.asarray(curves[0][0])
    if any(len(c[0]) != len(theta) for c in curves):
        raise ValueError("histograms with different bins: %s" % [d["folder"] for d in deposits])
    p = np.asarray([c[1] for c in curves])
    sem = p.std(axis=0, ddof=1) / math.sqrt(len(p)) if len(p) > 1 else None
    return theta, p.mean(axis=0), sem


def histogram_difference(deposits, reference, histogram):
    """rms over the bins of the seed-mean difference, and what the seed scatter gives"""
    name = HISTOGRAMS[histogram][0]
    theta, p, sem = seed_mean_histogram(deposits, name)
    theta0, p0, sem0 = seed_mean_histogram(reference, name)
    if not np.allclose(theta, theta0):
        raise ValueError("%s: different bins at the two delta_r" % name)
    noise = (float(np.sqrt(np.mean(sem ** 2 + sem0 ** 2)))
             if sem is not None and sem0 is not None else None)
    return {"rms_difference": float(np.sqrt(np.mean((p - p0) ** 2))),
            "rms_seed_scatter": noise, "seeds": [len(deposits), len(reference)]}


def histograms_with_delta_r(by_delta_r):
    """{delta_r: Selection} of one law: shapes at several delta_r, their crossings and their
    histograms' differences from delta_r = 0"""
    reference = by_delta_r.get(0.0)
    shapes = sorted({s for sel in by_delta_r.values() for s in sel.shapes})
    out = []
    for shape in shapes:
        present = [dr for dr in sorted(by_delta_r) if shape in by_delta_r[dr].shapes]
        if len(present) < 2:
            continue
        entry = {"eta": shape[0], "zeta": shape[1], "per_delta_r": [], "differences": []}
        for dr in present:
            deposits = by_delta_r[dr].shapes[shape]
            entry["per_delta_r"].append(dict({"delta_r": dr}, **{
                h: mean_crossing(deposits, h) for h in HISTOGRAMS}))
            if dr != 0.0 and reference is not None and shape in reference.shapes:
                entry["differences"].append(dict({"delta_r": dr}, **{
                    h: histogram_difference(deposits, reference.shapes[shape], h)
                    for h in HISTOGRAMS}))
        out.append(entry)
    return out


def load_deposits(results, n):
    """the deposits at N, each with its folder and its two histograms (theta, P)"""
    deposits = [d for d in read_csv(os.path.join(results, "deposits.csv")) if int(d["N"]) == n]
    for d in deposits:
        d["folder"] = os.path.join(results, "points", d["point"], "s%s" % d["seed"])
        for name, _, _ in HISTOGRAMS.values():
            d[name] = read_histo(os.path.join(d["folder"], name + ".dat"))[:2]
    return deposits


def claims(results, law, n):
    rng = np.random.default_rng(20261201)    # one stream, drawn in the order of the keys
    groups = {}
    for d in load_deposits(results, n):
        groups.setdefault((float(d["delta_r"]), d["law"]), []).append(d)
    selections = {key: Selection(v) for key, v in sorted(groups.items())}
    base = selections.get((0.0, law), Selection([]))
    maxima = {}
    for name in LINES:
        m = base.line_maximum(name, rng)
        if m is not None:
            maxima[name] = m
    out = {"law": law, "N": n, "deposits": len(base.deposits), "maxima": maxima,
           "symmetry": symmetry(base), "crossings": crossings(base),
           "constant_eta": constant_eta(base, rng)}
    density = []
    for (dr, name), sel in selections.items():
        if name == law and dr > 0.0:
            density.append({"delta_r": dr, "deposits": len(sel.deposits),
                            "phi_difference": phi_differences(sel, base),
                            "diagonal_maximum": sel.line_maximum("diagonal", rng)})
    out["polydispersity"] = {
        "density": density,
        "histograms": histograms_with_delta_r({dr: sel for (dr, name), sel in selections.items()
                                               if name == law})}
    out["laws"] = [{"law": name, "delta_r": dr, "deposits": len(sel.deposits),
                    "diagonal_maximum": sel.line_maximum("diagonal", rng),
                    "phi_difference": phi_differences(sel, selections.get((dr, law),
                                                                          Selection([]))),
                    "crossings": crossings(sel)}
                   for (dr, name), sel in selections.items() if name != law]
    return out


def number(value, spec):
    return "-" if value is None else spec % value


def maximum_cells(m):
    """highest point, fitted maximum and its bootstrap SD of a line_maximum result"""
    if m is None:
        return ["-", "fewer than 3 points", "-"]
    fit = ("%.3f, %.4f" % (m["x_max"], m["phi_max"])) if "x_max" in m else (
        "at the line's edge" if m["at_edge"] else "no maximum in the window")
    err = ("%.3f, %.4f" % (m["x_max_sd"], m["phi_max_sd"])) if "x_max_sd" in m else "-"
    return ["%g, %.4f" % (m["x_highest"], m["phi_highest"]), fit, err]


def row(cells):
    return "| " + " | ".join(cells) + " |"


def crossing_cell(c):
    if c is None:
        return "-"
    return "%.3f%s (%d)" % (c["theta"], "" if c["sem"] is None else " +- %.3f" % c["sem"],
                            c["seeds"])


def difference_cell(d):
    return "%.2e vs %s" % (d["rms_difference"],
                           "one seed" if d["rms_seed_scatter"] is None
                           else "%.2e" % d["rms_seed_scatter"])


def markdown(c):
    lines = ["| line | highest point | fitted maximum (x, phi) | +- (bootstrap SD) |",
             "|---|---|---|---|"]
    for name, m in c["maxima"].items():
        lines.append(row([name] + maximum_cells(m)))
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
    if c["constant_eta"]:
        lines += ["", "constant eta: the maximum over zeta",
                  "| eta | zetas | highest point (zeta, phi) | fitted maximum (zeta, phi) "
                  "| +- | zeta_max - eta |", "|---|---|---|---|---|---|"]
        for m in c["constant_eta"]:
            lines.append(row(["%g" % m["eta"], "%d" % m["zetas"]] + maximum_cells(m)
                             + [("%+.3f" % (m["x_max"] - m["eta"])) if "x_max" in m else "-"]))
    if c["polydispersity"]["density"]:
        lines += ["", "polydispersity: phi(delta_r) - phi(0), mean over the shapes",
                  "| delta_r | group | shapes | mean | +- | SD over shapes |",
                  "|---|---|---|---|---|---|"]
        for p in c["polydispersity"]["density"]:
            for group, m in p["phi_difference"]["mean"].items():
                if m["shapes"]:
                    lines.append(row(["%g" % p["delta_r"], group, "%d" % m["shapes"],
                                      "%+.4f" % m["mean"], number(m["sem"], "%.4f"),
                                      number(m["sd_over_shapes"], "%.4f")]))
        lines += ["", "| delta_r | diagonal: highest point | fitted maximum | +- |",
                  "|---|---|---|---|"]
        for p in c["polydispersity"]["density"]:
            lines.append(row(["%g" % p["delta_r"]] + maximum_cells(p["diagonal_maximum"])))
    if c["polydispersity"]["histograms"]:
        lines += ["", "histograms against delta_r: crossing angle +- sem (seeds); rms of the "
                  "difference from delta_r 0 vs the rms the seed scatter gives",
                  "| eta, zeta | delta_r | contact crossing | long-axis crossing "
                  "| contact difference | long-axis difference |", "|---|---|---|---|---|---|"]
        for h in c["polydispersity"]["histograms"]:
            diffs = {d["delta_r"]: d for d in h["differences"]}
            for p in h["per_delta_r"]:
                d = diffs.get(p["delta_r"])
                lines.append(row(["%g, %g" % (h["eta"], h["zeta"]), "%g" % p["delta_r"],
                                  crossing_cell(p["contact_normals"]),
                                  crossing_cell(p["long_axes"])]
                                 + ([difference_cell(d[k]) for k in HISTOGRAMS] if d
                                    else ["-", "-"])))
    if c["laws"]:
        lines += ["", "tangential laws against %s" % c["law"],
                  "| law | delta_r | diagonal: highest point | fitted maximum | +- "
                  "| mean phi difference (shapes) | +- | contact crossing | long-axis crossing |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for m in c["laws"]:
            mean = m["phi_difference"]["mean"]["all"]
            summary = m["crossings"]["summary"]
            lines.append(row(
                [m["law"], "%g" % m["delta_r"]] + maximum_cells(m["diagonal_maximum"])
                + ["%s (%d)" % (number(mean["mean"], "%+.4f"), mean["shapes"]),
                   number(mean["sem"], "%.4f")]
                + ["%s (%d shapes)" % (number(summary[k]["mean"], "%.3f"), summary[k]["shapes"])
                   for k in ("contact", "orient")]))
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results", help="the study's results folder (table.csv, deposits.csv)")
    ap.add_argument("--law", default="coulomb", help="the default tangential law")
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
