"""doc/study.md's table of the paper's claims against the numbers (tools/study/study_doc.py): one
row per statement of the paper, every number from the results with its standard error, the
verdicts at 3 sigma. Literature values are the cited papers' (constants below)."""
import math

from scipy import stats

from study_doc_claims import brief, pm, shape, signed, table, z_cell, z_text
from study_doc_depth import matched_answer
from study_doc_forces import forces_row
from study_verdicts import PAPER_WORDS
from study_stats import CHANCE_P, SIGMA, equivalent_sigma

RCP = 0.64                  # random close packing of spheres
DONEV_MAX = 0.735           # Donev et al. 2004, jammed ellipsoids near 1.25:1:0.8
ZHOU = (1.8, 0.6)           # Zhou et al. 2011, densest gravity-packed prolate / oblate a/c
# jammed sphere packings without friction and at infinite friction (Silbert 2010): phi, Z
SPHERE_LIMITS = {"frictionless": (0.64, 6.0), "infinite friction": (0.55, 4.0)}


def diff(pooled, a, b):
    """pooled(a) - pooled(b), its standard error, and its significance as Student's t with
    the fewer degrees of freedom of the two pooled SDs (the normal z of the same p), and
    those degrees of freedom"""
    d = pooled.mean(a) - pooled.mean(b)
    se = math.hypot(pooled.se(a), pooled.se(b))
    dof = min(pooled.dof(a), pooled.dof(b))
    return d, se, equivalent_sigma(d / se, dof), dof


def dtext(d, se, digits, dof=None):
    z = z_cell({"z": d / se, "dof": dof, "z_equivalent": equivalent_sigma(d / se, dof)})
    return "%+.*f +- %.*f (%s)" % (digits, d, digits, se, z)


def shared_diagonal(data):
    """the laws at delta_r 0 and the diagonal shapes every one of them has, so that the laws
    are compared over one range (the fall-back's a/c 12 and 16 ran with the default law only)"""
    laws = sorted({k[1] for k in data.sels if k[0] == 0.0})
    shapes = set.intersection(*({s for s in data.sels[(0.0, law)].shapes if s[0] == s[1]}
                                for law in laws))
    return laws, sorted(shapes)


def fall_over_rise(rise, fall):
    """-fall / rise with its error (the two share the top point: an upper bound)"""
    r = -fall[0] / rise[0]
    return r, abs(r) * math.hypot(fall[1] / fall[0], rise[1] / rise[0])


def density_rise_fall(data):
    out, ratios, peaks = [], [], []
    laws, diag = shared_diagonal(data)
    for law in laws:
        p = data.sels[(0.0, law)].quantity("phi")
        top = max(diag, key=p.mean)
        rise, fall = diff(p, top, diag[0]), diff(p, diag[-1], top)
        ratios.append("%s %s" % (law, pm(*fall_over_rise(rise, fall), 2)))
        peaks.append("%s %s" % (law, "yes" if rise[2] >= SIGMA and fall[2] <= -SIGMA
                                else "undecided"))
        out.append("%s: %s (spheres), %s %s, %s %s; rise %s, fall to %s %s"
                   % (law, pm(p.mean(diag[0]), p.se(diag[0]), 4), pm(p.mean(top), p.se(top), 4),
                      shape(top), pm(p.mean(diag[-1]), p.se(diag[-1]), 4), shape(diag[-1]),
                      dtext(*rise[:2], 4, rise[3]), shape(diag[-1]), dtext(*fall[:2], 4, fall[3])))
    return ["density rises from spheres, peaks, then falls slowly with asphericity",
            "; ".join(out),
            "rises and peaks (both at 3 sigma): " + ", ".join(peaks) + ". Falls slowly: the "
            "fall to the thinnest diagonal shape all laws have is this many times the rise: "
            + ", ".join(ratios) + " (the reader judges 'slowly')"]


def maximum_row(data):
    v = data.claims["verdicts"]
    cells = ["%s, delta_r %g: %.3f +- %.3f +- %.3f (%s; %s)"
             % (m["law"], m["delta_r"], m["x_max"], m["stat"] or 0, m["sys"],
                position_text(m, "1.4"), position_text(m, "golden_ratio"))
             for m in v["maximum"]]
    near = all(m["from_1.4"].startswith("consistent") for m in v["maximum"])
    excluded = ["%s delta_r %g" % (m["law"], m["delta_r"]) for m in v["maximum"]
                if m["from_golden_ratio"].startswith("differs")]
    where = ("at each" if len(excluded) == len(v["maximum"]) else
             "at %s only" % ", ".join(excluded) if excluded else "nowhere")
    return ["maximum along eta = zeta near 1.4; the golden-ratio remark (1.618)",
            "fitted maximum +- bootstrap +- fit window (sigma, then Student's t with the pooled "
            "SD's dof): " + "; ".join(cells),
            ("consistent with 1.4 at every delta_r and law" if near else
             "not everywhere consistent with 1.4") + "; the golden ratio is excluded %s "
            "(3 sigma, t)" % where]


