"""The verdicts of the study (claims.json `verdicts`), each with its significance and, where
it is below 3 sigma, the seeds per point a 3-sigma verdict needs (tools/study/study_stats.py):

* `errors`: the pooled seed SD of phi, Z, Q_zz and a_z per group of shapes, per selection;
* `maximum`: the diagonal maximum's position (statistical and fit-window errors) against the
  paper's 1.4 and the golden ratio, for every selection;
* `ridge`: the diagonal maximum against the prolate and oblate maxima, as fitted maxima
  (with the fit-window systematic), between the highest measured points, and at equal a/c
  across the maxima (the diagonal's shapes against the line interpolated in a/c);
* `asymmetry`: X(eta, zeta) - X(zeta, eta), eta > zeta, over the map's pairs (X = phi, Z, Q_zz,
  a_z): mean, sign count, chi^2;
* `delta_r`: Q_zz, a_z, phi and Z at delta_r > 0 against delta_r = 0 over the shapes, with the
  measuring slab's depth (delta_r is confounded with it at fixed N);
* `fall_back`: Z along the diagonal beyond its highest point;
* `crossings`, `sphere_isotropy`: tools/study/study_histograms.py.
"""
import math

import numpy as np
from scipy import stats

from study_histograms import crossings_both, sphere_isotropy
from study_stats import (CHANCE_P, MIN_DOF, NOT_A_LINE, SIGMA, THIN, decide, equivalent_sigma,
                         line_fit, seeds_needed, sign_test, significance)

GOLDEN = (1 + math.sqrt(5)) / 2
QUANTITIES = ("phi", "Z", "Qzz", "fabric_anisotropy")
PAPER_ANGLES = {"contact_normals": 0.2, "long_axes": 1 / 3}    # pi/5, pi/3
# the paper's words for them (Sec. 4): "slightly higher than theta ~ pi/5", "theta ~ pi/3"
PAPER_WORDS = {"contact_normals": "slightly above pi/5", "long_axes": "about pi/3"}
RIDGE_WINDOW = (1.4, 2.2)    # a/c across the spheroid lines' maxima (the study's set `ridge`)
# the widest step in a/c a line is interpolated over: across the maximum a straight line over
# 0.2 (the map's steps) is biased low by ~0.006 in phi (the prolate line falls 0.0078 from
# a/c 1.8 to 2), over the set ridge's 0.1 steps about a quarter of that
RIDGE_STEP = 0.1 + 1e-9


def selection_name(key):
    return "delta_r %g, %s" % key


def errors(selections):
    return [{"delta_r": dr, "law": law, "quantity": q, "groups": sel.quantity(q).groups}
            for (dr, law), sel in selections.items() for q in QUANTITIES if sel.has(q)]


def maximum_position(m, dof):
    """a fitted maximum's position against 1.4 and the golden ratio: z with its equivalent for
    Student's t with dof (the pooled phi SD's) and "differs from" at 3 sigma, else
    "consistent with" (not excluded; not a confirmation)"""
    if m is None or "x_max" not in m:
        return None
    err = math.hypot(m.get("x_max_sd") or 0.0, m["x_max_sys"])
    out = {"x_max": m["x_max"], "stat": m.get("x_max_sd"), "sys": m["x_max_sys"],
           "fits": {k: f["x_max"] for k, f in m["fits"].items()}, "dof": dof,
           "phi_max": m["phi_max"], "phi_stat": m.get("phi_max_sd"), "phi_sys": m["phi_max_sys"]}
    for key, value, name in (("1.4", 1.4, "1.4"), ("golden_ratio", GOLDEN, "the golden ratio")):
        z = (m["x_max"] - value) / err if err else None
        ze = equivalent_sigma(z, dof)
        out["z_from_" + key], out["z_equivalent_from_" + key] = z, ze
        out["from_" + key] = ("differs from " if ze is not None and abs(ze) >= SIGMA
                              else "consistent with ") + name
    return out


