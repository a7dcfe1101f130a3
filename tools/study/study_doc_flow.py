"""doc/study.md's permeability along the lines (tools/study/study_doc.py): the flow solve at the
defaults per shape (seeds' mean, statistical +- extrapolation error) and the verdicts
(study_flow_lines.py), from results/flow_lines/<run>.json beside the study's results."""
import math
import os

import numpy as np

from study_doc_claims import fit_cell, pm, table, z_cell, z_text
from study_flow_lines import (QUANTITIES, by_verdict, deposit_row, line_of, line_trends,
                              prolate_against_oblate, scatter_check, seeds_text, shape_means,
                              solved, summary, verdicts)
from study_stats import CHANCE_P, LINES, on_line

PLANNED = 2 * (1 + 3 * len(LINES))    # 2 seeds: the spheres and 3 shapes on each line
NAMES = {"k_zz": "k_zz", "k_xx": "k_xx", "anisotropy": "k_xx / k_zz",
         "k_zz_over_kozeny_carman": "k_zz / k_KC", "k_xx_over_kozeny_carman": "k_xx / k_KC"}
SCALE = {"k_zz": 1e-4, "k_xx": 1e-4, "anisotropy": 1.0, "k_zz_over_kozeny_carman": 1.0,
         "k_xx_over_kozeny_carman": 1.0}
DIGITS = {"k_zz": 2, "k_xx": 2, "anisotropy": 3, "k_zz_over_kozeny_carman": 3,
          "k_xx_over_kozeny_carman": 3}


def load_rows(folder):
    """the rows of the deposits solved at three voxels or more (extrapolated)"""
    return [deposit_row(r) for r in solved(folder) if "extrapolation" in r["flow"]]


def value_cell(m, q):
    """mean +- statistical error +- extrapolation bias, in SCALE's units"""
    scale, digits = SCALE[q], DIGITS[q]
    stat = "n/a" if m["stat"] is None else "%.*f" % (digits, m["stat"] / scale)
    sys = "n/a" if m["sys"] is None else "%.*f" % (digits, m["sys"] / scale)
    return "%.*f +- %s +- %s" % (digits, m["mean"] / scale, stat, sys)


def shape_text(s):
    return "spheres" if s == (1.0, 1.0) else "%g, %g" % s


def shape_name(s):
    return "the spheres" if s == (1.0, 1.0) else "(%s)" % shape_text(s)


def verdict_sentences(lead, items, where):
    """lead, then one sentence per quantity: its verdicts, each with where(keys) it holds, the
    undecided last; items [(key, q, decision)]"""
    return lead + " ".join(
        "%s: %s." % (NAMES[q], "; ".join("%s %s" % (v, where(keys)) for v, keys in by_verdict(
            [(key, d) for key, p, d in items if p == q])))
        for q in QUANTITIES if any(p == q for _, p, _ in items))


def summary_text(decisions):
    """which shapes differ (3 sigma) from the spheres or isotropy and which are undecided"""
    return verdict_sentences("Summary (verdicts at 3 sigma, the tables last): ",
                             sorted(decisions, key=lambda v: v[0]),
                             lambda ss: "at " + ", ".join(map(shape_name, ss)))


def pairs_text(pairs):
    """at which aspect ratios the prolate and oblate shapes differ"""
    if not pairs:
        return "Prolate against oblate: no aspect ratio solved on both lines yet."
    return verdict_sentences("Prolate (a, 1) against oblate (1, a) at equal a: ", pairs,
                             lambda ratios: "at a = " + ", ".join("%g" % a for a in ratios))


def trends_text(trends):
    """the lines along which each quantity grows or falls with a/c"""
    if not trends:
        return "Along the lines: no line has three shapes solved yet."
    return verdict_sentences("Along the lines (the weighted slope against a/c): ", trends,
                             lambda lines: "on " + ", ".join(lines))


