"""The contact forces of the study (claims.json `forces`; doc/study.md, "Contact forces").

The paper's abstract: the contact forces "are increasingly preferred along the vertical
direction as the shape deviates from a sphere". Each deposit since the force measures
(packing.dat's a_n, a_f, K0; doc/howto_deposit.md, "Forces") gives, in its measuring slab:

* a_n: Rothenburg and Bathurst's anisotropy of the contact normals (> 0: normals
  preferably vertical; doc/compute_contact_histo.rst defines it and a_f);
* a_f: the anisotropy of the mean normal-force magnitude over the directions (> 0: the
  vertical contacts carry more than their share);
* a_n + a_f: the force-weighted fabric's anisotropy, the forces' preference for the vertical;
* K0 = (sigma_xx + sigma_yy) / (2 sigma_zz) of the slab (packing.dat's).

Only deposits whose packing.dat gives these as means over a window after rest count
(`window_steps` > 0); before the window a deposit wrote one step's values of a bed that still
rings (+-3.5 % in sigma_zz), and those snapshots are left out here (their phi, Z and
histograms are not).

Along each line of shapes of one law at delta_r 0 (the default law's in claims.json `forces`,
another law's in its `laws` entry), spheres included: the diagonal
eta = zeta, the prolate line zeta = 1 and the oblate line eta = 1, with the seed SD pooled per
group of shapes over every shape of the selection (tools/study/study_stats.py; one error per shape,
whichever line it is read on): per shape the mean and standard error of each; the weighted
slope of each against the total aspect ratio a/c = eta zeta (its error scaled by the Birge
ratio where the shapes scatter about the line beyond chance: study_stats.line_fit), the
thinnest shape against the roundest and, where a measure saturates, against the shape where
it is largest. "The force anisotropy grows with asphericity" is the slope of a_n + a_f;
"faster than the geometric one" is the slope of a_f (the force-weighted anisotropy less the
geometric a_n, per deposit). `mirror`: the correlation across deposits of K0 with a_f, each
taken about its shape's mean (seed by seed).
"""
import math

import numpy as np
from scipy import stats

from study_stats import LINES, NOT_A_LINE, Pooled, decide, line_fit, on_line, seeds_needed

MEASURES = ("a_n", "a_f", "a_total", "K0")
NAMES = {"a_n": "contact normals a_n", "a_f": "normal-force magnitude a_f",
         "a_total": "force-weighted fabric a_n + a_f",
         "K0": "K0 = (sigma_xx + sigma_yy) / (2 sigma_zz)"}


def measured(deposit):
    """the deposit's force measures, or None if it has no window means of them (it predates
    the measures, or gave one step's snapshot)"""
    try:
        a_n, a_f, k0 = (float(deposit[k]) for k in ("a_n", "a_f", "K0"))
        if not float(deposit.get("window_steps") or 0) > 0:
            return None
    except (KeyError, TypeError, ValueError):
        return None
    if not all(math.isfinite(v) for v in (a_n, a_f, k0)):
        return None
    return {"a_n": a_n, "a_f": a_f, "a_total": a_n + a_f, "K0": k0}


def trend(pooled, shapes):
    """the slope of a measure against a/c over the shapes, and the last shape against the
    first (the roundest), each with its verdict"""
    x = [e * z for e, z in shapes]
    seeds = sorted({len(pooled.values[s]) for s in shapes})
    seeds = "%d" % seeds[0] if len(seeds) == 1 else "%d-%d" % (seeds[0], seeds[-1])
    dof = min(pooled.dof(s) for s in shapes)
    fit = line_fit(x, [pooled.mean(s) for s in shapes], [pooled.se(s) for s in shapes])
    if fit["lack_of_fit"]:
        dof = min(dof, fit["dof_lack_of_fit"])
    fewest = min(len(pooled.values[s]) for s in shapes)
    # seeds shrink the points' errors, not their scatter about a line they do not follow
    need = None if fit["lack_of_fit"] else seeds_needed(fit["slope"], [(fit["se"], fewest)])
    out = {"slope_per_unit_a/c": dict(
        fit, **{"from_a/c": x[0], "to_a/c": x[-1], "points": len(x)},
        **decide(fit["slope"] / fit["se"], need, seeds, "grows with a/c", "falls with a/c",
                 dof, why_no_seeds=NOT_A_LINE if fit["lack_of_fit"] else None))}
    out["thinnest_minus_roundest"] = difference(pooled, shapes[-1], shapes[0], seeds)
    # a trend that peaks: the largest value between the ends, above both, against each end
    top = max(shapes[1:-1], key=pooled.mean, default=None)
    if top is not None and pooled.mean(top) > max(pooled.mean(shapes[0]),
                                                  pooled.mean(shapes[-1])):
        out["thinnest_minus_largest"] = difference(pooled, shapes[-1], top, seeds)
        out["largest_minus_roundest"] = difference(pooled, top, shapes[0], seeds)
    # and one that dips: the lowest value between them against both ends
    bottom = min(shapes[1:-1], key=pooled.mean, default=None)
    if bottom is not None and pooled.mean(bottom) < min(pooled.mean(shapes[0]),
                                                         pooled.mean(shapes[-1])):
        out["thinnest_minus_smallest"] = difference(pooled, shapes[-1], bottom, seeds)
        out["smallest_minus_roundest"] = difference(pooled, bottom, shapes[0], seeds)
    return out


