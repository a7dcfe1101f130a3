"""The markdown summary of claims.json that tools/study/study_claims.py prints."""
import math

HISTOGRAMS = ("contact_normals", "long_axes")


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
