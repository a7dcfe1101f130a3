"""doc/study.md's verdict tables (tools/study/study_doc.py): every number from claims.json's
`verdicts` (tools/study/study_verdicts.py) with its error, its significance and its verdict at
3 sigma (or the seeds per point that verdict needs)."""
import math

import numpy as np

from study_stats import CHANCE_P, SIGMA
from study_verdicts import PAPER_WORDS

SIG = "%.1f sigma"


def pm(value, err, digits):
    """value +- error at `digits` decimals (the value alone without an error)"""
    if err is None or (isinstance(err, float) and np.isnan(err)):
        return "%.*f" % (digits, value)
    return "%.*f +- %.*f" % (digits, value, digits, err)


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(r) + " |" for r in rows])


def z_text(z):
    return "-" if z is None else SIG % z


def z_cell(entry):
    """z, and the equivalent z of Student's t with the pooled SD's degrees of freedom"""
    if entry.get("z") is None:
        return "-"
    if not entry.get("dof"):
        return z_text(entry["z"])
    return "%s (t with %.0f dof: %s)" % (z_text(entry["z"]), entry["dof"],
                                       z_text(entry["z_equivalent"]))


def fit_cell(t):
    """a slope's significance, with its lack of fit where the points leave the line"""
    lack = ("; chi^2 %.1f on %d dof about the line (p = %.1g): error scaled by the Birge ratio "
            "%.2f" % (t["chi2"], t["chi2_dof"], t["chi2_p"], t["birge_ratio"])
            if t.get("lack_of_fit") else "")
    return z_cell(t) + lack


def shape(s):
    return "(%g, %g)" % tuple(s)


def pi_text(theta):
    return "%.3f rad = %.3f pi" % (theta, theta / math.pi)


def maximum_rows(v):
    rows = []
    for m in v["maximum"]:
        fits = ", ".join("%s %.3f" % (k, x) for k, x in m["fits"].items() if x is not None)
        rows.append([
            "diagonal maximum's position, delta_r %g, %s" % (m["delta_r"], m["law"]),
            "%.3f +- %.3f (bootstrap) +- %.3f (fit window: %s); phi_max %s +- %.4f (window)"
            % (m["x_max"], m["stat"] or 0.0, m["sys"], fits,
               pm(m["phi_max"], m["phi_stat"], 4), m["phi_sys"]),
            "from 1.4: %s; from the golden ratio 1.618: %s" % (
                z_cell({"z": m["z_from_1.4"], "dof": m["dof"],
                        "z_equivalent": m["z_equivalent_from_1.4"]}),
                z_cell({"z": m["z_from_golden_ratio"], "dof": m["dof"],
                        "z_equivalent": m["z_equivalent_from_golden_ratio"]})),
            "%s; %s" % (m["from_1.4"], m["from_golden_ratio"])])
    return rows


def ridge_rows(v):
    rows = []
    for name, r in v.get("ridge", {}).items():
        f, h = r["fitted"], r["highest"]
        windows = ", ".join("%s %+.4f" % (k, d) for k, d in f["per_window"].items())
        rows.append(["diagonal maximum above the %s maximum: fitted maxima" % name,
                     "%+.4f +- %.4f (bootstrap) +- %.4f (fit window: %s)"
                     % (f["difference"], f["stat"], f["sys"], windows),
                     z_cell(f), f["verdict"]])
        rows.append(["diagonal maximum above the %s maximum: highest measured points" % name,
                     "phi%s - phi%s = %s (the highest of noisy points is biased upwards)"
                     % (shape(h["diagonal"]), shape(h["other"]),
                        pm(h["difference"], h["se"], 4).replace("0.", "+0.", 1)
                        if h["difference"] >= 0 else pm(h["difference"], h["se"], 4)),
                     z_cell(h), h["verdict"]])
        e = r.get("equal_aspect")
        if e:
            cells = mean_cells(e["mean"], 4, "diagonal shapes")
            rows.append(["diagonal above the %s line at equal a/c (%g-%g; the line "
                         "interpolated in a/c)" % ((name,) + tuple(e["window_a/c"]))] + cells)
    return rows


