"""A silo's discharge through an orifice (examples/discharge): the steady mass flow rate from the
discharged mass against time, and Beverloo's law fitted to the rates of several orifices.

Beverloo (1961): the mass flow rate through a circular orifice of diameter D0 in a flat floor,

    W = C rho_b sqrt(g) (D0 - k d)^(5/2),

rho_b the bulk density, d the particle diameter (here the volume-equivalent one). W^(2/5) is
linear in D0: W^(2/5) = s (D0 - k d) with s = (C rho_b sqrt(g))^(2/5), so a straight line
through the points (D0, W^(2/5)) gives C = s^(5/2) / (rho_b sqrt(g)) and k = -b / (s d) from its
slope s and intercept b. The law is for a steady rate: a window whose time blocks drift
(block_trend) is reported, not fitted.
"""
import math

import numpy as np
from scipy import stats

STEADY_P = 0.05    # a window whose blocks' trend has a smaller p is not a steady rate
# nor is one whose trend changes the rate by more than this across it, whatever its p: five
# blocks detect a drift only when it is several times the blocks' scatter
STEADY_RISE = 0.2


def steady_rate(t, mass, t0, blocks=5):
    """The steady rate of the discharged mass `mass` (cumulative, at times t) over t >= t0: the
    mean rate (the mass discharged over the window's span), its standard error from `blocks`
    equal time blocks (SD of the blocks' rates / sqrt(blocks): successive increments are
    correlated, so the blocks, not the samples, are the independent measurements), the
    least-squares slope and the blocks' rates. Needs >= 2 samples per block."""
    t, mass = np.asarray(t, dtype=float), np.asarray(mass, dtype=float)
    keep = t >= t0
    t, mass = t[keep], mass[keep]
    if blocks < 2 or len(t) < 2 * blocks:
        raise ValueError(f"steady_rate: {len(t)} samples after t0 = {t0} for {blocks} blocks "
                         "(needs >= 2 blocks, >= 2 samples each)")
    edges = np.linspace(t[0], t[-1], blocks + 1)
    at = np.interp(edges, t, mass)
    rates = np.diff(at) / np.diff(edges)
    slope = float(np.polyfit(t, mass, 1)[0])
    return {"rate": float((mass[-1] - mass[0]) / (t[-1] - t[0])),
            "se": float(np.std(rates, ddof=1) / math.sqrt(blocks)),
            "slope": slope, "blocks": rates.tolist(), "t0": float(t[0]), "t1": float(t[-1])}


def block_trend(rates):
    """Whether the blocks' rates drift through the window: the least-squares line of the rate
    against the block's index, its change across the window relative to the mean rate
    ("rise"), and the two-sided p of its slope (Student's t with blocks - 2 degrees of
    freedom). Steady: p >= STEADY_P and abs(rise) <= STEADY_RISE (at 5 % one steady window in
    twenty fails by chance; the test alone catches a drift of 3 blocks' SDs across the window
    in about a third of the windows, hence the bound on its size). A window without flow
    (a clogged orifice) is not steady."""
    rates = np.asarray(rates, dtype=float)
    if not rates.mean() > 0:
        return {"rise": None, "p": None, "steady": False}
    fit = stats.linregress(np.arange(len(rates)), rates)
    p = float(fit.pvalue) if fit.stderr > 0 else (1.0 if fit.slope == 0 else 0.0)
    rise = float(fit.slope * (len(rates) - 1) / rates.mean())
    return {"rise": rise, "p": p, "steady": p >= STEADY_P and abs(rise) <= STEADY_RISE}


def beverloo(d0, c, k, rho_b, d=1.0, g=1.0):
    """Beverloo's rate (0 where the orifice is not wider than k d)"""
    gap = np.clip(np.asarray(d0, dtype=float) - k * d, 0.0, None)
    return c * rho_b * math.sqrt(g) * gap ** 2.5


def fit_beverloo(d0, rate, se, rho_b, d=1.0, g=1.0):
    """Beverloo's C and k from the rates `rate` (standard errors `se`) at the orifice diameters
    d0: the weighted straight line through (D0, W^(2/5)) (weights from se, propagated:
    se(W^(2/5)) = (2/5) W^(-3/5) se(W)); C, k and their standard errors from the line's
    covariance (scaled by the reduced chi^2 when that is above 1: scatter beyond the errors
    widens them), their correlation, chi^2 and the degrees of freedom."""
    d0, rate, se = (np.asarray(v, dtype=float) for v in (d0, rate, se))
    if len(d0) < 3 or np.any(rate <= 0) or np.any(se <= 0):
        raise ValueError("fit_beverloo: needs >= 3 orifices with positive rates and errors")
    y = rate ** 0.4
    sy = 0.4 * rate ** -0.6 * se
    a = np.column_stack([d0, np.ones_like(d0)]) / sy[:, None]
    cov = np.linalg.inv(a.T @ a)
    s, b = cov @ (a.T @ (y / sy))
    chi2 = float(np.sum(((s * d0 + b - y) / sy) ** 2))
    dof = len(d0) - 2
    if dof > 0 and chi2 / dof > 1.0:
        cov = cov * (chi2 / dof)
    c = s ** 2.5 / (rho_b * math.sqrt(g))
    k = -b / (s * d)
    grad_c = np.array([2.5 * c / s, 0.0])
    grad_k = np.array([b / (s * s * d), -1.0 / (s * d)])
    dc, dk = math.sqrt(grad_c @ cov @ grad_c), math.sqrt(grad_k @ cov @ grad_k)
    return {"C": float(c), "dC": dc, "k": float(k), "dk": dk,
            "corr": float(grad_c @ cov @ grad_k / (dc * dk)), "slope": float(s),
            "intercept": float(b), "chi2": chi2, "dof": dof}
