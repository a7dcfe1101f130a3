"""Statistics of the study (doc/study.md, tools/study/study_claims.py, tools/plot/plot_figures.py).

* The seed-to-seed SD of one deposit, pooled per group of shapes within one selection (one
  delta_r, one tangential law): `spheroids` (the sphere and the lines zeta = 1 and eta = 1),
  `general a/c<4` and `general a/c>=4` (eta, zeta > 1, split at the total aspect ratio
  a/c = eta zeta = 4: the thin shapes scatter 2-3x more). Both general halves merge into
  `general` when either has fewer than MIN_DOF degrees of freedom; a group still below
  MIN_DOF takes the pool of its whole selection (`all`). A point's standard error is its
  group's SD / sqrt(its seeds): with 2-3 seeds its own SD has 1-2 degrees of freedom.
* The maximum of a line: parabolas through 3, 5 and 7 points around the highest point and a
  cubic through 7; each with a parametric bootstrap over the points' standard errors. The
  5-point parabola is the nominal fit, half the spread of the four is the fit-window
  systematic.
* Significance of a difference and the seeds per point that a 3-sigma verdict needs; the
  weighted slope of a trend.
"""
import math
import re

import numpy as np
from scipy import stats

MIN_DOF = 4
THIN = 4.0                 # a/c from which a general shape counts as thin
SIGMA = 3.0                # a verdict needs this many standard errors
CHANCE_P = 0.0027          # the two-sided p of SIGMA: a chi^2 beyond it is not chance
LARGE = 1000               # seeds per point beyond any study: "more than LARGE"
BOOTSTRAP = 2000
WINDOWS = (("parabola 3", 3, 2), ("parabola 5", 5, 2), ("parabola 7", 7, 2), ("cubic 7", 7, 3))
NOMINAL = "parabola 5"

# the study's lines of shapes: name -> (on the line, beyond the spheres; the axis that is x)
LINES = {"diagonal": (lambda e, z: e == z, "eta"),
         "prolate": (lambda e, z: z == 1.0 and e > 1.0, "eta"),
         "oblate": (lambda e, z: e == 1.0 and z > 1.0, "zeta")}


def on_line(name, eta, zeta):
    """whether the shape lies on the line, spheres included"""
    return LINES[name][0](eta, zeta) or eta == zeta == 1.0


def shape_group(eta, zeta):
    if eta == 1.0 or zeta == 1.0:
        return "spheroids"
    return "general a/c<4" if eta * zeta < THIN else "general a/c>=4"


def pool(samples):
    """(SD, degrees of freedom) pooled over the lists of two values or more; SD None if 0"""
    samples = [np.asarray(v, float) for v in samples if len(v) > 1]
    dof = sum(len(v) - 1 for v in samples)
    if not dof:
        return None, 0
    return math.sqrt(sum((len(v) - 1) * v.var(ddof=1) for v in samples) / dof), dof


def pooled_groups(shapes):
    """shapes: {(eta, zeta): [value per seed]} of one selection. Returns (groups, of_shape):
    groups {name: {sd, dof, shapes}}, of_shape {(eta, zeta): group name}"""
    of_shape = {s: shape_group(*s) for s in shapes}
    halves = ("general a/c<4", "general a/c>=4")
    dofs = {g: pool([shapes[s] for s in shapes if of_shape[s] == g])[1] for g in halves}
    if any(g in of_shape.values() and dofs[g] < MIN_DOF for g in halves):
        of_shape = {s: ("general" if g in halves else g) for s, g in of_shape.items()}
    whole_sd, whole_dof = pool(list(shapes.values()))
    groups = {}
    for g in sorted(set(of_shape.values())):
        members = [s for s in shapes if of_shape[s] == g]
        sd, dof = pool([shapes[s] for s in members])
        groups[g] = {"sd": sd, "dof": dof, "shapes": len(members)}
    for g, entry in list(groups.items()):
        if entry["dof"] < MIN_DOF and whole_dof > entry["dof"]:
            for s in shapes:
                if of_shape[s] == g:
                    of_shape[s] = "all"
            del groups[g]
            groups["all"] = {"sd": whole_sd, "dof": whole_dof, "shapes": len(shapes)}
    return groups, of_shape


class Pooled:
    """the pooled SDs of one quantity in one selection: sd(shape), se(shape)"""

    def __init__(self, shapes):
        self.values = {s: [float(x) for x in v] for s, v in shapes.items()}
        self.groups, self.of_shape = pooled_groups(self.values)

    def sd(self, shape):
        return self.groups[self.of_shape[shape]]["sd"]

    def dof(self, shape):
        return self.groups[self.of_shape[shape]]["dof"]

    def mean(self, shape):
        return float(np.mean(self.values[shape]))

    def se(self, shape):
        sd = self.sd(shape)
        return None if sd is None else sd / math.sqrt(len(self.values[shape]))


