"""The histograms' verdicts of the study (claims.json `verdicts`, tools/study/study_claims.py).

* `binned`: a selection's seed-mean histograms with the per-bin standard error from the seed
  SD pooled per bin over each group of shapes (tools/study/study_stats.py); plot_figures draws
  these error bars.
* `crossings_both`: the two readings of the paper's "crossing" angles. (i) where a shape's
  curve crosses the isotropic value 1/(4 pi), per shape with the pooled error of its
  crossing; (ii) where the curves of two shapes cross each other, for every pair of
  aspherical shapes whose curves differ (|a_z| or |Q_zz| apart by >= 3 standard errors), with
  the crossing's error from the per-bin errors and the slope of the difference.
* `sphere_isotropy`: the sphere's contact normals against 1/(4 pi): per bin of the upper half
  (the curve is symmetric about pi/2 by construction) the relative deviation with its
  error from the per-bin seed SD pooled over the sphere's deposits of its law's selections
  (never below the bin's counting error), the largest deviation and chi^2 over the bins;
  Pearson's chi^2 of the counts (a bin's contacts ~ its fraction x Nslab Z) as a check that
  does not lean on a few seeds.
"""
import math

import numpy as np
from scipy import stats

from study_stats import Pooled, equivalent_sigma, pool

ISOTROPIC = 1.0 / (4.0 * math.pi)
FILES = {"contact_normals": ("contact_histo", False, "fabric_anisotropy"),    # file, rising,
         "long_axes": ("orient_histo", True, "Qzz")}                         # amplitude
PAIR_SIGMA = 3.0          # two curves "differ" when their amplitudes are this far apart
# the shapes of Figs. 7a and 8 (tools/plot/plot_figures.py): the diagonal and the thinnest spheroids
FIGURE_SHAPES = ((1.0, 1.0), (1.2, 1.2), (1.6, 1.6), (2.0, 2.0), (3.0, 3.0), (3.0, 1.0),
                 (1.0, 3.0))


def binned(shapes, histogram):
    """{shape: (theta, mean P, its per-bin standard error)} from {shape: [deposits]}"""
    name = FILES[histogram][0]
    theta = np.asarray(next(iter(shapes.values()))[0][name][0])
    per_seed = {s: np.asarray([d[name][1] for d in v]) for s, v in shapes.items()}
    errors = np.zeros((len(per_seed), len(theta)))
    for k in range(len(theta)):
        pooled = Pooled({s: p[:, k] for s, p in per_seed.items()})
        errors[:, k] = [pooled.se(s) if pooled.se(s) is not None else np.nan for s in per_seed]
    return {s: (theta, p.mean(axis=0), errors[i]) for i, (s, p) in enumerate(per_seed.items())}


def first_crossing(theta, f, rising=None):
    """the first zero of f in (0, pi/2) by linear interpolation: (theta, bin index) or None;
    rising None: either direction"""
    for k in range(len(theta) - 1):
        if theta[k + 1] > math.pi / 2 + 1e-9:
            break
        up, down = f[k] < 0 <= f[k + 1], f[k] > 0 >= f[k + 1]
        if (up if rising else down) if rising is not None else (up or down):
            return float(theta[k] + (theta[k + 1] - theta[k]) * f[k] / (f[k] - f[k + 1])), k
    return None


def zeros(theta, f):
    """the number of sign changes of f over the bins below pi/2"""
    upper = np.asarray(f)[np.asarray(theta) < math.pi / 2]
    return int(np.sum(np.sign(upper[1:]) * np.sign(upper[:-1]) < 0))


def crossing_error(theta, f, err, k):
    """the error of the zero of f between bins k and k+1: the rms of the two bins' errors
    over the slope of f there"""
    slope = (f[k + 1] - f[k]) / (theta[k + 1] - theta[k])
    return float(math.hypot(err[k], err[k + 1]) / math.sqrt(2) / abs(slope))


