"""The contact forces of the study (claims.json `forces`; doc/study.md, "Contact forces").

The paper's abstract: the contact forces "are increasingly preferred along the vertical
direction as the shape deviates from a sphere". Each deposit since the force measures
(packing.dat's a_n, a_f, K0; doc/howto_deposit.md, "Forces") gives, in its measuring slab:

* a_n: Rothenburg and Bathurst's anisotropy of the contact normals (> 0: normals
  preferably vertical; doc/compute_contact_histo.rst defines it and a_f);
* a_f: the anisotropy of the mean normal-force magnitude over the directions (> 0: the
  vertical contacts carry more than their share);
* a_n + a_f: the force-weighted fabric's anisotropy, the forces' preference for the vertical;
* K0 = sigma_xx / sigma_zz of the slab.

Along the diagonal eta = zeta (spheres included) of the default law at delta_r 0, with the
seed SD pooled per group of shapes (tools/study_stats.py), over the deposits that have them:
per shape the mean and standard error of each; the weighted slope of each against the total
aspect ratio a/c = eta zeta, and the thinnest shape against the roundest. "The force
anisotropy grows with asphericity" is the slope of a_n + a_f; "faster than the geometric
one" is the slope of a_f (the force-weighted anisotropy less the geometric a_n, per deposit).
"""
import math

from study_stats import Pooled, decide, seeds_needed, weighted_slope

MEASURES = ("a_n", "a_f", "a_total", "K0")
NAMES = {"a_n": "contact normals a_n", "a_f": "normal-force magnitude a_f",
         "a_total": "force-weighted fabric a_n + a_f", "K0": "K0 = sigma_xx / sigma_zz"}


def measured(deposit):
    """the deposit's force measures, or None if it predates them"""
    try:
        a_n, a_f, k0 = (float(deposit[k]) for k in ("a_n", "a_f", "K0"))
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
    slope, se = weighted_slope(x, [pooled.mean(s) for s in shapes],
                               [pooled.se(s) for s in shapes])
    fewest = min(len(pooled.values[s]) for s in shapes)
    out = {"slope_per_unit_a/c": dict(
        {"slope": slope, "se": se, "from_a/c": x[0], "to_a/c": x[-1], "points": len(x)},
        **decide(slope / se, seeds_needed(slope, [(se, fewest)]), seeds, "grows with a/c",
                 "falls with a/c", dof))}
    a, b = shapes[-1], shapes[0]
    d, err = pooled.mean(a) - pooled.mean(b), math.hypot(pooled.se(a), pooled.se(b))
    need = seeds_needed(d, [(pooled.se(a), len(pooled.values[a])),
                            (pooled.se(b), len(pooled.values[b]))])
    out["thinnest_minus_roundest"] = dict(
        {"shapes": [list(a), list(b)], "difference": d, "se": err},
        **decide(d / err, need, seeds, "larger at a/c %g" % x[-1],
                 "smaller at a/c %g" % x[-1], min(pooled.dof(a), pooled.dof(b))))
    return out


def forces(deposits):
    """claims.json `forces` from the deposits of the default law at delta_r 0 (dicts with
    eta, zeta and the columns of deposits.csv); None when no diagonal shape has two of them"""
    by_shape = {}
    for d in deposits:
        m = measured(d)
        e, z = float(d["eta"]), float(d["zeta"])
        if m is not None and e == z:
            by_shape.setdefault((e, z), []).append(m)
    shapes = sorted(s for s, v in by_shape.items() if len(v) >= 2)
    if len(shapes) < 3:
        return None
    pooled = {q: Pooled({s: [m[q] for m in by_shape[s]] for s in shapes}) for q in MEASURES}
    rows = []
    for s in shapes:
        row = {"eta": s[0], "zeta": s[1], "a/c": s[0] * s[1], "seeds": len(by_shape[s])}
        for q, p in pooled.items():
            row[q] = {"mean": p.mean(s), "se": p.se(s)}
        rows.append(row)
    return {"line": "diagonal", "deposits": sum(len(by_shape[s]) for s in shapes),
            "per_shape": rows,
            "errors": {q: p.groups for q, p in pooled.items()},
            "trends": {q: trend(p, shapes) for q, p in pooled.items()}}
