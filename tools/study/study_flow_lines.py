"""The flow solve's permeability along the study's lines (doc/study.md, "Permeability along the
lines"; the solves: tools/pores/pore_flow_lines.py, one results/flow_lines/<run>.json per
deposit).

    solved(folder)    -> every deposit's json in pore_flow_lines.py's output folder
    deposit_row(json) -> the deposit's k_zz, k_xx, k_xx / k_zz, k_zz / k_KC, k_xx / k_KC with
                         their errors, and its cost (deposit_cost)
    shape_means(rows) -> per shape the seeds' mean of each quantity and its two errors
    verdicts(means)   -> each shape against the spheres (k, k / k_KC) and against isotropy
                         (k_xx / k_zz)
    prolate_against_oblate(means) -> at equal aspect ratio, the prolate shape less the oblate
    line_trends(means) -> the slope of each quantity against a/c along each line
    scatter_check(rows) -> each shape's own seed scatter and whether the shapes scatter alike
    summary(verdicts) -> per quantity the shapes of each verdict, undecided ones last

Errors. A deposit's k carries the error of the extrapolation to a vanishing voxel
(tools/pores/pore_flow_fit.py): the bracket's half-width (where in the bracket the limit lies,
a bias the seeds of a shape share) plus the line's and the offsets' standard errors (noise of
each deposit, like the box's sampling: part of the seeds' scatter). A shape's mean has a
statistical error, the seeds' relative SD pooled per group of shapes as the study pools
(study_stats.pooled_groups) / sqrt(seeds), and a systematic one, the rms of its deposits'
relative half-widths, not reduced by averaging. A verdict needs SIGMA standard errors of the
two combined, as the normal equivalent of Student's t with Welch-Satterthwaite's effective
degrees of freedom (study_stats.effective_dof: the pooled SD's, the bias a bound with none of
its own; study_stats.decide); without an error estimate it is undecided.
"""
import glob
import json
import math
import os

import numpy as np
from scipy import stats

from study_stats import (LINES, NOT_A_LINE, decide, effective_dof, line_fit, on_line,
                         pooled_groups, seeds_needed, significance)

# quantity: (the deposit's bias of it, what the verdict compares it with)
QUANTITIES = {"k_zz": ("k_zz_bias", "spheres"), "k_xx": ("k_xx_bias", "spheres"),
              "anisotropy": ("anisotropy_bias", "isotropy"),
              "k_zz_over_kozeny_carman": ("k_zz_bias", "spheres"),
              "k_xx_over_kozeny_carman": ("k_xx_bias", "spheres")}
EXTRAPOLATED = {"k_xx": "xx", "k_zz": "zz", "anisotropy": "anisotropy_xx_zz"}
SPHERES = (1.0, 1.0)


def solved(folder):
    """every deposit's json in folder (pore_flow_lines.py's OUT), whichever command solved it"""
    out = []
    for path in sorted(glob.glob(os.path.join(folder, "*.json"))):
        with open(path) as f:
            r = json.load(f)
        if "flow" in r:
            out.append(r)
    return out


def deposit_row(r):
    """one deposit's row from pore_flow_lines.py's json: k in d^2, each with its error"""
    k = r["flow"]
    if "ratio_to_kozeny_carman" not in k:
        raise ValueError("%s: solved before the flow domain's own medium was recorded: run "
                         "tools/pores/pore_flow_lines.py on it again" % r.get("folder"))
    ratio = k["ratio_to_kozeny_carman"]    # over the flow domain's own k_KC
    row = {"eta": r["eta"], "zeta": r["zeta"], "seed": r["seed"], "porosity": r["porosity"],
           "domain_porosity": k["medium"]["porosity"],
           "k_xx": k["xx"], "k_xx_error": k.get("xx_error", ""),
           "k_yy": k.get("yy", ""), "k_zz": k["zz"], "k_zz_error": k.get("zz_error", ""),
           "anisotropy": k["anisotropy_xx_zz"],
           "anisotropy_error": k.get("anisotropy_xx_zz_error", ""),
           "k_zz_over_kozeny_carman": ratio["zz"], "k_xx_over_kozeny_carman": ratio["xx"]}
    for q, key in EXTRAPOLATED.items():    # the bracket's half-width
        e = k.get("extrapolation", {}).get(key)
        row[q + "_bias"] = "" if e is None else 0.5 * abs(e["k0_fixed_p"] - e["k_finest"])
    row.update(deposit_cost(k))
    return row