def vertex(x, y, degree):
    """the maximum of the least-squares polynomial inside [x0, x-1]; y may be 2-d (one column
    per draw). Returns arrays (x_max, y_max), nan where there is none."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    cols = y.reshape(len(x), -1)
    c = np.polyfit(x, cols, degree)
    if degree == 2:
        with np.errstate(divide="ignore", invalid="ignore"):
            xm = np.where(c[0] < 0, -c[1] / (2 * c[0]), np.nan)
    else:    # cubic: the root of f' = a x^2 + b x + cc where f'' = 2 a x + b < 0, in the
        # stable form (q / a, cc / q): the cubic term of a near-parabola is ~0
        a, b, cc = 3 * c[0], 2 * c[1], c[2]
        disc = b * b - 4 * a * cc
        with np.errstate(divide="ignore", invalid="ignore"):
            q = -0.5 * (b + np.where(b < 0, -1.0, 1.0) * np.sqrt(np.abs(disc)))
            r1, r2 = q / a, cc / q
            xm = np.where(2 * a * r1 + b < 0, r1, r2)
            xm = np.where(disc >= 0, xm, np.nan)
    xm = np.where((xm >= x[0]) & (xm <= x[-1]), xm, np.nan)
    ym = sum(c[k] * xm ** (degree - k) for k in range(degree + 1))
    return xm, ym


def window(n, k, size):
    """indices of `size` consecutive points around k among n (shifted at the ends)"""
    lo = max(0, min(k - size // 2, n - size))
    return np.arange(lo, lo + size) if size <= n else None


def line_maximum(x, means, errors, rng, draws=BOOTSTRAP):
    """x sorted; errors: each mean's standard error (None: no bootstrap). The highest point,
    each window's fit with its bootstrap SD, the nominal fit and the fit-window systematic."""
    x, means = np.asarray(x, float), np.asarray(means, float)
    k = int(np.argmax(means))
    out = {"x_highest": float(x[k]), "y_highest": float(means[k]),
           "at_edge": k in (0, len(x) - 1)}
    if out["at_edge"]:
        return out
    fits = {}
    for name, size, degree in WINDOWS:
        idx = window(len(x), k, size)
        if idx is None:
            continue
        xm, ym = vertex(x[idx], means[idx], degree)
        if np.isnan(xm[0]):
            fits[name] = {"window": [float(x[idx[0]]), float(x[idx[-1]])], "x_max": None}
            continue
        fit = {"window": [float(x[idx[0]]), float(x[idx[-1]])], "x_max": float(xm[0]),
               "y_max": float(ym[0])}
        if errors is not None:
            noise = rng.normal(0.0, 1.0, (len(idx), draws)) * np.asarray(errors, float)[idx, None]
            bx, by = vertex(x[idx], means[idx, None] + noise, degree)
            ok = ~np.isnan(bx)
            fit.update(kept=int(ok.sum()), draws=draws)
            if ok.sum() > 1:
                fit.update(x_sd=float(bx[ok].std(ddof=1)), y_sd=float(by[ok].std(ddof=1)))
        fits[name] = fit
    out["fits"] = fits
    good = [f for f in fits.values() if f["x_max"] is not None]
    nominal = NOMINAL if NOMINAL in fits else "parabola 3"    # fewer than 5 points
    if nominal in fits and fits[nominal]["x_max"] is not None:
        out["nominal"] = nominal
        out.update({k2: fits[nominal][k2] for k2 in ("x_max", "y_max", "x_sd", "y_sd")
                    if k2 in fits[nominal]})
        out["x_sys"] = (max(f["x_max"] for f in good) - min(f["x_max"] for f in good)) / 2
        out["y_sys"] = (max(f["y_max"] for f in good) - min(f["y_max"] for f in good)) / 2
    return out


def significance(difference, stat, sys=0.0):
    """difference / sqrt(stat^2 + sys^2); None if the error is unknown or zero"""
    if stat is None:
        return None
    err = math.hypot(stat, sys or 0.0)
    return difference / err if err > 0 else None


def weighted_slope(x, y, se):
    """least squares of y against x with weights 1/se^2: (slope, its standard error)"""
    f = line_fit(x, y, se)
    return f["slope"], f["se_fit"]


