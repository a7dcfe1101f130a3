"""doc/study.md's summary of findings (tools/study/study_doc.py): one row per finding, its number
+- its one standard error and its verdict at 3 sigma; the statistics behind each verdict (t,
chi^2, Birge ratio, the seeds a verdict would need) are in the appendix table (study_doc_claims).
Also the matched-depth answer to the delta_r confound and the finite-size bound against the
effects it is compared with."""
import math

from study_doc_claims import brief, pm, shape, signed, table
from study_doc_depth import depth_share, finite_size_bound, matched
from study_doc_paper import diff
from study_doc_flow import summary_rows as flow_rows
from study_doc_forces import LINE_NAMES, mirror_meaning
from study_forces import shape_of_trend
from study_stats import CHANCE_P, SIGMA

def per_shape(m, digits):
    """the shapes of a mean one by one where they are few, else the mean"""
    if m.get("per_shape") and m["per_shape"][0]["shape"] and m["n"] <= 6:
        return "; ".join("%s %s" % (shape(r["shape"]), signed(r["difference"], r["se"], digits))
                         for r in m["per_shape"])
    return "mean over %d shapes %s" % (m["n"], signed(m["mean"], m["se"], digits))


def summary_rows(data):
    v, law = data.claims["verdicts"], data.law
    p = data.base.quantity("phi")
    diag = sorted(x for x in p.values if x[0] == x[1])
    top = max(diag, key=p.mean)
    rise = diff(p, top, diag[0])
    rows = [["phi rises from spheres to the diagonal's highest point %s (%s)" % (shape(top), law),
             signed(rise[0], rise[1], 4), "rises" if rise[2] >= SIGMA else "undecided"]]
    for m in v["maximum"]:    # every law's: the paper's law (viscous) beside the default
        rows.append(["diagonal maximum's position eta = zeta (%s, delta_r %g)"
                     % (m["law"], m["delta_r"]),
                     pm(m["x_max"], math.hypot(m["stat"] or 0.0, m["sys"]), 3),
                     "%s; %s" % (m["from_1.4"], m["from_golden_ratio"])])
    for name, r in v.get("ridge", {}).items():
        f = r["fitted"]
        rows.append(["diagonal maximum above the %s maximum (fitted)" % name,
                     signed(f["difference"], math.hypot(f["stat"], f["sys"]), 4),
                     brief(f["verdict"])])
        e = r.get("equal_aspect")
        if e:
            rows.append(["diagonal above the %s line at equal a/c (%g-%g)"
                         % ((name,) + tuple(e["window_a/c"])), per_shape(e["mean"], 4),
                         brief(e["mean"]["verdict"])])
    for q in ("phi", "Z"):
        a = v.get("asymmetry", {}).get(q)
        if a:
            rows.append(["%s(eta, zeta) - %s(zeta, eta), eta > zeta (%d pairs)" % (q, q, a["n"]),
                         signed(a["mean"], a["se"], 4 if q == "phi" else 3),
                         brief(a["verdict"])])
    for e in v.get("delta_r", []):
        for q in ("phi", "Z"):
            if q in e:
                rows.append(["%s(delta_r %g) - %s(0), N %d (%d shapes)"
                             % (q, e["delta_r"], q, data.n, e[q]["n"]),
                             per_shape(e[q], 4 if q == "phi" else 3), brief(e[q]["verdict"])])
        m = matched(data, e["delta_r"])
        if m and "phi" in m["matched_depth"] and "phi" in m.get("depth_effect", {}):
            x, d = m["matched_depth"]["phi"], m["depth_effect"]["phi"]
            rows.append(["phi(delta_r %g) - phi(0) at matched depth (%d shapes)"
                         % (e["delta_r"], x["n"]), per_shape(x, 4), brief(x["verdict"])])
            share = depth_share(m, "phi")
            rows.append(["the depth's part of it: phi(matched) - phi(N %d), delta_r %g"
                         % (data.n, e["delta_r"]), "%s%s" % (
                             signed(d["mean"], d["se"], 4), "" if share is None else
                             " (%.0f +- %.0f %% of the effect)" % (100 * share[0],
                                                                   100 * share[1])),
                         brief(d["verdict"])])
    fb = next((f for f in v["fall_back"] if f["law"] == law), {})
    if "slope_thin" in fb:
        s = fb["slope_thin"]
        rows.append(["Z falls back along eta = zeta over a/c >= 4 (dZ/d eta)",
                     signed(s["slope"], s["se"], 3), brief(s["verdict"])])
    a = data.base.quantity("fabric_anisotropy")
    if {(2.0, 2.0), (3.0, 3.0)} <= set(a.values):
        d = diff(a, (3.0, 3.0), (2.0, 2.0))
        rows.append(["the contact normals' anisotropy a_z = F_zz - (F_xx + F_yy)/2 deepens "
                     "from (2, 2) to (3, 3)", signed(d[0], d[1], 3),
                     "deepens" if d[2] >= SIGMA else "undecided"])
    c = v.get("crossings", {}).get("contact_normals")
    if c:
        m = c["each_other"]
        rows.append(["the contact-normal curves cross each other at (the paper: slightly "
                     "above pi/5)", "median %.3f pi (quartiles %.3f-%.3f pi)"
                     % (m["median"] / math.pi, m["quartiles"][0] / math.pi,
                        m["quartiles"][1] / math.pi),
                     "above pi/5" if m["quartiles"][0] > c["paper"] else "not above pi/5"])
    s = v.get("sphere_isotropy", {}).get("delta_r 0, %s" % law)
    if s:
        rows.append(["the spheres' contact normals isotropic (%s; chi^2 %.0f for %d bins)"
                     % (law, s["chi2"], s["chi2_dof"]),
                     "most significant bin %+.1f +- %.1f %% at theta %.2f"
                     % (100 * s["most_significant"]["deviation"],
                        100 * s["most_significant"]["se"], s["most_significant"]["theta"]),
                     "not isotropic" if max(s["p_isotropic"], s["p_counting"]) < CHANCE_P
                     else "undecided"])
    for line, f in (data.claims.get("forces") or {}).items():
        for q, what in (("a_total", "a_n + a_f (the forces' preference for the vertical)"),
                        ("a_f", "a_f (the forces' own part)"), ("K0", "K0")):
            if q in f["trends"]:
                t = f["trends"][q]["slope_per_unit_a/c"]
                label = "%s against a/c on %s (a/c %g-%g)" % (what, LINE_NAMES[line],
                                                             t["from_a/c"], t["to_a/c"])
                if t.get("lack_of_fit"):    # no line: its course, else the ends
                    ends = f["trends"][q]["thinnest_minus_roundest"]
                    course = shape_of_trend(f["trends"][q])
                    rows.append([label, "thinnest - roundest %s; not linear in a/c (chi^2 %.0f "
                                 "on %d dof about a line)" % (signed(ends["difference"],
                                                                     ends["se"], 3),
                                                              t["chi2"], t["chi2_dof"]),
                                 course if course.startswith("not monotone")
                                 else brief(ends["verdict"])])
                    continue
                rows.append([label, "slope " + signed(t["slope"], t["se"], 4),
                             brief(t["verdict"])])
    mirror = data.claims.get("force_mirror")
    if mirror:
        rows.append(["K0 mirrors a_f seed by seed", "r = %.2f (%d deposits)"
                     % (mirror["r"], mirror["deposits"]),
                     mirror_meaning(mirror)])
    b = finite_size_bound(data)
    if b:
        label, bound, small, large = b
        rows.append(["finite size: phi, %s" % label, "abs(difference) < %.4f (%g sigma)"
                     % (bound, SIGMA), "small against %s; not against %s (those hold at N %d "
                     "only)" % (", ".join(small) or "none", ", ".join(large) or "none",
                                data.n)])
    return rows + flow_rows(data.results)


def summary_block(data):
    return table(["finding", "number +- standard error", "verdict (3 sigma)"],
                 summary_rows(data))