def mean_cells(m, digits, what):
    """a mean over shapes: its numbers, chi^2 and Birge ratio, and the shapes one by one
    (each with its verdict where the verdict is per shape, or where they are few)"""
    text = ("mean over %d %s: %s; positive in %d of %d (sign test p = %.2g); chi^2 %.1f for %d "
            "(p = %.2g); about the mean %.1f for %d dof (p = %.2g), Birge ratio %.2f"
            % (m["n"], what, pm(m["mean"], m["se"], digits), m["positive"], m["nonzero"],
               m["sign_p"], m["chi2"], m["n"], m["chi2_p"], m["chi2_about_mean"], m["n"] - 1,
               m.get("chi2_about_mean_p") or 1.0, m["birge_ratio"]))
    if m.get("per_shape") and m["per_shape"][0]["shape"] and m["n"] <= 6:
        text += "; per shape: " + ", ".join(
            "%s %s (%s)" % (shape(r["shape"]), signed(r["difference"], r["se"], digits),
                            short_verdict(r["verdict"])) for r in m["per_shape"])
    return [text, z_cell(m), m["verdict"] + ("" if "mean_verdict" not in m else
                                             "; the mean: %s" % m["mean_verdict"])]


def signed(value, err, digits):
    return "%+.*f +- %.*f" % (digits, value, digits, err)


ACROSS = "depends on shape"


def brief(verdict):
    """a verdict for the summary: without the seeds it would need, and without the chi^2 of
    a per-shape verdict (both in the appendix)"""
    if verdict.startswith(ACROSS):
        return ACROSS + ": " + verdict.split("): ", 1)[1]
    return short_verdict(verdict)


def short_verdict(verdict):
    """a verdict without the seeds it would need (those are in the appendix table)"""
    return "undecided" if verdict.startswith("undecided") else verdict


def asymmetry_rows(v):
    rows = []
    for q, m in v.get("asymmetry", {}).items():
        digits = 4 if q == "phi" else 3
        big = m["largest"]
        cells = mean_cells(m, digits, "pairs")
        cells[0] += "; largest at %s: %s" % (shape(big["pair"]),
                                             pm(big["difference"], big["se"], digits))
        rows.append(["%s(eta, zeta) - %s(zeta, eta), eta > zeta" % (q, q)] + cells)
    return rows


def delta_r_rows(v, matched_text=None):
    """matched_text(delta_r): the effect at matched depth where the slab row states the
    confound"""
    rows = []
    for e in v.get("delta_r", []):
        d, d0 = e["depth"], e["depth_at_0"]
        if d and d0:
            rows.append(["measuring slab at delta_r %g against 0 (N fixed)" % e["delta_r"],
                         "thickness %.1f d (%.1f-%.1f) against %.1f d (%.1f-%.1f); solid per "
                         "area %.2f d against %.2f d (%+.0f %%)"
                         % (d["thickness_mean"], *d["thickness_range"], d0["thickness_mean"],
                            *d0["thickness_range"], d["solid_per_area_mean"],
                            d0["solid_per_area_mean"],
                            100 * (d["solid_per_area_mean"] / d0["solid_per_area_mean"] - 1)),
                         "-", "at fixed N delta_r is confounded with depth; %s"
                         % ((matched_text and matched_text(e["delta_r"])) or
                            "no deposits at matched depth")])
        for q in ("Qzz", "fabric_anisotropy", "phi", "Z"):
            if q in e:
                m = e[q]
                cells = mean_cells(m, 4, "shapes")
                cells[0] += "; relative to the mean abs(%s(0)): %+.1f %%" % (q, 100 * m["relative"])
                rows.append(["%s(delta_r %g) - %s(0)" % (q, e["delta_r"], q)] + cells)
    return rows


def fall_back_rows(v):
    rows = []
    labels = {"slope_thin": "dZ/d eta over eta = zeta >= 2 (a/c >= 4, chosen beforehand)",
              "slope_from_peak": "dZ/d eta from the highest Z on (biased to fall)"}
    for f in v["fall_back"]:
        tag = "delta_r %g, %s" % (f["delta_r"], f["law"])
        for key, label in labels.items():
            if key in f:
                s = f[key]
                rows.append(["Z falls back along eta = zeta, %s: %s" % (tag, label),
                             "%s per unit eta (%g to %g, %d points; chi^2 %.1f on %d dof about "
                             "the line)" % (pm(s["slope"], s["se"], 3), s["from"], s["to"],
                                            s["points"], s["chi2"], s["chi2_dof"]),
                             fit_cell(s), s["verdict"]])
        for key, label in (("end_minus_peak", "Z%s - Z%s (end - highest)"),
                           ("end_minus_highest_spheroid", "Z%s - Z%s (end - highest spheroid)")):
            if key in f:
                s = f[key]
                fall = ("" if key != "end_minus_peak" else
                        "; a fall larger than %.2f excluded at %g sigma"
                        % (s["largest_fall"], SIGMA))
                rows.append(["Z along eta = zeta, %s: " % tag
                             + label % (shape(s["shapes"][0]), shape(s["shapes"][1])),
                             pm(s["difference"], s["se"], 3) + fall, z_cell(s), s["verdict"]])
    return rows


