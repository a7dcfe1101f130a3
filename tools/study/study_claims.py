#!/usr/bin/python3
"""The numbers behind the paper's claims, from a study's results folder (doc/study.md).

    ./ellipsoid-dep python tools/study/study_claims.py results/study [--law coulomb] [--N 3000]

Reads deposits.csv (tools/study/study_table.py) and the histograms of every deposit at N and writes
claims.json into the results folder (and prints it as markdown). The deposits are taken one
selection at a time: those of one delta_r and one tangential law. `--law` names the default
law (the study's); the first three keys are its deposits at delta_r = 0:

Errors: a shape's standard error is the seed-to-seed SD pooled over its group of shapes in
its selection, / sqrt(its seeds) (tools/study/study_stats.py: spheroids, general shapes below and
above a/c = 4; `errors` lists every group's SD and degrees of freedom per quantity).

* `maxima`: for the diagonal eta = zeta and the prolate (zeta = 1, vs eta) and oblate
  (eta = 1, vs zeta) lines, the position and height of the density maximum: the nominal fit
  is a parabola through the highest point and its neighbours (five points), its error a
  parametric bootstrap (every point's mean redrawn from a normal distribution with its
  standard error; fits whose vertex leaves the window are dropped and counted); `fits` holds
  the 3-, 5- and 7-point parabolas and the 7-point cubic, and half their spread is the
  fit-window systematic (x_max_sys, phi_max_sys);
* `symmetry`: phi(eta, zeta) - phi(zeta, eta) over the map's pairs, its mean, and chi^2 per
  pair against the standard errors from the pooled seed SD (about 1 when the map is
  symmetric within the seed scatter);
* `crossings`: the angle theta in (0, pi/2) at which a shape's P(Omega(theta)) of contact
  normals (and of long axes) crosses the isotropic value 1/(4 pi), per shape, with the
  standard error over its seeds (`verdicts` gives it from the pooled SD); the paper reports
  contact-normal curves crossing "slightly above pi/5" and long-axis curves with an invariant
  near pi/3;
* `constant_eta`: for each eta with three values of zeta or more, the maximum of phi over
  zeta (the same fit and bootstrap), to compare zeta_max with eta;
* `polydispersity`: `density`, for each delta_r > 0 of the default law: per shape present at
  that delta_r and at 0, phi(delta_r) - phi(0) with its standard error (each side's pooled
  SD of its group / sqrt(its seeds)), grouped by line (diagonal
  with the spheres, prolate, oblate, other), the mean difference over the shapes of each
  line and of all (standard error from the shapes' standard errors), and the diagonal's
  fitted maximum at that delta_r; `histograms`, for each shape present at several
  delta_r: its crossing angles per delta_r, and per delta_r > 0 the rms over the bins of the
  difference between its seed-mean histograms at delta_r and at 0, against the rms
  difference that the seed scatter alone gives (the rms of the difference's standard
  error; null with one seed);
* `laws`: for each other tangential law and each delta_r it was run at: its diagonal
  maximum, per shape phi(law) - phi(default law) grouped as above, and its crossings;
* `forces`: the force measures a_n, a_f, a_n + a_f and K0 along the diagonal and the spheroid
  lines (a key per line), their trends against a/c and verdicts (tools/study/study_forces.py), over
  the deposits that have them as window means (window_steps > 0); `force_mirror`: the
  correlation of K0 with a_f across those deposits, seed by seed;
* `depth`: delta_r at matched depth beside delta_r at the study's N, and the finite-size
  check (tools/study/study_depth.py; the deposits at another N or box); null without them;
* `verdicts`: each claim's comparison with its significance and the seeds per point a
  3-sigma verdict needs (tools/study/study_verdicts.py, tools/study/study_histograms.py).
"""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _paths  # noqa: E402,F401  (tools/_paths.py: the topic folders on sys.path)
from deposit_run import read_histo, read_packing  # noqa: E402
from study_claims_md import markdown  # noqa: E402
from study_stats import LINES, Pooled, line_maximum, on_line  # noqa: E402
from study_depth import depth_claims  # noqa: E402
from study_forces import forces, measured, mirror  # noqa: E402
from study_verdicts import verdicts  # noqa: E402
from study_histograms import histogram_difference  # noqa: E402

ISOTROPIC = 1.0 / (4.0 * math.pi)
OTHER = "other"    # the group of shapes on none of the lines
HISTOGRAMS = {"contact_normals": ("contact_histo", False, "contact"),    # name: (file, rising
              "long_axes": ("orient_histo", True, "orient")}             # crossing, summary)


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def maximum_entry(m, seed_sd):
    """study_stats.line_maximum's result under the keys of claims.json: the highest point,
    the nominal fit (x_max, phi_max), its bootstrap SD (*_sd) and fit-window systematic
    (*_sys), every window's fit (`fits`); seed_sd: the pooled SD of the highest point"""
    out = {"at_edge": m["at_edge"], "x_highest": m["x_highest"], "phi_highest": m["y_highest"],
           "seed_sd": seed_sd}
    if m["at_edge"]:
        return out
    out["fits"] = m["fits"]
    if "x_max" not in m:
        out["fit"] = None
        return out
    nominal = m["fits"][m["nominal"]]
    out.update(x_max=m["x_max"], phi_max=m["y_max"], window=nominal["window"],
               nominal=m["nominal"], bootstrap_draws=nominal.get("draws", 0),
               bootstrap_kept=nominal.get("kept", 0), x_max_sys=m["x_sys"],
               phi_max_sys=m["y_sys"])
    if "x_sd" in m:
        out.update(x_max_sd=m["x_sd"], phi_max_sd=m["y_sd"])
    return out