def line_fit(x, y, se):
    """the weighted straight line with its lack of fit: slope, se_fit (from the points'
    errors), chi2 about the line on n - 2 degrees of freedom, its p and the Birge ratio
    sqrt(chi2 / dof). Where chi2 is beyond chance (p < CHANCE_P) the points scatter about the
    line more than their errors allow (the trend is not a line): the slope's error `se` is
    then se_fit times the Birge ratio, with n - 2 degrees of freedom (`dof_lack_of_fit`)"""
    w = 1 / np.asarray(se, float) ** 2
    x, y = np.asarray(x, float), np.asarray(y, float)
    xm = np.sum(w * x) / w.sum()
    sxx = np.sum(w * (x - xm) ** 2)
    slope = float(np.sum(w * (x - xm) * y) / sxx)
    intercept = float(np.sum(w * y) / w.sum() - slope * xm)
    chi2 = float(np.sum(w * (y - intercept - slope * x) ** 2))
    dof = len(x) - 2
    p = float(stats.chi2.sf(chi2, dof)) if dof > 0 else None
    birge = math.sqrt(chi2 / dof) if dof > 0 else None
    scaled = p is not None and p < CHANCE_P and birge > 1
    se_fit = float(1 / math.sqrt(sxx))
    return {"slope": slope, "se_fit": se_fit, "se": se_fit * birge if scaled else se_fit,
            "chi2": chi2, "chi2_dof": dof, "chi2_p": p, "birge_ratio": birge,
            "lack_of_fit": scaled, "dof_lack_of_fit": dof if scaled else None}


def seeds_needed(difference, parts, sys=0.0, sigma=SIGMA):
    """seeds per point for `difference` to be `sigma` standard errors of the normal, the
    statistical error shrinking as 1/sqrt(seeds): a lower bound, as Student's t at the degrees
    of freedom of those seeds needs as many or more. parts [(standard error now, seeds now),
    ...], one per independent term. None when there is no difference, or when the fixed
    systematic alone is a third of the difference or more (no number of seeds decides it)."""
    if any(se is None for se, _ in parts):
        return None
    room = (difference / sigma) ** 2 - (sys or 0.0) ** 2
    if room <= 0:
        return None
    return max(2, math.ceil(sum(se * se * n for se, n in parts) / room))


def equivalent_sigma(z, dof):
    """the normal z of the same two-sided p as Student's t = z with `dof` degrees of freedom
    (the pooled SD's): a few degrees of freedom widen the tails"""
    if z is None or not dof:
        return z
    p = 2 * stats.t.sf(abs(z), dof)
    return math.copysign(float(stats.norm.isf(p / 2)), z)


def effective_dof(stat, dof, sys):
    """Welch-Satterthwaite's degrees of freedom of sqrt(stat^2 + sys^2) where stat has dof and
    the systematic sys, not estimated from the seeds, has infinitely many:
    dof (1 + sys^2 / stat^2)^2; the normal (None) without a statistical part"""
    if not dof:
        return dof
    if not stat:
        return None
    return dof * (1.0 + (sys or 0.0) ** 2 / stat ** 2) ** 2


def seeds_words(seeds):
    """'1 seed', '2 seeds', '1-2 seeds': the seeds per point as a verdict says them"""
    return "%s seed%s" % (seeds, "" if str(seeds) == "1" else "s")


NOT_A_LINE = "no number of seeds decides it: the shapes leave the line beyond chance"


def decide(z, needed, seeds, yes, no, dof=None, sigma=SIGMA, why_no_seeds=None):
    """the verdict at `sigma` on z (taken as Student's t with `dof` degrees of freedom when
    given): {z, dof, z_equivalent, seeds_needed (None once decided), verdict}; why_no_seeds:
    why no number of seeds decides it where needed is None (default: no difference, or a
    systematic of a third of it or more)"""
    ze = equivalent_sigma(z, dof)
    out = {"z": z, "dof": dof, "z_equivalent": ze, "seeds_needed": None}
    if ze is None:
        out["verdict"] = "undecided: no error estimate"
    elif ze >= sigma:
        out["verdict"] = yes
    elif ze <= -sigma:
        out["verdict"] = no
    elif needed is None:
        out["verdict"] = "undecided at %s; %s" % (
            seeds_words(seeds), why_no_seeds or "no number of seeds decides it at this difference")
    else:
        needed = max(needed, max(int(k) for k in re.findall(r"\d+", str(seeds))) + 1)
        out["seeds_needed"] = needed
        out["verdict"] = ("undecided at %s; needs more than %d (the difference measured "
                          "is near 0)" % (seeds_words(seeds), LARGE) if needed > LARGE else
                          "undecided at %s; needs at least %d" % (seeds_words(seeds), needed))
    return out


def sign_test(diffs):
    """(positive, total, two-sided binomial p) of the signs of diffs (zeros dropped)"""
    d = [x for x in diffs if x != 0]
    n, k = len(d), sum(1 for x in d if x > 0)
    if not n:
        return k, n, None
    tail = sum(math.comb(n, j) for j in range(0, min(k, n - k) + 1)) / 2 ** n
    return k, n, min(1.0, 2 * tail)