def crossing_rows(v):
    rows = []
    for key, c in v.get("crossings", {}).items():
        iso, mut, fig = c["isotropic_level"], c["each_other"], c["each_other_figure_shapes"]
        paper = c["paper"]
        rows.append(["%s: crossing of each curve with 1/(4 pi)" % key.replace("_", " "),
                     "median %s over %d shapes (range %.2f-%.2f rad, SD over shapes %.2f); "
                     "a shape's error: median %.3f rad"
                     % (pi_text(iso["median"]), len(iso["shapes"]), *iso["range"],
                        iso["sd_over_shapes"], float(np.median([r["se"] for r in iso["shapes"]
                                                                if r["se"] is not None]))),
                     "paper: %s (%s): %s the range" % (
                         PAPER_WORDS[key], pi_text(paper),
                         "inside" if iso["range"][0] <= paper <= iso["range"][1]
                         else "outside"),
                     "the level crossing (median) lies %+.2f rad from %s"
                     % (iso["median"] - paper, pi_text(paper))])
        for label, m in (("all pairs of distinct curves", mut),
                         ("the curves of the figure", fig)):
            if "median" not in m:
                continue
            inside = m["quartiles"][0] <= paper <= m["quartiles"][1]
            rows.append(["%s: curves crossing each other, %s" % (key.replace("_", " "), label),
                         "median %s over %d pairs (quartiles %.2f-%.2f, range %.2f-%.2f rad; "
                         "%d pairs too alike, %d cross more than once); a crossing's error: "
                         "median %.3f rad" % (pi_text(m["median"]), m["pairs"], *m["quartiles"],
                                              *m["range"], m["similar_pairs"],
                                              m["ambiguous_pairs"], m["median_se"]),
                         "paper: %s (%s): %s the quartiles" % (
                             PAPER_WORDS[key], pi_text(paper), "inside" if inside
                             else "outside"),
                         "the mutual crossing (median) lies %+.2f rad from %s%s"
                         % (m["median"] - paper, pi_text(paper),
                            "; above it, as the paper says, the lower quartile by more than "
                            "3 single crossings' errors ('slightly' is the reader's call)"
                            if key == "contact_normals" and m["quartiles"][0] - paper
                            >= SIGMA * m["median_se"] else "")])
    return rows


def sphere_rows(v):
    rows = []
    for key, s in v.get("sphere_isotropy", {}).items():
        if not s:
            continue
        big, sig = s["largest"], s["most_significant"]
        beyond = ["%.2f: %+.0f +- %.0f %%" % (t, 100 * d, 100 * e)
                  for t, d, e in zip(s["theta"], s["deviation"], s["se"]) if abs(d) > 0.10]
        rows.append(["sphere's contact normals against 1/(4 pi), %s" % key,
                     "most significant deviation %+.1f +- %.1f %% at theta %.2f; largest %+.0f +- "
                     "%.0f %% at theta %.2f; bins beyond 10 %%: %s; chi^2 %.1f for %d bins "
                     "(errors: per-bin seed SD pooled over the sphere's deposits of every "
                     "delta_r of its law, %d dof)"
                     % (100 * sig["deviation"], 100 * sig["se"], sig["theta"],
                        100 * big["deviation"], 100 * big["se"], big["theta"],
                        "; ".join(beyond) or "none", s["chi2"], s["chi2_dof"],
                        s["dof_of_the_errors"]),
                     "most significant: %s; chi^2 p = %.1g; with counting errors chi^2 %.1f, "
                     "p = %.1g"
                     % (z_cell(dict(sig, dof=s["dof_of_the_errors"])), s["p_isotropic"],
                        s["chi2_counting"], s["p_counting"]),
                     "not isotropic (both chi^2 beyond 3 sigma)"
                     if max(s["p_isotropic"], s["p_counting"]) < CHANCE_P else
                     "undecided: one chi^2 is within 3 sigma"])
    return rows


def verdicts_block(data, matched_text=None):
    v = data.claims["verdicts"]
    rows = (maximum_rows(v) + ridge_rows(v) + asymmetry_rows(v) + delta_r_rows(v, matched_text)
            + fall_back_rows(v) + crossing_rows(v) + sphere_rows(v))
    return table(["question", "measured (+- standard error)", "significance",
                  "verdict (3 sigma; else the seeds per point it needs)"], rows)