def deposit_cost(flow):
    """seconds summed over the deposit's solves (each resolution, direction and offset), from
    the solves themselves, so that a run resumed solve by solve counts each solve once:
    solve_seconds the wall time with the meshing (and any wait for a shared machine),
    solver_cpu_seconds simpleFoam's CPU time; "" without the solves"""
    resolutions = flow.get("resolutions")
    return {name: "" if not resolutions else sum(sum(r[key].values()) for r in resolutions)
            for name, key in (("solve_seconds", "seconds"),
                              ("solver_cpu_seconds", "solver_cpu_seconds"))}


def relative_bias(row, q):
    """the deposit's extrapolation bias of q relative to its value (None: one voxel only)"""
    bias_key = QUANTITIES[q][0]
    bias = row.get(bias_key)
    if bias in ("", None):
        return None
    return float(bias) / float(row[bias_key[:-len("_bias")]])


def by_shape(rows):
    """{(eta, zeta): [rows]}"""
    shapes = {}
    for r in rows:
        shapes.setdefault((float(r["eta"]), float(r["zeta"])), []).append(r)
    return shapes


def relative(rs, q):
    """the seeds' values of q over their mean"""
    values = np.array([r[q] for r in rs], float)
    return values / values.mean()


def shape_means(rows):
    """{(eta, zeta): {"seeds": [...], q: {mean, stat, sys, dof}}, "pooled": {q: {group: (sd,
    dof)}}}: stat the seeds' standard error (relative SD pooled per group of shapes), sys the
    rms relative extrapolation bias, both times the mean"""
    shapes = by_shape(rows)
    out = {"pooled": {}}
    for s, rs in shapes.items():
        out[s] = {"seeds": sorted(int(r["seed"]) for r in rs)}
    for q in QUANTITIES:
        groups, of_shape = pooled_groups({s: list(relative(rs, q)) for s, rs in shapes.items()})
        out["pooled"][q] = {g: (e["sd"], e["dof"]) for g, e in groups.items()}
        for s, rs in shapes.items():
            sd, dof = out["pooled"][q][of_shape[s]]
            mean = float(np.mean([r[q] for r in rs]))
            biases = [relative_bias(r, q) for r in rs]
            sys = (None if None in biases else
                   mean * math.sqrt(np.mean(np.square(biases))))
            stat = None if sd is None else mean * sd / math.sqrt(len(rs))
            out[s][q] = {"mean": mean, "stat": stat, "sys": sys, "dof": dof}
    return out


def scatter_check(rows):
    """{q: {"own": {shape: the seeds' relative SD}, "bartlett_p": p, "identical": [shapes]}}:
    whether the shapes with two seeds or more scatter alike, as pooling their SDs assumes
    (Bartlett's test of equal variances of the seeds' values relative to their shape's mean;
    None below two shapes, and where a shape's seeds agree exactly, listed in "identical": a
    deposit counted twice?)"""
    out = {}
    for q in QUANTITIES:
        own = {s: relative(rs, q) for s, rs in by_shape(rows).items() if len(rs) > 1}
        identical = sorted(s for s, v in own.items() if v.std() == 0)
        p = (float(stats.bartlett(*own.values()).pvalue)
             if len(own) > 1 and not identical else None)
        out[q] = {"own": {s: float(v.std(ddof=1)) for s, v in own.items()}, "bartlett_p": p,
                  "identical": identical}
    return out


def seeds_text(means, shapes):
    """the seeds per shape of the shapes, as 2 or 1-2"""
    return "-".join(sorted({"%d" % len(means[s]["seeds"]) for s in shapes}))


def verdicts(means):
    """[(shape, q, decision)]: k and k / k_KC against the spheres', k_xx / k_zz against 1"""
    out = []
    shapes = sorted(s for s in means if s != "pooled")
    for q, (_, against) in QUANTITIES.items():
        for s in shapes:
            if against == "isotropy":
                out.append((s, q, compare(means, q, s, None)))
            elif s != SPHERES and SPHERES in means:
                out.append((s, q, compare(means, q, s, SPHERES)))
    return out


def prolate_against_oblate(means):
    """[(aspect ratio, q, decision)]: at each aspect ratio solved on both lines, the prolate
    shape (a, 1) less the oblate one (1, a)"""
    ratios = sorted(s[0] for s in means if s != "pooled" and s[1] == 1.0 and s[0] > 1.0
                    and (1.0, s[0]) in means)
    return [(a, q, compare(means, q, (a, 1.0), (1.0, a), ("higher on the prolate line",
                                                           "higher on the oblate line")))
            for q in QUANTITIES for a in ratios]