def position_text(m, key):
    return "from %s %s, t %s" % ("1.618" if key == "golden_ratio" else key,
                                 z_text(m["z_from_" + key]), z_text(m["z_equivalent_from_" + key]))


def ridge_row(data):
    r = data.claims["verdicts"].get("ridge", {})
    cells, verdicts = [], []
    for name, x in r.items():
        f, h = x["fitted"], x["highest"]
        cells.append("%s: fitted %+.4f +- %.4f +- %.4f (%s); highest points %s - %s: %s"
                     % (name, f["difference"], f["stat"], f["sys"], z_text(f["z"]),
                        shape(h["diagonal"]), shape(h["other"]), dtext(h["difference"],
                                                                     h["se"], 4)))
        verdict = "%s: fitted %s; highest points %s" % (name, f["verdict"], h["verdict"])
        e = x.get("equal_aspect")
        if e:
            m = e["mean"]
            cells[-1] += "; at equal a/c (%d diagonal shapes): %s" % (m["n"], "; ".join(
                "%s %s" % (shape(r["shape"]), signed(r["difference"], r["se"], 4))
                for r in m["per_shape"]) if "mean_verdict" in m else
                dtext(m["mean"], m["se"], 4, m.get("dof")))
            verdict += "; at equal a/c %s" % brief(m["verdict"])
        verdicts.append(verdict)
    return ["the diagonal maximum above the prolate and oblate maxima", "; ".join(cells),
            "; ".join(verdicts)]


def symmetry_row(data):
    a = data.claims["verdicts"]["asymmetry"]["phi"]
    p = data.base.quantity("phi")
    diag = sorted(s for s in p.values if s[0] == s[1])
    rise = max(p.mean(s) for s in diag) - p.mean(diag[0])
    rms = data.claims["symmetry"]["rms_difference"]
    return ["near-symmetry about eta = zeta (density)",
            "%d pairs: mean phi(eta > zeta) - phi(eta < zeta) %s (%s); rms %.4f (%.0f %% of the "
            "rise from spheres to the maximum); chi^2 %.1f for %d pairs (p = %.1g)"
            % (a["n"], pm(a["mean"], a["se"], 4), z_cell(a), rms, 100 * rms / rise,
               a["chi2"], a["n"], a["chi2_p"]),
            "pair by pair: %s (the pairs scatter %.1f times their errors)"
            % (brief(a["verdict"]), a["birge_ratio"]) if "mean_verdict" in a else
            "no tilt detected: abs(mean) < %.4f at %g sigma; symmetric within the seed scatter"
            % (abs(a["mean"]) + SIGMA * a["se"], SIGMA)]


def constant_eta_row(data):
    cells, bad = [], []
    for m in data.claims["constant_eta"]:
        if m.get("x_max") is None:
            cells.append("eta %g: highest at zeta = %g (the line's end)" % (m["eta"],
                                                                           m["x_highest"]))
            bad.append("%g" % m["eta"])
            continue
        err = math.hypot(m.get("x_max_sd") or 0, m["x_max_sys"])
        z = (m["x_max"] - m["eta"]) / err
        cells.append("eta %g: zeta_max %.2f +- %.2f +- %.2f (%s from eta)"
                     % (m["eta"], m["x_max"], m.get("x_max_sd") or 0, m["x_max_sys"],
                        z_text(z)))
        if abs(z) >= SIGMA:
            bad.append("%g" % m["eta"])
    return ["along lines of constant eta the maximum near eta = zeta", "; ".join(cells),
            "differs (>= 3 sigma, or the maximum at the line's end) at eta = " + ", ".join(bad)
            if bad else "agrees at every eta"]