def compare_fits(a, b):
    """fitted heights a - b: nominal difference, bootstrap error, fit-window systematic"""
    windows = [k for k in a["fits"] if k in b["fits"] and a["fits"][k].get("x_max") is not None
               and b["fits"][k].get("x_max") is not None]
    per_window = {k: a["fits"][k]["y_max"] - b["fits"][k]["y_max"] for k in windows}
    stat = math.hypot(a.get("phi_max_sd") or 0.0, b.get("phi_max_sd") or 0.0)
    sys = (max(per_window.values()) - min(per_window.values())) / 2
    return a["phi_max"] - b["phi_max"], stat, sys, per_window


def ridge(maxima, base):
    """the diagonal's maximum against the prolate and oblate ones, both ways"""
    diag = maxima.get("diagonal")
    out = {}
    for name, highest in (("prolate", lambda x: (x, 1.0)), ("oblate", lambda x: (1.0, x))):
        other = maxima.get(name)
        if not diag or not other or "phi_max" not in diag or "phi_max" not in other:
            continue
        d, stat, sys, per_window = compare_fits(diag, other)
        sa, sb = (diag["x_highest"],) * 2, highest(other["x_highest"])
        na, nb = len(base.phi[sa]), len(base.phi[sb])
        seeds = "%d and %d" % (na, nb) if na != nb else "%d" % na
        z = significance(d, stat, sys)
        need = seeds_needed(d, [(diag.get("phi_max_sd"), na), (other.get("phi_max_sd"), nb)],
                            sys)
        yes, no = "the diagonal's is higher", "the %s line's is higher" % name
        dof = min(base.pooled.dof(sa), base.pooled.dof(sb))
        fitted = dict({"difference": d, "stat": stat, "sys": sys, "per_window": per_window},
                      **decide(z, need, seeds, yes, no, dof))
        ea, eb = base.standard_error(sa), base.standard_error(sb)
        dh = base.pooled.mean(sa) - base.pooled.mean(sb)
        se = math.hypot(ea, eb) if ea is not None and eb is not None else None
        z = significance(dh, se)
        need = seeds_needed(dh, [(ea, na), (eb, nb)])
        out[name] = {"fitted": fitted, "highest": dict(
            {"diagonal": list(sa), "other": list(sb), "difference": dh, "se": se},
            **decide(z, need, seeds, yes, no, dof))}
        equal = equal_aspect(base, name, yes, no)
        if equal:
            out[name]["equal_aspect"] = equal
    return out


def equal_aspect(base, name, yes, no):
    """phi on the diagonal less phi on a spheroid line at the same total aspect ratio a/c,
    over the diagonal's shapes in the window RIDGE_WINDOW: the line's phi interpolated
    linearly in a/c between its two neighbouring shapes (their errors propagated) where they
    are at most RIDGE_STEP apart; per shape and their mean (mean_of_differences)"""
    phi = base.quantity("phi")
    line = [(x, s) for x, s in base.line(name) if phi.se(s) is not None]
    rows, shapes = [], []
    for x, s in base.line("diagonal"):
        ac = x * x
        if not RIDGE_WINDOW[0] <= ac <= RIDGE_WINDOW[1] or phi.se(s) is None:
            continue
        k = next((k for k in range(1, len(line)) if line[k - 1][0] <= ac <= line[k][0]), None)
        if k is None:
            continue
        (x0, s0), (x1, s1) = line[k - 1], line[k]
        if x1 - x0 > RIDGE_STEP:
            continue
        w = (ac - x0) / (x1 - x0)
        at = (1 - w) * phi.mean(s0) + w * phi.mean(s1)
        se = math.hypot((1 - w) * phi.se(s0), w * phi.se(s1))
        var = ((1 - w) * phi.sd(s0)) ** 2 + (w * phi.sd(s1)) ** 2 + phi.sd(s) ** 2
        rows.append((phi.mean(s) - at, math.hypot(phi.se(s), se), var,
                     min(phi.dof(s), phi.dof(s0), phi.dof(s1))))
        shapes.append({"diagonal": list(s), "a/c": ac, "between": [list(s0), list(s1)],
                       "difference": rows[-1][0], "se": rows[-1][1]})
    if not rows:
        return None
    counts = sorted({len(base.phi[tuple(r["diagonal"])]) for r in shapes})
    dof = min(base.pooled.dof(tuple(r["diagonal"])) for r in shapes)
    mean = mean_of_differences(rows, "-".join("%d" % c for c in (counts[0], counts[-1]))
                               if len(counts) > 1 else "%d" % counts[0], dof, yes, no,
                               [tuple(r["diagonal"]) for r in shapes])
    return {"window_a/c": list(RIDGE_WINDOW), "per_shape": shapes, "mean": mean}