def line_of(eta, zeta):
    """the line of LINES a shape lies on (spheres: the diagonal), else OTHER"""
    return next((name for name, (lies_on, _) in LINES.items() if lies_on(eta, zeta)), OTHER)


class Selection:
    """the deposits of one delta_r and one tangential law: per shape its deposits and phi
    per seed, and the seed-to-seed SD of phi pooled per group of shapes (study_stats)"""

    def __init__(self, deposits):
        self.deposits = deposits
        self.shapes = {}
        for d in deposits:
            self.shapes.setdefault((float(d["eta"]), float(d["zeta"])), []).append(d)
        self.shapes = dict(sorted(self.shapes.items()))
        self.phi = {s: [float(d["phi"]) for d in v] for s, v in self.shapes.items()}
        self.pooled = Pooled(self.phi)

    def subset(self, keep):
        """the Selection of the deposits d with keep(d)"""
        return Selection([d for d in self.deposits if keep(d)])

    def has(self, name):
        """whether every deposit has a value of this column (older tables lack some)"""
        return all(d.get(name) not in (None, "") for d in self.deposits)

    def with_forces(self):
        """the Selection of the deposits that have the force measures, with their columns
        (study_forces.measured: a_n, a_f, a_total, K0)"""
        return Selection([dict(d, **m) for d in self.deposits
                          if (m := measured(d)) is not None])

    def quantity(self, name):
        """the pooled SDs of another column of deposits.csv"""
        return Pooled({s: [float(d[name]) for d in v] for s, v in self.shapes.items()})

    def line(self, name):
        """[(x, shape)] along a line of LINES, spheres included, sorted by x"""
        axis = LINES[name][1]
        return sorted(((e if axis == "eta" else z), (e, z)) for (e, z) in self.phi
                      if on_line(name, e, z))

    def maximum(self, points, rng, pooled=None):
        """the maximum along [(x, shape)] of phi (or of another Pooled quantity)"""
        pooled = pooled or self.pooled
        shapes = [s for _, s in points]
        errors = [pooled.se(s) for s in shapes]
        m = line_maximum([x for x, _ in points], [pooled.mean(s) for s in shapes],
                         None if None in errors else errors, rng)
        highest = shapes[int(np.argmax([pooled.mean(s) for s in shapes]))]
        return maximum_entry(m, pooled.sd(highest))

    def line_maximum(self, name, rng):
        """the fitted maximum along a line; None with fewer than three points on it"""
        points = self.line(name)
        return self.maximum(points, rng) if len(points) >= 3 else None

    def standard_error(self, shape):
        """of the shape's mean phi: its group's pooled seed SD / sqrt(its seeds). None while
        its group has no shape with two seeds."""
        return self.pooled.se(shape)


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
    v = [x for x in (crossing(*d[name][:2], rising) for d in deposits) if x is not None]
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
            se_v, se_w = selection.standard_error((e, z)), selection.standard_error((z, e))
            if se_v is not None and se_w is not None:
                chi2.append(diffs[-1] ** 2 / (se_v ** 2 + se_w ** 2))
    return {"pairs": len(diffs),
            "mean_difference": float(np.mean(diffs)) if diffs else None,
            "rms_difference": float(np.sqrt(np.mean(np.square(diffs)))) if diffs else None,
            "chi2_per_pair": float(np.mean(chi2)) if chi2 else None,
            "pairs_with_errors": len(chi2)}


def constant_eta(selection, rng):
    """the maximum over zeta along each eta with three values of zeta or more"""
    out = []
    for eta in sorted({e for e, _ in selection.phi}):
        points = sorted((z, (e, z)) for (e, z) in selection.phi if e == eta)
        if len(points) >= 3:
            out.append(dict({"eta": eta, "zetas": len(points)},
                            **selection.maximum(points, rng)))
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
                    h: histogram_difference(deposits, reference.shapes[shape],
                                            HISTOGRAMS[h][0])
                    for h in HISTOGRAMS}))
        out.append(entry)
    return out


def load_deposits(results, n):
    """the deposits at N in in.deposit's default box, each with its folder and its two
    histograms (theta, P)"""
    return [d for d in load_all_deposits(results) if int(d["N"]) == n and not d.get("width")]


def load_all_deposits(results):
    """every deposit of deposits.csv, each with its folder, its two histograms (theta, P) and
    its measuring slab's thickness"""
    deposits = read_csv(os.path.join(results, "deposits.csv"))
    for d in deposits:
        d["folder"] = os.path.join(results, "points", d["point"], "s%s" % d["seed"])
        for name, _, _ in HISTOGRAMS.values():
            d[name] = read_histo(os.path.join(d["folder"], name + ".dat"))
        path = os.path.join(d["folder"], "packing.dat")
        pk = read_packing(path) if os.path.exists(path) else {}
        d["slab"] = pk["zhi"] - pk["zlo"] if "zhi" in pk else None
    return deposits


def claims(results, law, n):
    rng = np.random.default_rng(20261201)    # one stream, drawn in the order of the keys
    everything = Selection(load_all_deposits(results))
    groups = {}
    for d in everything.deposits:
        if int(d["N"]) == n and not d.get("width"):
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
                    "crossings": crossings(sel), "forces": forces(sel.deposits)}
                   for (dr, name), sel in selections.items() if name != law]
    out["forces"] = forces(base.deposits)
    out["force_mirror"] = mirror(base.deposits)
    out["depth"] = depth_claims(everything, law, n)
    out["verdicts"] = verdicts(out, selections, law)
    return out


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