def delta_r_density_row(data):
    p = data.base.quantity("phi")
    diag = sorted(s for s in p.values if s[0] == s[1])
    rise = diff(p, max(diag, key=p.mean), diag[0])
    cells = []
    for e in (e for e in data.claims["verdicts"]["delta_r"] if "phi" in e):
        m = e["phi"]
        share = m["mean"] / rise[0]
        cells.append("delta_r %g: %s over %d shapes (positive in %d; %s), %.0f +- %.0f %% of "
                     "the rise from spheres to the maximum"
                     % (e["delta_r"], pm(m["mean"], m["se"], 4), m["n"], m["positive"],
                        z_cell(m), 100 * share,
                        100 * abs(share) * math.hypot(m["se"] / m["mean"], rise[1] / rise[0])))
    verdicts = ["delta_r %g: %s" % (e["delta_r"], brief(e["phi"]["verdict"]))
                for e in data.claims["verdicts"]["delta_r"] if "phi" in e]
    answers = ["delta_r %g %s" % (e["delta_r"], matched_answer(data, e["delta_r"]))
               for e in data.claims["verdicts"]["delta_r"] if matched_answer(data, e["delta_r"])]
    return ["delta_r minor for density; polydisperse deposits denser",
            "phi(delta_r) - phi(0), N fixed: " + "; ".join(cells),
            "; ".join(verdicts) + "; 'minor' is the reader's call against the percentages; at "
            "fixed N delta_r also thins the measuring slab: " + ("; ".join(answers) or
                                                                  "no deposits at matched depth")]


def z_row(data):
    z = data.base.quantity("Z")
    sphere = (1.0, 1.0)
    spheroids = [s for s in z.values if (s[0] == 1.0) != (s[1] == 1.0)]
    general = [s for s in z.values if s[0] > 1.0 and s[1] > 1.0]
    top_s, top_g = max(spheroids, key=z.mean), max(general, key=z.mean)
    rise, higher = diff(z, top_s, sphere), diff(z, top_g, top_s)
    # the highest of many noisy means is biased upwards: count instead the general shapes
    # above the highest spheroid each beyond 3 sigma, Bonferroni-corrected for their number
    bonferroni = float(stats.norm.isf(stats.norm.sf(SIGMA) / len(general)))
    above = [g for g in general if diff(z, g, top_s)[2] >= bonferroni]
    fb = next((f for f in data.claims["verdicts"]["fall_back"] if f["law"] == data.law), {})
    slope = fb.get("slope_thin", {})
    end = fb.get("end_minus_peak")
    return ["Z rises for spheroids, peaks higher for general ellipsoids, falls back for "
            "eta = zeta >> 1",
            "spheres %s; highest spheroid %s %s (rise %s); highest general shape %s %s (above "
            "the spheroids' %s; the highest of noisy points is biased upwards); %d of %d "
            "general shapes lie above the highest spheroid by %.1f sigma or more each (3 sigma, "
            "Bonferroni-corrected); slope over eta = zeta >= 2: %s per unit eta (%s)%s"
            % (pm(z.mean(sphere), z.se(sphere), 2), shape(top_s), pm(z.mean(top_s),
                                                                      z.se(top_s), 2),
               dtext(*rise[:2], 2, rise[3]), shape(top_g), pm(z.mean(top_g), z.se(top_g), 2),
               dtext(*higher[:2], 2, higher[3]), len(above), len(general), bonferroni,
               pm(slope.get("slope", math.nan), slope.get("se"), 3), z_cell(slope),
               "" if end is None else "; the thinnest against the highest, %s - %s: %s, a "
               "fall larger than %.2f excluded at %g sigma"
               % (shape(end["shapes"][0]), shape(end["shapes"][1]),
                  dtext(end["difference"], end["se"], 2, end.get("dof")), end["largest_fall"],
                  SIGMA)),
            "rises: %s; peaks higher: %s; falls back: %s (the verdict table below)"
            % ("yes" if rise[2] >= SIGMA else "undecided", "yes" if above else
               "undecided", fall_back_verdict(slope, end))]


def fall_back_verdict(slope, end):
    """yes where Z falls over the thin shapes or ends below its highest point; otherwise not
    seen, with the largest fall the data leave open"""
    if slope.get("verdict") == "falls" or (end or {}).get("verdict") == "lower":
        return "yes"
    if end is None:
        return slope.get("verdict", "-")
    return ("not seen up to a/c %g: the slope over a/c >= 4 is %s, and a fall from the highest "
            "point larger than %.2f is excluded at %g sigma"
            % (end["shapes"][0][0] * end["shapes"][0][1], slope.get("verdict", "-"),
               end["largest_fall"], SIGMA))