def scatter_text(rows):
    """the shapes' own seed scatter against the pooling's assumption that they scatter alike"""
    parts = []
    for q, c in scatter_check(rows).items():
        if c["identical"]:
            parts.append("%s: the seeds of %s agree exactly (one deposit counted twice?), no "
                         "test" % (NAMES[q], ", ".join(map(shape_name, c["identical"]))))
        if c["bartlett_p"] is None:
            continue
        low = min(c["own"], key=c["own"].get)
        high = max(c["own"], key=c["own"].get)
        parts.append("%s %.1f %% %s to %.1f %% %s, p = %.2g%s" % (
            NAMES[q], 100 * c["own"][low], shape_name(low), 100 * c["own"][high],
            shape_name(high), c["bartlett_p"],
            " (beyond chance: the pooled error understates the most scattered shapes')"
            if c["bartlett_p"] < CHANCE_P else ""))
    if not parts:
        return ""
    return ("Each shape's own relative seed SD, and Bartlett's test that the shapes scatter "
            "alike, as the pooling assumes: %s." % "; ".join(parts))


def cost_text(rows):
    """the deposits' cost: median and range of their solves' summed wall and CPU minutes"""
    def minutes(key):
        m = np.array([r[key] for r in rows if r[key] != ""]) / 60.0
        return "%.0f min (%.0f to %.0f)" % (np.median(m), m.min(), m.max())
    if all(r["solve_seconds"] == "" for r in rows):
        return "No solve's cost recorded."
    return ("Cost per deposit, summed over its solves (median, range): the solver's CPU %s; "
            "wall time %s, with the meshing and the waits of a machine shared with other runs."
            % (minutes("solver_cpu_seconds"), minutes("solve_seconds")))


def flow_rows(results):
    """the solved deposits' rows; results: the study's results folder, the flow solves' lie
    beside it"""
    return load_rows(os.path.join(os.path.dirname(os.path.normpath(results)), "flow_lines"))


def difference_cell(name, q, d):
    """a shape's (name's) difference from its reference with its combined error, and the z of its
    verdict (the normal equivalent of Student's t)"""
    value = "%+.*f" % (DIGITS[q], d["difference"] / SCALE[q])
    if d["stat"] is not None:
        value += " +- %.*f" % (DIGITS[q], math.hypot(d["stat"], d["sys"]) / SCALE[q])
    z = "" if d["z_equivalent"] is None else " (%s)" % z_text(d["z_equivalent"])
    return "%s %s%s" % (name, value, z)


def counted(groups, what):
    """'verdict at a, b; undecided in n of N what' from [(verdict, [names])]"""
    return "; ".join("undecided in %d" % len(names) if v == "undecided" else
                     "%s at %s" % (v, ", ".join(names)) for v, names in groups) + \
        " of %d %s" % (sum(len(names) for _, names in groups), what)


def summary_rows(results):
    """the summary of findings' rows of the flow solve: per quantity each line's most aspherical
    shape solved (the spheres too against isotropy), its difference from the reference with
    the combined error and z, and the shapes counted by verdict; k_xx / k_zz of the prolate
    against the oblate shape at equal aspect ratio"""
    rows = flow_rows(results)
    if not rows:
        return []
    means = shape_means(rows)
    shapes = [s for s in means if s != "pooled"]
    aspherical = [s for s in shapes if s != (1.0, 1.0)]
    ends = list(dict.fromkeys(    # in LINES' order
        max((s for s in aspherical if on_line(line, *s)), key=lambda s: s[0] * s[1])
        for line in LINES if any(on_line(line, *s) for s in aspherical)))
    seeds = "seeds per shape: %s" % seeds_text(means, shapes)
    decisions = verdicts(means)
    out = []
    for q, groups in summary(decisions).items():
        against = QUANTITIES[q][1]
        shown = ([(1.0, 1.0)] if against == "isotropy" and (1.0, 1.0) in means else []) + ends
        found = {s: d for s, p, d in decisions if p == q}
        out.append(["%s - %s%s (flow solve; %s), at %seach line's most aspherical shape "
                    "solved" % (NAMES[q], "1" if against == "isotropy" else "the spheres'",
                                " in 1e-4 d^2" if SCALE[q] != 1.0 else "", seeds,
                                "the spheres and " if against == "isotropy" else ""),
                    "; ".join(difference_cell(shape_name(s), q, found[s])
                              for s in shown if s in found),
                    counted([(v, list(map(shape_name, ss))) for v, ss in groups], "shapes")])
    pairs = [(a, d) for a, q, d in prolate_against_oblate(means) if q == "anisotropy"]
    if pairs:
        out.append(["k_xx / k_zz: prolate (a, 1) - oblate (1, a) (flow solve; %s)" % seeds,
                    "; ".join(difference_cell("a = %g" % a, "anisotropy", d)
                              for a, d in pairs),
                    counted([(v, ["a = %g" % a for a in ratios])
                             for v, ratios in by_verdict(pairs)], "aspect ratios")])
    return out