def isotropic_crossings(shapes, histogram):
    """per aspherical shape the crossing with 1/(4 pi): its mean over the seeds and the
    error from the crossing's SD pooled per group (deposits whose curve does not cross are
    left out)"""
    name, rising, _ = FILES[histogram]
    per_seed = {}
    for s, deposits in shapes.items():
        if s == (1.0, 1.0):
            continue
        v = [first_crossing(np.asarray(d[name][0]), np.asarray(d[name][1]) - ISOTROPIC, rising)
             for d in deposits]
        v = [c[0] for c in v if c is not None]
        if v:
            per_seed[s] = v
    if not per_seed:
        return {"shapes": []}
    pooled = Pooled(per_seed)
    rows = [{"eta": s[0], "zeta": s[1], "theta": pooled.mean(s), "se": pooled.se(s),
             "seeds": len(v)} for s, v in per_seed.items()]
    t = np.array([r["theta"] for r in rows])
    return {"shapes": rows, "groups": pooled.groups, "mean": float(t.mean()),
            "median": float(np.median(t)),
            "sd_over_shapes": float(t.std(ddof=1)) if len(t) > 1 else None,
            "range": [float(t.min()), float(t.max())]}


def mutual_crossings(shapes, histogram, amplitude, only=None):
    """the crossings of the seed-mean curves of every pair of aspherical shapes (of `only`,
    if given) whose amplitudes (Pooled) differ by PAIR_SIGMA standard errors or more"""
    curves = binned({s: v for s, v in shapes.items() if s != (1.0, 1.0)}, histogram)
    keys = sorted(k for k in curves if only is None or k in only)
    found, ambiguous, similar = [], 0, 0
    for i, a in enumerate(keys):
        for b in keys[i + 1:]:
            se = math.hypot(amplitude.se(a) or 0.0, amplitude.se(b) or 0.0)
            if se == 0 or abs(amplitude.mean(a) - amplitude.mean(b)) < PAIR_SIGMA * se:
                similar += 1
                continue
            theta, pa, ea = curves[a]
            f = pa - curves[b][1]
            if zeros(theta, f) != 1:
                ambiguous += 1
                continue
            c, k = first_crossing(theta, f)
            err = np.hypot(ea, curves[b][2])
            found.append({"pair": [list(a), list(b)], "theta": c,
                          "se": crossing_error(theta, f, err, k)})
    out = {"pairs": len(found), "similar_pairs": similar, "ambiguous_pairs": ambiguous,
           "crossings": found}
    if found:
        t = np.array([r["theta"] for r in found])
        out.update(median=float(np.median(t)), quartiles=[float(np.percentile(t, 25)),
                                                          float(np.percentile(t, 75))],
                   range=[float(t.min()), float(t.max())],
                   median_se=float(np.median([r["se"] for r in found])))
    return out


def crossings_both(selection, pi_fraction):
    """both readings for both histograms; pi_fraction: the paper's angle per histogram"""
    out = {}
    for histogram, (_, _, amplitude) in FILES.items():
        if not selection.has(amplitude):
            continue
        iso = isotropic_crossings(selection.shapes, histogram)
        mutual = mutual_crossings(selection.shapes, histogram, selection.quantity(amplitude))
        paper = pi_fraction[histogram] * math.pi
        figure = mutual_crossings(selection.shapes, histogram, selection.quantity(amplitude),
                                  FIGURE_SHAPES)
        out[histogram] = {"paper": paper, "isotropic_level": iso, "each_other": mutual,
                          "each_other_figure_shapes": figure}
    return out


