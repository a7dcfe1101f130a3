"""delta_r at matched depth and the finite-size check of the study (claims.json `depth`).

At the study's N the box's edge is 0.3 sqrt(N) for every delta_r, so a polydisperse deposit
holds less solid (0.69 of it at delta_r 0.6) and its measuring slab is thinner: delta_r is
confounded with depth. The sets matched_depth_* of workflow/config/paper.yaml pour N / <V>
particles (<V>: the mean particle volume over the mono-sized one) into the box of the study's
N, so their slabs hold the solid of the delta_r 0 deposits. Here, per delta_r, over the
shapes poured at matched depth: X(delta_r, matched) - X(0) and, side by side on the same
shapes, X(delta_r, the study's N) - X(0), and their difference X(matched) - X(the study's N)
(`depth_effect`: what depth does), with the slabs' thicknesses (shape_effects and
depth of tools/study/study_verdicts.py; pooled seed SDs per group of shapes). The force measures
(tools/study/study_forces.py) the same way over the deposits that have them (`forces`), and their
trends along the diagonal at that delta_r (`force_trends`) beside delta_r 0's over the same
shapes (`force_trends_at_0`): does the force anisotropy grow with asphericity in a
polydisperse deposit too?

Finite size: each other (N, box) of the default law at delta_r 0 (the sets finite_size_*: a
box twice as wide at the same height, N x 4 in its default box; and the study's box four times
as deep, a `width` given) against the study's N in its default box, shape by shape: the
quantities, the force measures and both histograms (the rms over the bins of the seed-mean
difference against the rms of its standard error).
"""
from study_forces import MEASURES, forces
from study_histograms import FILES, histogram_difference
from study_verdicts import depth, shape_effects


def box(d):
    """a deposit's (N, width); width None in in.deposit's default box"""
    return int(d["N"]), (float(d["width"]) if d.get("width") else None)


def depth_claims(everything, law, n):
    """claims.json `depth` from a study_claims.Selection of every deposit (any N and box), or
    None when no deposit of the law is in another box or at another N"""
    mine = [d for d in everything.deposits if d["law"] == law]

    def select(dr, keep):
        return everything.subset(lambda d: d["law"] == law and float(d["delta_r"]) == dr
                                 and keep(box(d)))

    def subset(sel, shapes):
        return sel.subset(lambda d: (float(d["eta"]), float(d["zeta"])) in shapes)

    study_box = (n, None)
    base = select(0.0, lambda b: b == study_box)
    out = {"matched": [], "finite_size": []}
    for dr in sorted({float(d["delta_r"]) for d in mine if box(d)[1] and float(d["delta_r"])}):
        matched = select(dr, lambda b: b[1] is not None)
        fixed = select(dr, lambda b: b == study_box)
        shapes = set(matched.shapes)
        out["matched"].append({
            "delta_r": dr, "N": sorted({box(d)[0] for d in matched.deposits}),
            "width": sorted({box(d)[1] for d in matched.deposits}),
            "shapes": [list(s) for s in sorted(shapes)],
            "depth": {"matched": depth(matched), "study_N": depth(subset(fixed, shapes)),
                      "delta_r_0": depth(subset(base, shapes))},
            "matched_depth": shape_effects(matched, base, "at delta_r %g, matched depth" % dr),
            "study_N": shape_effects(fixed, base, "at delta_r %g, N %d" % (dr, n), shapes),
            # what the depth itself does: matched depth against the study's N, shape by shape
            "depth_effect": shape_effects(matched, fixed, "at matched depth than at N %d" % n,
                                          shapes),
            "forces": shape_effects(matched.with_forces(), base.with_forces(),
                                    "at delta_r %g, matched depth" % dr, quantities=MEASURES),
            "force_trends": forces(matched.deposits),
            "force_trends_at_0": forces(subset(base, shapes).deposits)})
    for other in sorted({box(d) for d in mine if float(d["delta_r"]) == 0.0} - {study_box},
                        key=lambda b: (b[0], b[1] or 0.0)):
        sel = select(0.0, lambda b: b == other)
        label = "at N %d%s" % (other[0], "" if other[1] is None else ", width %g" % other[1])
        shapes = set(sel.shapes)
        out["finite_size"].append({
            "N": other[0], "width": other[1], "shapes": [list(s) for s in sorted(shapes)],
            "depth": depth(sel), "depth_at_study_N": depth(subset(base, shapes)),
            "effects": shape_effects(sel, base, label, shapes),
            "forces": shape_effects(sel.with_forces(), base.with_forces(), label, shapes,
                                    MEASURES),
            "histograms": [dict({"eta": s[0], "zeta": s[1]}, **{
                h: histogram_difference(sel.shapes[s], base.shapes[s], FILES[h][0])
                for h in FILES}) for s in sorted(shapes) if s in base.shapes]})
    return out if out["matched"] or out["finite_size"] else None
