"""doc/study.md's delta_r at matched depth and finite size (tools/study/study_doc.py; claims.json
`depth`, tools/study/study_depth.py): the tables, the matched-depth answer to the delta_r confound
(with the part of the effect the depth accounts for), Z at delta_r 0.6 reconciled between the
two sets, and the finite-size bound against the effects it is compared with."""
import math

from study_doc_claims import brief, pm, shape, signed, table, z_cell
from study_forces import MEASURES, NAMES
from study_stats import SIGMA


def matched(data, dr):
    """claims.json `depth`'s entry of delta_r at matched depth, or None"""
    return next((m for m in (data.claims.get("depth") or {}).get("matched", [])
                 if m["delta_r"] == dr), None)


def depth_share(m, q):
    """(share, its error) of the delta_r effect at matched depth that the depth accounts for:
    (X(matched) - X(N fixed)) / (X(matched) - X(0)) over the same shapes"""
    d, e = m["depth_effect"].get(q), m["matched_depth"].get(q)
    if not d or not e or not e["mean"]:
        return None
    share = d["mean"] / e["mean"]
    return share, abs(share) * math.hypot(d["se"] / d["mean"] if d["mean"] else 0.0,
                                          e["se"] / e["mean"])


def matched_answer(data, dr, q="phi"):
    """the delta_r effect at matched depth beside N fixed on the same shapes, and the part of
    it the depth accounts for; '' without deposits at matched depth"""
    m = matched(data, dr)
    if m is None or q not in m["matched_depth"] or q not in m["study_N"] or \
            q not in m.get("depth_effect", {}):
        return ""
    a, b = m["matched_depth"][q], m["study_N"][q]
    share = depth_share(m, q)
    d = m["depth_effect"][q]
    return ("at matched depth (%d shapes) %s %s, at N %d on the same shapes %s; the depth "
            "itself, X(matched) - X(N %d): %s (%s)%s"
            % (len(m["shapes"]), q, signed(a["mean"], a["se"], 4), data.n,
               signed(b["mean"], b["se"], 4), data.n, signed(d["mean"], d["se"], 4),
               brief(d["verdict"]), "" if share is None else
               ", %.0f +- %.0f %% of the effect at matched depth" % (100 * share[0],
                                                                    100 * share[1])))


def z_reconciled(data, dr):
    """Z at delta_r where all shapes at N fixed decide it: against the matched set's few
    shapes, and what the depth does to it; None elsewhere"""
    m = matched(data, dr)
    e = next((e for e in data.claims.get("verdicts", {}).get("delta_r", [])
              if e["delta_r"] == dr), {})
    if m is None or "Z" not in e or "Z" not in m["matched_depth"] or \
            e["Z"]["verdict"].startswith("undecided"):
        return None
    a, b, d = m["matched_depth"]["Z"], m["study_N"]["Z"], m["depth_effect"]["Z"]
    return ("Z at delta_r %g: over %d shapes at N %d %s (%s); on the %d matched shapes at N %d "
            "%s (%s), at matched depth %s (%s); matched against N %d on those shapes %s (%s): "
            "the matched set has fewer shapes, not a different Z"
            % (dr, e["Z"]["n"], data.n, signed(e["Z"]["mean"], e["Z"]["se"], 3),
               brief(e["Z"]["verdict"]), len(m["shapes"]), data.n, signed(b["mean"], b["se"], 3),
               brief(b["verdict"]), signed(a["mean"], a["se"], 3), brief(a["verdict"]), data.n,
               signed(d["mean"], d["se"], 3), brief(d["verdict"]))
            if d["verdict"].startswith("undecided") else
            "Z at delta_r %g: matched depth against N %d %s: %s"
            % (dr, data.n, signed(d["mean"], d["se"], 3), brief(d["verdict"])))


def finite_size_bound(data):
    """the finite-size bound on phi against the study's phi effects: (label, the bound, the
    effects larger than it, those not); None without the finite-size deposits"""
    f = next((f for f in (data.claims.get("depth") or {}).get("finite_size", [])
              if "phi" in f["effects"]), None)
    if f is None:
        return None
    m = f["effects"]["phi"]
    bound = abs(m["mean"]) + SIGMA * m["se"]
    v = data.claims.get("verdicts", {})
    effects = [("the diagonal maximum above the %s maximum" % k, r["fitted"]["difference"])
               for k, r in v.get("ridge", {}).items()]
    effects += [("phi(delta_r %g) - phi(0)" % e["delta_r"], e["phi"]["mean"])
                for e in v.get("delta_r", []) if "phi" in e]
    label = "N %d%s against N %d" % (f["N"], "" if f["width"] is None else
                                     ", box edge %g" % f["width"], data.n)
    return (label, bound, ["%s (%+.4f)" % (k, x) for k, x in effects if abs(x) > bound],
            ["%s (%+.4f)" % (k, x) for k, x in effects if abs(x) <= bound])


def bound_text(data):
    b = finite_size_bound(data)
    if b is None:
        return ""
    label, bound, small, large = b
    return ("%s: a phi difference above %.4f excluded at %g sigma; small against %s; not "
            "against %s, which hold at N %d only"
            % (label, bound, SIGMA, ", ".join(small) or "none", ", ".join(large) or "none",
               data.n))