def fabric_row(data):
    a = data.base.quantity("fabric_anisotropy")
    diag = sorted(s for s in a.values if s[0] == s[1])
    s = data.claims["verdicts"]["sphere_isotropy"].get("delta_r 0, %s" % data.law)
    deepen = (diff(a, (3.0, 3.0), (2.0, 2.0)) if {(2.0, 2.0), (3.0, 3.0)} <= set(a.values)
              else None)
    thinnest = diag[-1]
    cells = ", ".join("%s %s" % (shape(x), pm(a.mean(x), a.se(x), 3))
                      for x in diag[:1] + [d for d in diag if d[0] in (1.4, 2.0, 3.0)]
                      + [thinnest] * (thinnest[0] > 3.0)
                      + [x for x in ((3.0, 1.0), (1.0, 3.0)) if x in a.values])
    sig, big = s["most_significant"], s["largest"]
    return ["contact normals flat for spheres, maximum near theta = 0, minimum at pi/2, "
            "deepening with asphericity",
            "a_z = F_zz - (F_xx + F_yy)/2: %s; a_z(3, 3) - a_z(2, 2) %s; spheres: most "
            "significant deviation from 1/(4 pi) %+.1f +- %.1f %% at theta %.2f, largest %+.0f "
            "+- %.0f %% at theta %.2f (per-bin errors pooled over the sphere deposits of every "
            "delta_r of its law), chi^2 %.0f for %d bins"
            % (cells, dtext(*deepen[:2], 3, deepen[3]) if deepen else "-",
               100 * sig["deviation"], 100 * sig["se"], sig["theta"], 100 * big["deviation"],
               100 * big["se"], big["theta"], s["chi2"], s["chi2_dof"]),
            "the ellipsoids: %s. Spheres: not flat (chi^2 p = %.1g with pooled errors, %.1g "
            "with counting errors)"
            % ("a_z grows from a/c 4 to 9 (3 sigma, t)" if deepen and deepen[2] >= SIGMA else
               "a_z from a/c 4 to 9 undecided", s["p_isotropic"], s["p_counting"])
            if s and max(s["p_isotropic"], s["p_counting"]) < CHANCE_P else
            "spheres: flat or undecided (see the verdict table)"]


def crossing_row(data, key, claim):
    c = data.claims["verdicts"]["crossings"][key]
    iso, mut = c["isotropic_level"], c["each_other"]
    return [claim,
            "curves crossing each other: median %.3f pi (quartiles %.3f-%.3f pi, %d pairs); "
            "crossing the isotropic level: median %.3f pi (range %.3f-%.3f pi, %d shapes)"
            % (mut["median"] / math.pi, mut["quartiles"][0] / math.pi,
               mut["quartiles"][1] / math.pi, mut["pairs"], iso["median"] / math.pi,
               iso["range"][0] / math.pi, iso["range"][1] / math.pi, len(iso["shapes"])),
            "the paper: %s; the medians lie %+.3f pi (each other) and %+.3f pi (the isotropic "
            "level) from %.3f pi" % (PAPER_WORDS[key], (mut["median"] - c["paper"]) / math.pi,
                                     (iso["median"] - c["paper"]) / math.pi,
                                     c["paper"] / math.pi)]


def histograms_delta_r_row(data):
    cells = []
    for e in data.claims["verdicts"]["delta_r"]:
        for q, name in (("Qzz", "Q_zz"), ("fabric_anisotropy", "a_z")):
            if q in e:
                m = e[q]
                cells.append("%s at delta_r %g: %s (%s; %+.0f %% of abs(%s(0)); positive in %d "
                             "of %d)" % (name, e["delta_r"], pm(m["mean"], m["se"], 4),
                                         z_cell(m), 100 * m["relative"], name,
                                         m["positive"], m["nonzero"]))
    return ["delta_r has no significant effect on the anisotropy (both histograms)",
            "X(delta_r) - X(0) over the shapes: " + "; ".join(cells),
            "; ".join("%s %g: %s" % (q, e["delta_r"], e[q]["verdict"])
                      for e in data.claims["verdicts"]["delta_r"] for q in ("Qzz",
                                                                            "fabric_anisotropy")
                      if q in e) + ". At fixed N the polydisperse slab is thinner (confounded)"]