def shape_of_trend(t):
    """a measure's course along a line from its trend entry: "not monotone" where it rises to
    its largest value and falls after it (or dips and rises), each step decided; else the
    slope's verdict"""
    for first, then, up, down in (("largest_minus_roundest", "thinnest_minus_largest",
                                   "rises", "falls"),
                                  ("smallest_minus_roundest", "thinnest_minus_smallest",
                                   "falls", "rises")):
        a, b = t.get(first), t.get(then)
        if a and b and not a["verdict"].startswith("undecided") and \
                not b["verdict"].startswith("undecided"):
            turn, end = a["shapes"][0], b["shapes"][0]
            return ("not monotone: %s to a/c %g (%+.3f +- %.3f), then %s to a/c %g "
                    "(%+.3f +- %.3f)" % (up, turn[0] * turn[1], a["difference"], a["se"], down,
                                         end[0] * end[1], b["difference"], b["se"]))
    slope, ends = t["slope_per_unit_a/c"]["verdict"], t["thinnest_minus_roundest"]
    if not slope.startswith("undecided") and ends["verdict"].startswith("undecided"):
        return "slope: %s, but the thinnest against the roundest: %+.3f +- %.3f, %s" % (
            slope, ends["difference"], ends["se"], ends["verdict"])
    return slope


def difference(pooled, a, b, seeds):
    """shape a's mean less shape b's with its error and verdict"""
    d, err = pooled.mean(a) - pooled.mean(b), math.hypot(pooled.se(a), pooled.se(b))
    need = seeds_needed(d, [(pooled.se(a), len(pooled.values[a])),
                            (pooled.se(b), len(pooled.values[b]))])
    return dict({"shapes": [list(a), list(b)], "difference": d, "se": err},
                **decide(d / err, need, seeds, "larger at a/c %g" % (a[0] * a[1]),
                         "smaller at a/c %g" % (a[0] * a[1]), min(pooled.dof(a), pooled.dof(b))))


def line_forces(measures, pooled, line):
    """one line's entry of `forces`, or None when fewer than 3 of its shapes have two
    deposits with the force measures; pooled: {measure: Pooled} over the selection"""
    shapes = sorted(s for s in pooled["K0"].values if on_line(line, *s))
    if len(shapes) < 3:
        return None
    rows = []
    for s in shapes:
        row = {"eta": s[0], "zeta": s[1], "a/c": s[0] * s[1], "seeds": len(measures[s])}
        for q, p in pooled.items():
            row[q] = {"mean": p.mean(s), "se": p.se(s)}
        rows.append(row)
    # a_f is the coefficient of the second-order form of fbar(theta) only where that form's
    # E(theta) = (1 + a_n (3 cos^2 theta - 1)) / (4 pi) is a distribution: a_n < 1 (at a_n >= 1
    # it is negative near pi/2); its trend runs over those shapes
    holds = [s for s in shapes if pooled["a_n"].mean(s) < 1.0]
    trends = {q: trend(p, shapes) for q, p in pooled.items() if q != "a_f"}
    if len(holds) >= 3:
        trends["a_f"] = trend(pooled["a_f"], holds)
    return {"line": line, "deposits": sum(len(measures[s]) for s in shapes),
            "per_shape": rows, "a_n_at_least_1": [list(s) for s in shapes if s not in holds],
            "errors": {q: p.groups for q, p in pooled.items()},
            "trends": {q: trends[q] for q in MEASURES if q in trends}}


def by_shape(deposits):
    """{shape: [force measures per deposit]} over the deposits with window means"""
    out = {}
    for d in deposits:
        m = measured(d)
        if m is not None:
            out.setdefault((float(d["eta"]), float(d["zeta"])), []).append(m)
    return out


def forces(deposits):
    """claims.json `forces` from the deposits of one law and delta_r (dicts with
    eta, zeta and the columns of deposits.csv): {line: entry} for the lines of LINES that have
    3 shapes with two deposits each; None when no line has. The seed SDs are pooled over
    every shape with two deposits, so a shape on two lines has one error"""
    shapes = {s: v for s, v in by_shape(deposits).items() if len(v) >= 2}
    pooled = {q: Pooled({s: [m[q] for m in v] for s, v in shapes.items()}) for q in MEASURES}
    lines = {line: line_forces(shapes, pooled, line) for line in LINES} if shapes else {}
    return {k: v for k, v in lines.items() if v is not None} or None


def mirror(deposits, a="K0", b="a_f"):
    """the Pearson correlation across deposits of a with b, each about its shape's mean (the
    shape's trend taken out: seed by seed), over the shapes with two deposits or more: r, the
    deposits and shapes, and the two-sided p of r = 0 (t with deposits - shapes - 1 dof);
    None with fewer than 3 degrees of freedom"""
    shapes = {s: v for s, v in by_shape(deposits).items() if len(v) >= 2}
    da, db = [], []
    for v in shapes.values():
        x, y = np.array([m[a] for m in v]), np.array([m[b] for m in v])
        da += list(x - x.mean())
        db += list(y - y.mean())
    dof = len(da) - len(shapes) - 1
    if dof < 3 or not np.std(da) or not np.std(db):
        return None
    r = float(np.corrcoef(da, db)[0, 1])
    t = r * math.sqrt(dof / max(1e-300, 1 - r * r))
    return {"r": r, "deposits": len(da), "shapes": len(shapes), "dof": dof,
            "p": float(2 * stats.t.sf(abs(t), dof)), "quantities": [a, b]}