DEPTH_QUANTITIES = ("phi", "Z", "Qzz", "fabric_anisotropy")


def effect_cell(m, digits):
    return "%s (%s): %s" % (pm(m["mean"], m["se"], digits), z_cell(m), m["verdict"])


def thickness(d):
    return "-" if d is None else "%.1f" % d["thickness_mean"]


def slope_cell(line_entry, q):
    if line_entry is None:
        return "-"
    t = line_entry["trends"][q]["slope_per_unit_a/c"]
    return "%s (%s, a/c %g-%g): %s" % (pm(t["slope"], t["se"], 4), z_cell(t), t["from_a/c"],
                                       t["to_a/c"], t["verdict"])


def matched_forces_rows(matched):
    """the force measures at matched depth against delta_r 0, and their trend along the
    diagonal at each delta_r beside delta_r 0's over the same shapes"""
    rows = []
    for m in matched:
        diagonal = (m.get("force_trends") or {}).get("diagonal")
        at_0 = (m.get("force_trends_at_0") or {}).get("diagonal")
        for q in (q for q in MEASURES if q in m.get("forces", {})):
            rows.append(["%g" % m["delta_r"], NAMES[q], effect_cell(m["forces"][q], 3),
                         slope_cell(diagonal, q), slope_cell(at_0, q)])
    return rows


def depth_block(data):
    """delta_r at matched depth beside the study's N, and the finite-size check (claims.json
    `depth`, tools/study/study_depth.py)"""
    c = data.claims.get("depth")
    if c is None:
        return ("No deposit at matched depth or at another N yet (the sets matched_depth_* and "
                "finite_size_* of workflow/config/paper.yaml).")
    rows = []
    for m in c["matched"]:
        t = m["depth"]
        for q in (q for q in DEPTH_QUANTITIES if q in m["matched_depth"]):
            rows.append(["%g" % m["delta_r"], "%d shapes, N %s" % (
                len(m["shapes"]), "/".join("%d" % n for n in m["N"])), q,
                effect_cell(m["matched_depth"][q], 4 if q == "phi" else 3),
                effect_cell(m["study_N"][q], 4 if q == "phi" else 3) if q in m["study_N"]
                else "-", effect_cell(m["depth_effect"][q], 4 if q == "phi" else 3)
                if q in m.get("depth_effect", {}) else "-",
                "%s / %s / %s" % (thickness(t["matched"]), thickness(t["study_N"]),
                                  thickness(t["delta_r_0"]))])
    out = [table(["delta_r", "matched points", "quantity", "X(delta_r) - X(0), matched depth",
                  "X(delta_r) - X(0), N %d" % data.n, "X(matched) - X(N %d): the depth"
                  % data.n, "slab (d): matched / N %d / delta_r 0" % data.n], rows)
           ] if rows else []
    answers = ["delta_r %g: %s." % (m["delta_r"], matched_answer(data, m["delta_r"]))
               for m in c["matched"] if matched_answer(data, m["delta_r"])]
    answers += ["%s." % z for z in (z_reconciled(data, m["delta_r"]) for m in c["matched"])
                if z]
    if answers:
        out.append(" ".join(answers))
    forces = matched_forces_rows(c["matched"])
    if forces:
        out.append(table(["delta_r", "force measure", "X(delta_r) - X(0), matched depth",
                          "slope per unit a/c on eta = zeta at delta_r",
                          "the same at delta_r 0 (the same shapes)"], forces))
    rows = []
    for f in c["finite_size"]:
        box = "N %d, %s" % (f["N"], "default box" if f["width"] is None
                            else "box edge %g d" % f["width"])
        for q in (q for q in DEPTH_QUANTITIES if q in f["effects"]):
            m = f["effects"][q]
            digits = 4 if q == "phi" else 3
            rows.append([box, ", ".join(shape(s) for s in f["shapes"]), q,
                         effect_cell(m, digits),
                         "%.*f" % (digits, abs(m["mean"]) + SIGMA * m["se"]),
                         "%s / %s" % (thickness(f["depth"]), thickness(f["depth_at_study_N"]))])
    if rows:
        out.append(table(["deposits", "shapes", "quantity", "X - X(N %d)" % data.n,
                          "abs(X - X(N %d)) larger than this excluded (%g sigma)" % (data.n, SIGMA),
                          "slab (d): these / N %d" % data.n], rows))
        if bound_text(data):
            out.append(bound_text(data) + ".")
    rows = [["N %d, %s" % (f["N"], "default box" if f["width"] is None
                           else "box edge %g d" % f["width"]), shape((h["eta"], h["zeta"])),
             name.replace("_", " "), "%.4f" % h[name]["rms_difference"],
             "-" if h[name]["rms_seed_scatter"] is None else "%.4f" % h[name]["rms_seed_scatter"],
             "%d / %d" % tuple(h[name]["seeds"])]
            for f in c["finite_size"] for h in f.get("histograms", [])
            for name in ("contact_normals", "long_axes")]
    if rows:
        out.append(table(["deposits", "shape", "histogram",
                          "rms over the bins of P - P(N %d)" % data.n,
                          "rms of its standard error (seed scatter)", "seeds"], rows))
    return "\n\n".join(out)
