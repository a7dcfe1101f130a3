"""The extrapolation of the flow solve's permeabilities to a vanishing voxel (doc/howto_pores.md,
"Permeability from a flow solve"): k(h) = k0 + C h^p from three or more voxel sizes h.

The order p is not known well enough to be fitted from three values whose differences are of
the size of their own errors (a mean over the grid's offsets); what the convergence studies
show is that the error falls at least as fast as h^2 from the default voxels on (the random
sphere pack: p 2.2 at d/16-d/24, 4.1 at d/20-d/32; the plane slit: 2). So k0 lies between
the least-squares extrapolation at p = P_MIN (P_FIXED) and the finest voxel's value (p
without bound): k0 is the middle of that bracket, its error the half-width plus the fixed-p
fit's standard error and the values' own errors carried through that fit. The p fitted
through the three finest values (and k0 at it) is reported beside, not used.
"""
import math

import numpy as np

P_FIXED = 2.0          # the slowest order of the stair-step error from the default voxels on
P_RANGE = (0.25, 8.0)  # a fitted p outside this is no convergence order: not used


def fixed_order_fit(h, k, p):
    """least squares k = k0 + C h^p: (k0, C, standard error of k0; None with 2 points)"""
    x = np.asarray(h, float) ** p
    k = np.asarray(k, float)
    A = np.column_stack([np.ones_like(x), x])
    (k0, c), *_ = np.linalg.lstsq(A, k, rcond=None)
    dof = len(k) - 2
    if dof < 1:
        return float(k0), float(c), None
    s2 = float(((k - k0 - c * x) ** 2).sum()) / dof
    cov = s2 * np.linalg.inv(A.T @ A)
    return float(k0), float(c), math.sqrt(max(cov[0, 0], 0.0))


def fitted_order(h, k):
    """p of k = k0 + C h^p through three points (h decreasing), or None when the differences
    change sign or p leaves P_RANGE"""
    (h1, h2, h3), (k1, k2, k3) = h, k
    d12, d23 = k1 - k2, k2 - k3
    if d12 == 0 or d23 == 0 or (d12 > 0) != (d23 > 0):
        return None
    ratio = d12 / d23

    def g(p):    # increasing in p for h1 > h2 > h3
        return (h1 ** p - h2 ** p) / (h2 ** p - h3 ** p) - ratio

    lo, hi = P_RANGE
    if g(lo) > 0 or g(hi) < 0:
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(mid) < 0 else (lo, mid)
    return 0.5 * (lo + hi)


def propagated_error(h, sigma, p):
    """the standard error of the fixed-p least-squares k0 from independent errors sigma of
    the values (k0 is linear in them)"""
    x = np.asarray(h, float) ** p
    A = np.column_stack([np.ones_like(x), x])
    row = np.linalg.solve(A.T @ A, A.T)[0]
    return float(np.sqrt(((row * np.asarray(sigma, float)) ** 2).sum()))


def extrapolate(h, k, sigma=None, p_fixed=P_FIXED):
    """k0 of k(h) = k0 + C h^p, p >= p_fixed, from (h, k) at three or more voxel sizes (any
    order); sigma: the values' own standard errors (of a mean over the grid's offsets)"""
    order = np.argsort(h)[::-1]
    h = [float(h[i]) for i in order]
    k = [float(k[i]) for i in order]
    sigma = [0.0] * len(h) if sigma is None else [float(sigma[i]) for i in order]
    if len(h) < 3 or len(set(h)) < len(h):
        raise ValueError("the extrapolation needs three or more different voxel sizes")
    k0_fixed, _, se = fixed_order_fit(h, k, p_fixed)
    p = fitted_order(h[-3:], k[-3:])    # the three finest
    k0_fitted = None if p is None else fixed_order_fit(h[-3:], k[-3:], p)[0]
    half_width = 0.5 * abs(k0_fixed - k[-1])
    offset_error = propagated_error(h, sigma, p_fixed)
    return {"k0": 0.5 * (k0_fixed + k[-1]), "error": half_width + se + offset_error,
            "p_fitted": p, "k0_fitted_p": k0_fitted, "p_fixed": p_fixed,
            "k0_fixed_p": k0_fixed, "fixed_p_standard_error": se, "k_finest": k[-1],
            "offset_error": offset_error, "voxels": h, "k": k, "k_offset_errors": sigma}
