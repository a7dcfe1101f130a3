"""The flow solve's permeability along the study's lines (doc/study.md, "Permeability along the
lines"; the solves: tools/pores/pore_flow_lines.py, one results/flow_lines/<run>.json per
deposit).

    deposit_row(json) -> the deposit's k_zz, k_xx, k_xx / k_zz, k_zz / k_KC with their errors
    shape_means(rows) -> per shape the seeds' mean of each quantity and its two errors
    verdicts(means)   -> each shape against the spheres (k) and against isotropy (k_xx / k_zz)

Errors. A deposit's k carries the error of the extrapolation to a vanishing voxel
(tools/pores/pore_flow_fit.py); the seeds scatter beyond it (each deposit is one 5 d box, so
the box's sampling error is part of that scatter). A shape's mean has a statistical error,
the seeds' relative SD pooled over every shape with two seeds or more (study_stats.pool) /
sqrt(seeds), and a systematic one, the rms of its deposits' relative extrapolation errors,
not reduced by averaging (the voxel error is a bias the seeds share). A verdict needs SIGMA
standard errors of the two combined, the statistical part taken as Student's t with the pooled
SD's degrees of freedom (study_stats.decide).
"""
import math

import numpy as np

from study_stats import LINES, decide, on_line, pool, seeds_needed, significance

# quantity: (the deposit's error of it, what the verdict compares it with)
QUANTITIES = {"k_zz": ("k_zz_error", "spheres"), "k_xx": ("k_xx_error", "spheres"),
              "anisotropy": ("anisotropy_error", "isotropy"),
              "k_zz_over_kozeny_carman": ("k_zz_error", "spheres")}
SPHERES = (1.0, 1.0)


def deposit_row(r):
    """one deposit's row from pore_flow_lines.py's json: k in d^2, each with its error"""
    k = r["flow"]
    kxx = 0.5 * (k["xx"] + k["yy"]) if "yy" in k else k["xx"]
    return {"eta": r["eta"], "zeta": r["zeta"], "seed": r["seed"], "porosity": r["porosity"],
            "k_xx": k["xx"], "k_xx_error": k.get("xx_error", ""),
            "k_yy": k.get("yy", ""), "k_zz": k["zz"], "k_zz_error": k.get("zz_error", ""),
            "anisotropy": k["anisotropy_xx_zz"],
            "anisotropy_error": k.get("anisotropy_xx_zz_error", ""),
            "k_zz_over_kozeny_carman": k["zz"] / r["k_kozeny_carman"],
            "k_xx_over_kozeny_carman": kxx / r["k_kozeny_carman"]}


def relative_error(row, q):
    """the deposit's extrapolation error of q relative to its value (None: one voxel only)"""
    error_key = QUANTITIES[q][0]
    err = row.get(error_key)
    if err in ("", None):
        return None
    base = "anisotropy" if q == "anisotropy" else error_key[:-len("_error")]
    return float(err) / float(row[base])


def shape_means(rows):
    """{(eta, zeta): {"seeds": [...], q: {mean, stat, sys}}, "pooled": {q: (sd, dof)}}: stat
    the seeds' standard error (relative SD pooled over the shapes), sys the rms relative
    extrapolation error, both times the mean"""
    shapes = {}
    for r in rows:
        shapes.setdefault((float(r["eta"]), float(r["zeta"])), []).append(r)
    out = {"pooled": {}}
    for s, rs in shapes.items():
        out[s] = {"seeds": sorted(int(r["seed"]) for r in rs)}
    for q in QUANTITIES:
        relative = [np.array([r[q] for r in rs]) / np.mean([r[q] for r in rs])
                    for rs in shapes.values()]
        sd, dof = pool(relative)
        out["pooled"][q] = (sd, dof)
        for s, rs in shapes.items():
            mean = float(np.mean([r[q] for r in rs]))
            errors = [relative_error(r, q) for r in rs]
            sys = (None if None in errors else
                   mean * math.sqrt(np.mean(np.square(errors))))
            stat = None if sd is None else mean * sd / math.sqrt(len(rs))
            out[s][q] = {"mean": mean, "stat": stat, "sys": sys}
    return out


def verdicts(means, sigma=None):
    """[(shape, q, decision)]: k and k / k_KC against the spheres', k_xx / k_zz against 1"""
    extra = {} if sigma is None else {"sigma": sigma}
    out = []
    shapes = sorted(s for s in means if s != "pooled")
    for q, (_, against) in QUANTITIES.items():
        sd, dof = means["pooled"][q]
        for s in shapes:
            m = means[s][q]
            if against == "spheres":
                if s == SPHERES or SPHERES not in means:
                    continue
                ref = means[SPHERES][q]
                diff = m["mean"] - ref["mean"]
                parts = [(m["stat"], len(means[s]["seeds"])),
                         (ref["stat"], len(means[SPHERES]["seeds"]))]
                sys = math.hypot(m["sys"] or 0.0, ref["sys"] or 0.0)
                yes, no = "higher than the spheres'", "lower than the spheres'"
            else:
                diff = m["mean"] - 1.0
                parts = [(m["stat"], len(means[s]["seeds"]))]
                sys = m["sys"] or 0.0
                yes, no = "k_xx > k_zz", "k_xx < k_zz"
            stat = (None if any(p[0] is None for p in parts)
                    else math.sqrt(sum(p[0] ** 2 for p in parts)))
            z = significance(diff, stat, sys)
            compared = (s, SPHERES) if against == "spheres" else (s,)
            seeds = "-".join(sorted({"%d" % len(means[t]["seeds"]) for t in compared}))
            needed = seeds_needed(diff, parts, sys, **extra)
            d = decide(z, needed, seeds, yes, no, dof, **extra)
            d.update(difference=diff, stat=stat, sys=sys)
            out.append((s, q, d))
    return out


def line_of(shape):
    """the names of the lines the shape lies on (the spheres lie on all three)"""
    return [name for name in LINES if on_line(name, *shape)]