def sphere_isotropy(selections, key):
    """the sphere's contact normals in selection `key` (delta_r, law) against 1/(4 pi); the
    per-bin error from the seed SD pooled over the sphere's deposits of every delta_r of the
    same law (the sphere is one shape per selection, too few seeds to pool within one; another
    law's beds differ in structure, and their scatter is not this law's); the bin of the most
    significant deviation and the bin of the largest"""
    name = FILES["contact_normals"][0]
    spheres = {k: sel.shapes[(1.0, 1.0)] for k, sel in selections.items()
               if (1.0, 1.0) in sel.shapes and k[1] == key[1]}
    if key not in spheres:
        return None
    theta = np.asarray(spheres[key][0][name][0])
    half = theta < math.pi / 2
    rel = {k: np.asarray([d[name][1] for d in v])[:, half] / ISOTROPIC - 1
           for k, v in spheres.items()}
    dof = pool([r[:, 0] for r in rel.values()])[1]
    if not dof:
        return None    # no sphere with two seeds: no error
    sd = np.array([pool([r[:, b] for r in rel.values()])[0] for b in range(int(half.sum()))])
    mean, n = rel[key].mean(axis=0), len(rel[key])
    # cross-check: counting errors, counts = fraction * samples, samples ~ Nslab Z; the
    # Poisson error of d = counts / expected - 1 is sqrt(counts) / expected = (1 + d) / sqrt
    known = all(d.get("Nslab") and d.get("Z") for d in spheres[key])
    counts = sum(np.asarray(d[name][2])[half] * float(d["Nslab"]) * float(d["Z"])
                 for d in spheres[key]) if known else None
    se_counting = (1 + mean) / np.sqrt(counts) if known else None
    # a seed SD of few dof can come out small by chance in a bin: never below counting
    se = sd / math.sqrt(n) if not known else np.maximum(sd / math.sqrt(n), se_counting)
    z = mean / se

    def bin_entry(k):
        return {"theta": float(theta[half][k]), "deviation": float(mean[k]), "se": float(se[k]),
                "z": float(z[k]), "z_equivalent": equivalent_sigma(float(z[k]), dof)}
    chi2 = float(np.sum(z ** 2))
    bins = int(half.sum()) - 1    # the normalisation fixes one combination of the bins
    # Pearson's chi^2, sum (counts - expected)^2 / expected
    chi2_counting = float(np.sum(mean ** 2 * counts / (1 + mean))) if known else None
    return {"seeds": n, "dof_of_the_errors": dof, "theta": theta[half].tolist(),
            "deviation": mean.tolist(), "se": se.tolist(),
            "se_counting": se_counting.tolist() if known else None,
            "most_significant": bin_entry(int(np.argmax(np.abs(z)))),
            "largest": bin_entry(int(np.argmax(np.abs(mean)))),
            "chi2_counting": chi2_counting,
            "p_counting": float(stats.chi2.sf(chi2_counting, bins)) if known else None,
            "within_10_percent": bool(np.all(np.abs(mean) <= 0.10)),
            "chi2": chi2, "chi2_dof": bins, "p_isotropic": float(stats.chi2.sf(chi2, bins))}


def seed_mean_histogram(deposits, name):
    """theta, the mean P over the deposits, and its standard error per bin (None: one seed)"""
    curves = [d[name] for d in deposits]
    theta = np.asarray(curves[0][0])
    if any(len(c[0]) != len(theta) for c in curves):
        raise ValueError("histograms with different bins: %s" % [d["folder"] for d in deposits])
    p = np.asarray([c[1] for c in curves])
    sem = p.std(axis=0, ddof=1) / math.sqrt(len(p)) if len(p) > 1 else None
    return theta, p.mean(axis=0), sem


def histogram_difference(deposits, reference, name):
    """rms over the bins of the seed-mean difference of histogram `name` (a deposit's key:
    contact_histo, orient_histo), and what the seed scatter gives"""
    theta, p, sem = seed_mean_histogram(deposits, name)
    theta0, p0, sem0 = seed_mean_histogram(reference, name)
    if not np.allclose(theta, theta0):
        raise ValueError("%s: different bins in the two sets of deposits" % name)
    noise = (float(np.sqrt(np.mean(sem ** 2 + sem0 ** 2)))
             if sem is not None and sem0 is not None else None)
    return {"rms_difference": float(np.sqrt(np.mean((p - p0) ** 2))),
            "rms_seed_scatter": noise, "seeds": [len(deposits), len(reference)]}