def line_trends(means):
    """[(line, q, trend)]: the weighted straight line of q against a/c = eta zeta over the
    line's shapes (the spheres included; 3 or more with errors), its slope with the
    statistical and systematic parts propagated apart, and the verdict (study_stats.line_fit:
    beyond-chance scatter about the line scales the error by the Birge ratio)"""
    out = []
    for line in LINES:
        shapes = sorted((s for s in means if s != "pooled" and on_line(line, *s)),
                        key=lambda s: s[0] * s[1])
        for q in QUANTITIES:
            if len(shapes) < 3 or any(means[s][q]["stat"] is None or means[s][q]["sys"] is None
                                      for s in shapes):
                continue
            m = [means[s][q] for s in shapes]
            x = np.array([s[0] * s[1] for s in shapes])
            se = np.array([math.hypot(p["stat"], p["sys"]) for p in m])
            fit = line_fit(x, [p["mean"] for p in m], se)
            w = se ** -2    # the slope is sum c_i y_i
            xm = np.sum(w * x) / w.sum()
            c = w * (x - xm) / np.sum(w * (x - xm) ** 2)
            stat = float(np.sqrt(np.sum((c * [p["stat"] for p in m]) ** 2)))
            sys = float(np.sqrt(np.sum((c * [p["sys"] for p in m]) ** 2)))
            birge = fit["se"] / fit["se_fit"]
            dof = effective_dof(stat, min(p["dof"] for p in m), sys)
            if fit["lack_of_fit"]:
                dof = min(dof or math.inf, fit["dof_lack_of_fit"])
            fewest = min(len(means[s]["seeds"]) for s in shapes)
            seeds = seeds_text(means, shapes)
            need = (None if fit["lack_of_fit"] else
                    seeds_needed(fit["slope"], [(stat, fewest)], sys))
            out.append((line, q, dict(fit, stat=stat * birge, sys=sys * birge,
                                      shapes=[list(s) for s in shapes],
                                      **decide(fit["slope"] / fit["se"], need, seeds,
                                               "grows with a/c", "falls with a/c", dof,
                                               why_no_seeds=NOT_A_LINE
                                               if fit["lack_of_fit"] else None))))
    return out


def compare(means, q, s, ref, words=None):
    """shape s's mean of q less ref's (None: less 1, isotropy), with its statistical and
    systematic errors and the verdict"""
    m = means[s][q]
    parts, biases = [(m["stat"], len(means[s]["seeds"]))], [m["sys"]]
    dof, compared = m["dof"], [s]
    if ref is None:
        diff = m["mean"] - 1.0
        words = words or ("k_xx > k_zz", "k_xx < k_zz")
    else:
        r = means[ref][q]
        diff = m["mean"] - r["mean"]
        parts.append((r["stat"], len(means[ref]["seeds"])))
        biases.append(r["sys"])
        dof, compared = min(dof, r["dof"]), [s, ref]
        words = words or ("higher than the spheres'", "lower than the spheres'")
    known = None not in biases and all(p[0] is not None for p in parts)
    stat = math.sqrt(sum(p[0] ** 2 for p in parts)) if known else None
    sys = math.sqrt(sum(b ** 2 for b in biases)) if known else 0.0
    seeds = seeds_text(means, compared)
    d = decide(significance(diff, stat, sys), seeds_needed(diff, parts, sys), seeds, *words,
               effective_dof(stat, dof, sys))
    d.update(difference=diff, stat=stat, sys=sys)
    return d


def summary(decisions):
    """{q: [(verdict, [shapes])]} in QUANTITIES' order: the shapes grouped by their verdict on
    q (by_verdict)"""
    per_q = {}
    for s, q, d in sorted(decisions, key=lambda v: v[0]):
        per_q.setdefault(q, []).append((s, d))
    return {q: by_verdict(per_q[q]) for q in QUANTITIES if q in per_q}


def by_verdict(decisions):
    """[(verdict, [keys])] from [(key, decision)]: the decided verdicts first in the order
    met, the undecided ones as one group last"""
    groups = {}
    for key, d in decisions:
        groups.setdefault("undecided" if d["verdict"].startswith("undecided")
                          else d["verdict"], []).append(key)
    return sorted(groups.items(), key=lambda g: g[0] == "undecided")


def line_of(shape):
    """the names of the lines the shape lies on (the spheres lie on all three)"""
    return [name for name in LINES if on_line(name, *shape)]