def mean_of_differences(rows, seeds, dof, yes, no, shapes=None, unit="shapes"):
    """rows [(difference, se, var at one seed[, dof of se, else dof])]: the mean over the
    shapes, its error, its significance (Student's t with dof, the fewest of the pooled SDs'),
    the sign test, chi^2 and the verdict (with the seeds per point a 3-sigma mean needs).

    Where the differences scatter about their mean more than their errors allow (chi^2 about
    the mean above its n - 1 degrees of freedom), the mean's error is scaled by the Birge
    ratio sqrt(chi^2 / (n - 1)) and taken with n - 1 degrees of freedom. Where that scatter is
    beyond chance (p < CHANCE_P, 3 sigma) the effect depends on the shape and a mean over
    shapes answers no question: the verdict is then each shape's own (`per_shape`, its
    difference against its own error; shapes: their (eta, zeta), in the order of rows)"""
    d = np.array([r[0] for r in rows])
    n, dof0 = len(rows), dof
    within = math.sqrt(sum(r[1] ** 2 for r in rows)) / n
    var1 = sum(r[2] for r in rows) / n ** 2
    mean = float(d.mean())
    chi2_about_mean = float(sum(((r[0] - mean) / r[1]) ** 2 for r in rows))
    birge = math.sqrt(chi2_about_mean / (n - 1)) if n > 1 else 1.0
    p_scatter = float(stats.chi2.sf(chi2_about_mean, n - 1)) if n > 1 else None
    se, between = within, 0.0
    if birge > 1:
        se, dof = within * birge, min(dof, n - 1) if dof else n - 1
        between = within * math.sqrt(birge ** 2 - 1)
    z = significance(mean, se)
    chi2 = float(sum((r[0] / r[1]) ** 2 for r in rows))
    k, m, p = sign_test(d)
    need = seeds_needed(mean, [(within, var1 / within ** 2)], between)   # within^2 seeds = var1
    out = dict({"n": n, "mean": mean, "se": se, "se_within": within,
                "birge_ratio": birge, "positive": k, "nonzero": m,
                "sign_p": p, "chi2": chi2, "chi2_p": float(stats.chi2.sf(chi2, n)),
                "chi2_about_mean": chi2_about_mean, "chi2_about_mean_p": p_scatter,
                "sd_over_shapes": float(d.std(ddof=1)) if n > 1 else None, "seeds": seeds},
               **decide(z, need, seeds, yes, no, dof))
    out["per_shape"] = [dict({"shape": list(shapes[i]) if shapes else None,
                              "difference": r[0], "se": r[1]},
                             **decide(r[0] / r[1], seeds_needed(r[0], [(math.sqrt(r[2]), 1)]),
                                      seeds, yes, no, r[3] if len(r) > 3 else dof0))
                        for i, r in enumerate(rows)]
    each = {r["verdict"] for r in out["per_shape"]}
    if p_scatter is not None and p_scatter < CHANCE_P:
        out["mean_verdict"] = out["verdict"]
        out["verdict"] = depends_on_shape(out["per_shape"], yes, no, chi2_about_mean, n, unit)
        out["seeds_needed"] = None
    elif out["verdict"].startswith("undecided") and len(each) == 1 and each <= {yes, no}:
        # the mean's error carries the shapes' scatter; each shape alone is decided, one way
        out["mean_verdict"] = out["verdict"]
        out["verdict"] = "%s in each of the %d %s" % (each.pop(), n, unit)
        out["seeds_needed"] = None
    return out


def depends_on_shape(per_shape, yes, no, chi2, n, unit):
    """the verdict of a mean over shapes that disagree: how many shapes are decided each way"""
    up = sum(1 for r in per_shape if r["verdict"] == yes)
    down = sum(1 for r in per_shape if r["verdict"] == no)
    parts = ["%s in %d" % (yes, up)] * bool(up) + ["%s in %d" % (no, down)] * bool(down)
    parts += ["undecided in %d" % (n - up - down)] * bool(n - up - down)
    return ("depends on shape (the shapes scatter beyond chance, chi^2 %.0f on %d dof): %s of "
            "%d %s" % (chi2, n - 1, ", ".join(parts), n, unit))