def flow_lines_block(results):
    """results: the study's results folder; the flow solves' lie beside it"""
    rows = flow_rows(results)
    if not rows:
        return "No deposit solved at the defaults yet."
    means = shape_means(rows)
    shapes = sorted((s for s in means if s != "pooled"),
                    key=lambda s: (s != (1.0, 1.0), line_of(s), s))
    pooled = "; ".join("%s: %s" % (NAMES[q], ", ".join(
        "%s %s" % (g, "unknown" if sd is None else "%.1f %% (%d dof)" % (100 * sd, dof))
        for g, (sd, dof) in sorted(groups.items()))) for q, groups in means["pooled"].items())
    head = ("Deposits solved: %d of the %d planned (2 seeds at each of %d shapes). The seeds' "
            "relative SD, pooled per group of shapes: %s. Each cell: mean +- statistical error "
            "+- extrapolation bias (n/a: no seed scatter to pool yet)."
            % (len(rows), PLANNED, PLANNED // 2, pooled))
    values = table(["eta, zeta", "line", "seeds", "porosity (slab)", "porosity (box)"]
                   + ["%s%s" % (NAMES[q], " (1e-4 d^2)" if SCALE[q] != 1.0 else "")
                      for q in QUANTITIES],
                   [[shape_text(s), ", ".join(line_of(s)) if s != (1.0, 1.0) else "all",
                     ",".join("%d" % n for n in means[s]["seeds"])]
                    + ["%.4f" % np.mean([r[key] for r in rows if (r["eta"], r["zeta"]) == s])
                       for key in ("porosity", "domain_porosity")]
                    + [value_cell(means[s][q], q) for q in QUANTITIES] for s in shapes])
    decisions = verdicts(means)
    pairs = prolate_against_oblate(means)
    trends = line_trends(means)
    tests = len(decisions) + len(pairs) + len(trends)
    head += (" %d comparisons (the tables below): were there no effect at all, %.2f of them "
             "would be decided at 3 sigma by chance (p %g each). " % (
                 tests, tests * CHANCE_P, CHANCE_P) + cost_text(rows))
    head = " ".join(filter(None, (head, scatter_text(rows))))
    decided = table(["eta, zeta", "quantity", "against", "difference", "z", "verdict"],
                    [[shape_text(s), NAMES[q], QUANTITIES[q][1],
                      ("%+.2e d^2" if SCALE[q] != 1.0 else "%+.3f") % d["difference"],
                      z_cell(d), d["verdict"]]
                     for s, q, d in sorted(decisions, key=lambda v: (v[1], v[0]))])
    blocks = [summary_text(decisions), pairs_text(pairs), trends_text(trends), head, values,
              decided]
    if pairs:
        blocks.append(table(["a", "quantity", "prolate (a, 1) - oblate (1, a)", "z", "verdict"],
                            [["%g" % a, NAMES[q],
                              ("%+.2e d^2" if SCALE[q] != 1.0 else "%+.3f") % d["difference"],
                              z_cell(d), d["verdict"]]
                             for a, q, d in sorted(pairs, key=lambda v: (v[1], v[0]))]))
    if trends:
        blocks.append(table(["line", "quantity", "slope per unit a/c (a/c range)", "z",
                             "verdict"],
                            [[line, NAMES[q] + (" (1e-4 d^2)" if SCALE[q] != 1.0 else ""),
                              "%s (%g-%g)" % (
                                pm(d["slope"] / SCALE[q], d["se"] / SCALE[q], DIGITS[q] + 1),
                                d["shapes"][0][0] * d["shapes"][0][1],
                                d["shapes"][-1][0] * d["shapes"][-1][1]), fit_cell(d),
                              d["verdict"]] for line, q, d in trends]))
    return "\n\n".join(blocks)