def law_row(data):
    cells, verdicts = [], []
    laws, diag = shared_diagonal(data)
    maxima = {m["law"]: m for m in data.claims["verdicts"]["maximum"] if m["delta_r"] == 0}
    for law in laws:
        p = data.sels[(0.0, law)].quantity("phi")
        z = data.sels[(0.0, law)].quantity("Z")
        top = max(diag, key=p.mean)
        zs = [z.mean(s) for s in diag]
        cells.append("%s: phi %s (spheres), %s %s, %s %s; Z %.1f-%.1f on the shared diagonal"
                     % (law, pm(p.mean(diag[0]), p.se(diag[0]), 4), pm(p.mean(top), p.se(top), 4),
                        shape(top), pm(p.mean(diag[-1]), p.se(diag[-1]), 4), shape(diag[-1]),
                        min(zs), max(zs)))
        m = maxima.get(law)
        if m is None:
            continue
        err = math.hypot(m["phi_stat"] or 0.0, m["phi_sys"])
        ze = equivalent_sigma((m["phi_max"] - RCP) / err, m["dof"])
        ratio = fall_over_rise(diff(p, top, diag[0]), diff(p, diag[-1], top))
        verdicts.append("%s: fitted maximum %+.4f +- %.4f from %g (t %s: %s), fall %s times "
                        "the rise" % (law, m["phi_max"] - RCP, err, RCP, z_text(ze),
                                      "above" if ze >= SIGMA else "not significantly above",
                                      pm(*ratio, 2)))
    return ["which tangential law reproduces the paper (maximum 'significantly higher than "
            "the one observed in random close packing of spheres', taken as %g; slow fall)"
            % RCP, "; ".join(cells), "; ".join(verdicts)]


def claims_block(data):
    return table(["claim (paper)", "measured (+- standard error)", "verdict"], paper_rows(data))


def paper_rows(data):
    return [density_rise_fall(data), maximum_row(data), ridge_row(data), symmetry_row(data),
            constant_eta_row(data), delta_r_density_row(data), z_row(data), fabric_row(data),
            forces_row(data),
            crossing_row(data, "contact_normals", "the contact-normal curves cross slightly "
                         "above pi/5"),
            crossing_row(data, "long_axes", "long axes horizontal, with an invariant near pi/3"),
            histograms_delta_r_row(data), law_row(data)] + literature_rows(data)


def literature_rows(data):
    m = data.claims["maxima"]
    rows = []
    if "prolate" in m and "oblate" in m and "x_max" in m["prolate"] and "x_max" in m["oblate"]:
        pr, ob = m["prolate"], m["oblate"]
        ep = math.hypot(pr.get("x_max_sd") or 0, pr["x_max_sys"])
        eo = math.hypot(ob.get("x_max_sd") or 0, ob["x_max_sys"])
        rows.append(["Zhou et al. 2011: gravity-packed spheroids densest near a/c %g (prolate) "
                     "and %g (oblate)" % ZHOU,
                     "prolate a/c %.2f +- %.2f (%s from %g); oblate c/a %.3f +- %.3f (%s from %g)"
                     % (pr["x_max"], ep, z_text((pr["x_max"] - ZHOU[0]) / ep), ZHOU[0],
                        1 / ob["x_max"], eo / ob["x_max"] ** 2,
                        z_text((1 / ob["x_max"] - ZHOU[1]) / (eo / ob["x_max"] ** 2)), ZHOU[1]),
                     "errors of bootstrap and fit window in quadrature; the literature values "
                     "carry none here"])
    (phi_hi, z_hi), (phi_lo, z_lo) = SPHERE_LIMITS["frictionless"], \
        SPHERE_LIMITS["infinite friction"]
    laws = sorted({k[1] for k in data.sels if k[0] == 0.0}, key=lambda law: law != data.law)
    for law in laws:    # the default law first
        p, z = data.sels[(0.0, law)].quantity("phi"), data.sels[(0.0, law)].quantity("Z")
        top = max(p.values, key=p.mean)
        rows.append(["Donev et al. 2004: jammed ellipsoids up to %g near 1.25:1:0.8" % DONEV_MAX,
                     "highest deposit %s at %s (%s)" % (pm(p.mean(top), p.se(top), 4),
                                                        shape(top), law),
                     "below the jammed packings" if p.mean(top) + SIGMA * p.se(top) < DONEV_MAX
                     else "not below the jammed packings at 3 sigma"])
        sphere = (1.0, 1.0)
        if sphere not in p.values:
            continue
        side = {(True, True): "above the frictionless limit in both",
                (False, False): "between the two limits in both"}
        above = (p.mean(sphere) > phi_hi, z.mean(sphere) > z_hi)
        below = p.mean(sphere) < phi_lo or z.mean(sphere) < z_lo
        rows.append(["Silbert 2010: jammed spheres, phi %g and Z %g without friction, phi %g "
                     "and Z %g at infinite friction" % (phi_hi, z_hi, phi_lo, z_lo),
                     "spheres (%s): phi %s, Z %s" % (law, pm(p.mean(sphere), p.se(sphere), 4),
                                                     pm(z.mean(sphere), z.se(sphere), 2)),
                     "below the infinite-friction limit" if below else
                     side.get(above, "above the frictionless limit in one of phi and Z")])
    return rows