def asymmetry(base):
    """X(eta, zeta) - X(zeta, eta) with eta > zeta, over the pairs of the map"""
    out = {}
    for q in (q for q in QUANTITIES if base.has(q)):
        pooled = base.quantity(q)
        rows, pairs = [], []
        for (e, z) in pooled.values:
            if e > z and (z, e) in pooled.values:
                a, b = (e, z), (z, e)
                if pooled.se(a) is None or pooled.se(b) is None:
                    continue
                rows.append((pooled.mean(a) - pooled.mean(b),
                             math.hypot(pooled.se(a), pooled.se(b)),
                             pooled.sd(a) ** 2 + pooled.sd(b) ** 2,
                             min(pooled.dof(a), pooled.dof(b))))
                pairs.append([e, z])
        if not rows:
            continue
        dof = min(g["dof"] for g in pooled.groups.values())
        m = mean_of_differences(rows, "2-3", dof, "asymmetric: larger for eta > zeta",
                                "asymmetric: larger for eta < zeta", pairs, "pairs")
        k = int(np.argmax([abs(r[0]) for r in rows]))
        m["largest"] = {"pair": pairs[k], "difference": rows[k][0], "se": rows[k][1]}
        out[q] = m
    return out


def depth(selection):
    """the measuring slab: thickness (d) and solid per area phi * thickness over deposits"""
    if any(d.get("slab") is None for d in selection.deposits):
        return None
    t = np.array([d["slab"] for d in selection.deposits])
    solid = np.array([float(d["phi"]) * d["slab"] for d in selection.deposits])
    return {"thickness_mean": float(t.mean()), "thickness_range": [float(t.min()),
                                                                   float(t.max())],
            "solid_per_area_mean": float(solid.mean())}


def shape_effects(sel, base, label, shapes=None, quantities=QUANTITIES):
    """per quantity: X(sel) - X(base) over the shapes both have (of `shapes` if given; Q_zz
    without the sphere, whose long axis is arbitrary), their mean and its verdict ("larger" or
    "smaller" + label)"""
    out = {}
    for q in (q for q in quantities if sel.has(q) and base.has(q)):
        p, p0 = sel.quantity(q), base.quantity(q)
        common = [s for s in p.values if s in p0.values and (shapes is None or s in shapes)
                  and not (q == "Qzz" and s == (1.0, 1.0))]
        if not common or any(p.se(s) is None or p0.se(s) is None for s in common):
            continue
        rows = [(p.mean(s) - p0.mean(s), math.hypot(p.se(s), p0.se(s)),
                 p.sd(s) ** 2 + p0.sd(s) ** 2, min(p.dof(s), p0.dof(s))) for s in common]
        counts = sorted({len(v[s]) for v in (p.values, p0.values) for s in common})
        seeds = "%d" % counts[0] if len(counts) == 1 else "%d-%d" % (counts[0], counts[-1])
        dof = min(g["dof"] for g in list(p.groups.values()) + list(p0.groups.values()))
        m = mean_of_differences(rows, seeds, dof, "larger " + label, "smaller " + label,
                                common)
        scale = float(np.mean([abs(p0.mean(s)) for s in common]))
        m["relative"] = m["mean"] / scale if scale else None
        out[q] = m
    return out


def delta_r_effects(selections, law):
    """per delta_r > 0 of the default law and quantity: X(delta_r) - X(0) over the shapes
    present at both"""
    base = selections.get((0.0, law))
    if base is None:
        return []
    return [dict({"delta_r": dr, "depth": depth(sel), "depth_at_0": depth(base)},
                 **shape_effects(sel, base, "at delta_r %g, N fixed" % dr))
            for (dr, name), sel in selections.items() if name == law and dr != 0.0]


