"""The extrapolation of the flow solve's permeabilities to a vanishing voxel (doc/howto_pores.md,
"Permeability from a flow solve"): k(h) = k0 + C h^p from three or more voxel sizes h.

With three sizes the fit with p free has no degree of freedom left: p follows from the ratio
of the two differences (when the values converge monotonically) and k0 from it. The fit with
p fixed (P_FIXED, from the convergence study) is a least-squares line in h^p with one degree
of freedom, whose residual measures how well the values follow the form. k0 is the mean of the
two, and its error covers both: half their difference plus the fixed-p fit's standard error;
without a fitted p (values that do not converge monotonically) k0 is the fixed-p value and the
error the whole extrapolation, |k0 - k(finest)|, plus the standard error.
"""
import math

import numpy as np

P_FIXED = 2.0          # the order of the stair-step error on average (measured p: howto)
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
    """k0 of k(h) = k0 + C h^p from (h, k) at three or more voxel sizes (any order); sigma:
    the values' own standard errors (of a mean over the grid's offsets), added to the error"""
    order = np.argsort(h)[::-1]
    h = [float(h[i]) for i in order]
    k = [float(k[i]) for i in order]
    sigma = [0.0] * len(h) if sigma is None else [float(sigma[i]) for i in order]
    if len(h) < 3 or len(set(h)) < len(h):
        raise ValueError("the extrapolation needs three or more different voxel sizes")
    k0_fixed, c_fixed, se = fixed_order_fit(h, k, p_fixed)
    p = fitted_order(h[-3:], k[-3:])    # the three finest
    k0_fitted = None
    if p is not None:
        k0_fitted, _, _ = fixed_order_fit(h[-3:], k[-3:], p)
        k0 = 0.5 * (k0_fitted + k0_fixed)
        error = 0.5 * abs(k0_fitted - k0_fixed) + se
    else:
        k0 = k0_fixed
        error = abs(k0_fixed - k[-1]) + se
    offset_error = propagated_error(h, sigma, p_fixed)
    return {"k0": k0, "error": error + offset_error, "p_fitted": p, "k0_fitted_p": k0_fitted,
            "p_fixed": p_fixed, "k0_fixed_p": k0_fixed, "fixed_p_standard_error": se,
            "offset_error": offset_error, "voxels": h, "k": k, "k_offset_errors": sigma}
