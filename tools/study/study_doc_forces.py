"""doc/study.md's contact-force tables and the abstract's row of the claims table
(study_doc.py): the force measures of the deposits with window means (claims.json `forces`,
`force_mirror`; study_forces.py), per shape and their trends along the lines."""
from study_doc_claims import fit_cell, pm, shape, table, z_cell
from study_forces import MEASURES, NAMES, shape_of_trend
from study_stats import CHANCE_P

LINE_NAMES = {"diagonal": "eta = zeta", "prolate": "prolate (zeta = 1)",
              "oblate": "oblate (eta = 1)"}
MIRROR_MEANING = ("a deposit whose vertical contacts carry more than their share of the force "
                  "(a_f above its shape's mean) has less horizontal stress (K0 below its "
                  "shape's mean)")


def mirror_meaning(m):
    """what the correlation of K0 with a_f says at 3 sigma"""
    if m["p"] >= CHANCE_P:
        return "not decided at 3 sigma"
    return MIRROR_MEANING if m["r"] < 0 else "K0 and a_f rise together"


def mirror_text(m, law):
    if m is None:
        return "K0 against a_f seed by seed (%s): fewer than 3 degrees of freedom." % law
    return ("K0 against a_f seed by seed (%s; each about its shape's mean, %d deposits of %d "
            "shapes): r = %.2f (p = %.1g, t with %d dof): %s."
            % (law, m["deposits"], m["shapes"], m["r"], m["p"], m["dof"], mirror_meaning(m)))


def force_lines(claims):
    """[(label, name, f)]: the default law's force lines (claims.json `forces`), then the
    other laws' at delta_r 0 (their `laws` entries), named with their law"""
    out = [(line, LINE_NAMES[line], f) for line, f in (claims.get("forces") or {}).items()]
    for entry in claims.get("laws", []):
        if entry["delta_r"] == 0 and entry.get("forces"):
            out += [("%s, %s" % (line, entry["law"]),
                     "%s, %s" % (LINE_NAMES[line], entry["law"]), f)
                    for line, f in entry["forces"].items()]
    return out


def forces_block(data):
    """the force measures along the lines of shapes and their trends (claims.json `forces`)"""
    if data.claims.get("forces") is None:
        return ("No line of shapes has 3 shapes with two deposits with window means of the "
                "force measures yet (sets `equilibrium`, `equilibrium_lines`).")
    per_shape, trends, notes = [], [], []
    for line, _, f in force_lines(data.claims):
        per_shape += [[line, "%g" % r["eta"], "%g" % r["zeta"], "%g" % r["a/c"],
                       "%d" % r["seeds"]] + [pm(r[q]["mean"], r[q]["se"], 3) for q in MEASURES]
                      for r in f["per_shape"]]
        for q in (q for q in MEASURES if q in f["trends"]):
            slope = f["trends"][q]["slope_per_unit_a/c"]
            end = f["trends"][q]["thinnest_minus_roundest"]
            top = f["trends"][q].get("thinnest_minus_largest")
            trends.append([line, NAMES[q], "%s (a/c %g-%g)" % (
                pm(slope["slope"], slope["se"], 4), slope["from_a/c"], slope["to_a/c"]),
                fit_cell(slope), slope["verdict"], pm(end["difference"], end["se"], 3),
                z_cell(end), end["verdict"], "-" if top is None else "%s than at %s: %s (%s): %s"
                % (shape(top["shapes"][0]), shape(top["shapes"][1]),
                   pm(top["difference"], top["se"], 3), z_cell(top), top["verdict"])])
        if f.get("a_n_at_least_1"):
            notes.append("%s: a_n >= 1 at %s, where the second-order form is negative near "
                         "pi/2; a_f's trend stops before" % (
                             line, ", ".join(shape(s) for s in f["a_n_at_least_1"])))
    text = (table(["line", "eta", "zeta", "a/c", "seeds", "a_n", "a_f", "a_n + a_f", "K0"],
                  per_shape)
            + "\n\n" + table(["line", "measure", "slope per unit a/c", "significance",
                               "verdict", "thinnest - roundest", "significance", "verdict",
                               "thinnest - largest (a saturating measure)"], trends))
    return text + "\n\n" + " ".join(
        ["%s." % n for n in notes] + [mirror_text(data.claims.get("force_mirror"), data.law)])


def force_line_text(name, f):
    """one line's force-weighted anisotropy a_n + a_f and its own part a_f against a/c"""
    t = f["trends"]
    total = t["a_total"]["slope_per_unit_a/c"]
    own = t.get("a_f", {}).get("slope_per_unit_a/c")
    first, last = f["per_shape"][0], f["per_shape"][-1]
    seeds = sorted({r["seeds"] for r in f["per_shape"]})
    return ("%s, %d deposits (%s seeds per shape): force-weighted anisotropy a_n + a_f "
            "%s at %s, %s at %s, slope %s per unit a/c (%s); the forces' own part a_f: %s"
            % (name, f["deposits"],
               "-".join("%d" % k for k in (seeds[0], seeds[-1])) if len(seeds) > 1
               else "%d" % seeds[0],
               pm(first["a_total"]["mean"], first["a_total"]["se"], 3),
               shape((first["eta"], first["zeta"])),
               pm(last["a_total"]["mean"], last["a_total"]["se"], 3),
               shape((last["eta"], last["zeta"])), pm(total["slope"], total["se"], 4),
               fit_cell(total), "fewer than 3 shapes with a_n < 1" if own is None else
               "slope %s (%s, a/c %g-%g)" % (pm(own["slope"], own["se"], 4), fit_cell(own),
                                             own["from_a/c"], own["to_a/c"])))


def forces_row(data):
    claim = ("abstract: the contact forces are increasingly preferred along the vertical as "
             "the shape deviates from a sphere")
    if "diagonal" not in (data.claims.get("forces") or {}):
        return [claim, "not measured: fewer than 3 diagonal shapes have two deposits with "
                "window means of the force measures", "undecided"]
    lines = force_lines(data.claims)
    verdicts = []
    for _, name, f in lines:
        t = f["trends"]
        verdicts.append("%s: increasingly vertical: %s; faster than the contact normals' "
                        "anisotropy (a_f): %s; K0: %s"
                        % (name, shape_of_trend(t["a_total"]),
                           shape_of_trend(t["a_f"]) if "a_f" in t else "-",
                           shape_of_trend(t["K0"])))
    return [claim, "; ".join(force_line_text(name, f) for _, name, f in lines),
            "; ".join(verdicts)]