def slope_entry(z, shapes):
    """the weighted slope of Z against eta over the shapes (its error scaled by the Birge
    ratio where the points scatter about the line beyond chance), its significance, seeds"""
    fit = line_fit([s[0] for s in shapes], [z.mean(s) for s in shapes],
                   [z.se(s) for s in shapes])
    counts = sorted({len(z.values[s]) for s in shapes})
    seeds = "%d" % counts[0] if len(counts) == 1 else "%d-%d" % (counts[0], counts[-1])
    dof = min(map(z.dof, shapes))
    if fit["lack_of_fit"]:
        dof = min(dof, fit["dof_lack_of_fit"])
    need = None if fit["lack_of_fit"] else seeds_needed(fit["slope"], [(fit["se"], counts[0])])
    return dict(fit, **{"from": shapes[0][0], "to": shapes[-1][0], "points": len(shapes)},
                **decide(fit["slope"] / fit["se"], need, seeds, "rises", "falls", dof,
                         why_no_seeds=NOT_A_LINE if fit["lack_of_fit"] else None))


def fall_back(sel):
    """Z along eta = zeta: the slope over eta >= 2 (a/c >= 4, chosen before looking) and from
    the highest point on (biased to fall: the highest point is the noisiest upward), the end
    against the highest point and against the highest spheroid"""
    if not sel.has("Z"):
        return None
    z = sel.quantity("Z")
    diag = sorted(s for s in z.values if s[0] == s[1])
    if len(diag) < 3 or any(z.se(s) is None for s in z.values):
        return None
    k = int(np.argmax([z.mean(s) for s in diag]))
    out = {"peak": list(diag[k]), "end": list(diag[-1])}
    thin = [s for s in diag if s[0] * s[1] >= THIN]
    if len(thin) >= 2:
        out["slope_thin"] = slope_entry(z, thin)
    if len(diag) - k >= 2:
        out["slope_from_peak"] = slope_entry(z, diag[k:])
    pairs = {"end_minus_peak": (diag[-1], diag[k])}
    spheroids = [s for s in z.values if (s[0] == 1.0) != (s[1] == 1.0)]
    if spheroids:
        pairs["end_minus_highest_spheroid"] = (diag[-1], max(spheroids, key=z.mean))
    for key, (a, b) in pairs.items():
        if a == b:
            continue
        d, se = z.mean(a) - z.mean(b), math.hypot(z.se(a), z.se(b))
        need = seeds_needed(d, [(z.se(a), len(z.values[a])), (z.se(b), len(z.values[b]))])
        out[key] = dict({"shapes": [list(a), list(b)], "difference": d, "se": se,
                         # the largest fall the data leave open at SIGMA: what "no fall-back"
                         # means where the difference is undecided
                         "largest_fall": max(0.0, SIGMA * se - d)},
                        **decide(d / se, need, len(z.values[a]), "higher", "lower",
                                 min(z.dof(a), z.dof(b))))
    return out


def verdicts(claims, selections, law):
    """the verdicts of claims.json from its maxima and the selections {(delta_r, law):
    study_claims.Selection}"""
    base = selections.get((0.0, law))
    out = {"sigma": SIGMA, "groups": {"min_dof": MIN_DOF, "thin_from_a/c": THIN},
           "errors": errors(selections), "maximum": [], "fall_back": []}
    diagonal_maxima = {(0.0, law): claims["maxima"].get("diagonal")}
    diagonal_maxima.update({(p["delta_r"], law): p["diagonal_maximum"]
                            for p in claims["polydispersity"]["density"]})
    diagonal_maxima.update({(m["delta_r"], m["law"]): m["diagonal_maximum"]
                            for m in claims["laws"]})
    for (dr, name), m in sorted(diagonal_maxima.items()):
        sel = selections.get((dr, name))
        position = maximum_position(m, min(g["dof"] for g in sel.pooled.groups.values())
                                    if sel else None)
        if position:
            out["maximum"].append(dict({"delta_r": dr, "law": name}, **position))
    for (dr, name), sel in selections.items():
        f = fall_back(sel) if dr == 0.0 else None
        if f:
            out["fall_back"].append(dict({"delta_r": dr, "law": name}, **f))
    if base is None:
        return out
    out["ridge"] = ridge(claims["maxima"], base)
    out["asymmetry"] = asymmetry(base)
    out["delta_r"] = delta_r_effects(selections, law)
    out["crossings"] = crossings_both(base, PAPER_ANGLES)
    out["sphere_isotropy"] = {selection_name(k): sphere_isotropy(selections, k)
                              for k in selections if (1.0, 1.0) in selections[k].shapes}
    return out
