"""A silo's wall stress against depth (examples/silo): binning the side wall's per-contact
forces, the vertical stress of the bulk from a slice's force balance, Janssen's profile fitted
to the wall stress, and the statistics over seeds.

Conventions: the silo is a cylinder of radius R about the vertical axis through `centre`
(x, y), its floor at z = 0, gravity along -z. A row of the side wall's `contacts` array (fix
wall/gran/region/ellipsoid ... contacts: count, the force the wall exerts on the particle,
the contact point on the wall, R*) gives at the contact point the outward radial unit e_r:
the pile presses the wall with the normal force -F.e_r and drags it down with the vertical
shear F_z (the wall's friction holding the particle up). Stresses are these over the wall's
area of a bin, 2 pi R dz; sigma_w > 0 presses, tau_w > 0 carries weight.

Janssen (a column of bulk weight density rho_b g, wall friction mobilised to
mu = tau_w / sigma_w, sigma_w = K sigma_v): at depth h below the free surface

    sigma_v(h) = rho_b g lambda (1 - exp(-h / lambda)),   lambda = R / (2 K mu),
    sigma_w(h) = K sigma_v(h) = A (1 - exp(-h / lambda)),  A = rho_b g R / (2 mu),

so the wall stress alone, fitted for A and lambda, gives mu = rho_b g R / (2 A) and
K = A / (rho_b g lambda).
"""
import math

import numpy as np
from scipy.optimize import curve_fit


def wall_bins(contacts, centre, radius, edges):
    """The side wall's stresses in the z bins `edges` from its contacts array (rows without a
    contact skipped), binned by the contact point's height: dict of sigma_w (normal), tau_w
    (vertical shear), tau_theta (azimuthal shear, anticlockwise about +z) and count (contacts,
    column 1), each per bin, and the total vertical shear force fz (the wall's force on the
    pile, all contacts whatever their bin)."""
    rows = np.asarray(contacts, dtype=float)
    rows = rows[rows[:, 0] > 0.0]
    force, point = rows[:, 1:4], rows[:, 4:7]
    radial = point[:, :2] - np.asarray(centre, dtype=float)
    radial /= np.linalg.norm(radial, axis=1)[:, None]
    normal = -np.einsum("ij,ij->i", force[:, :2], radial)
    theta = -(force[:, 0] * radial[:, 1] - force[:, 1] * radial[:, 0])    # the pile on the wall
    edges = np.asarray(edges, dtype=float)
    area = 2.0 * math.pi * radius * np.diff(edges)

    def per_bin(values):
        return np.histogram(point[:, 2], bins=edges, weights=values)[0] / area
    return {"sigma_w": per_bin(normal), "tau_w": per_bin(force[:, 2]),
            "tau_theta": per_bin(theta),
            "count": np.histogram(point[:, 2], bins=edges, weights=rows[:, 0])[0],
            "fz": float(np.sum(force[:, 2]))}


def vertical_stress(z, weight, wall_fz, floor_fz, levels, radius):
    """The bulk's mean vertical stress on the horizontal planes `levels`, from the force
    balance of the particles whose centres lie above each (their weight less the wall's
    vertical force on them) and, as a check, of those below (the floor's and the wall's
    vertical forces on them less their weight); over the cross-section pi R^2. z, weight,
    wall_fz: per particle (centre height, m g, the side wall's vertical force on it);
    floor_fz: the floor's force on the pile (> 0). Both are the same at rest."""
    z, weight, wall_fz = (np.asarray(v, dtype=float) for v in (z, weight, wall_fz))
    area = math.pi * radius**2
    above = np.array([np.sum((weight - wall_fz)[z > lv]) for lv in levels]) / area
    below = np.array([floor_fz + np.sum((wall_fz - weight)[z <= lv]) for lv in levels]) / area
    return above, below


def janssen(h, amplitude, lam):
    return amplitude * (1.0 - np.exp(-np.asarray(h) / lam))


def fit_janssen(h, sigma_w, rho_g, radius):
    """Janssen's profile A (1 - exp(-h / lambda)) fitted to the wall stress at depths h (scipy's
    curve_fit; standard errors from its covariance): A, lambda and, with the bulk weight
    density rho_g, the mobilised friction mu = rho_g R / (2 A) and K = A / (rho_g lambda),
    their errors propagated with A and lambda's covariance, and the rms residual."""
    h, sigma_w = np.asarray(h, dtype=float), np.asarray(sigma_w, dtype=float)
    if len(h) < 3:
        raise ValueError(f"fit_janssen: {len(h)} bins; the fit needs 3")
    (a, lam), cov = curve_fit(janssen, h, sigma_w, p0=(rho_g * radius, radius))
    mu, k = rho_g * radius / (2.0 * a), a / (rho_g * lam)
    grad_mu = np.array([-mu / a, 0.0])
    grad_k = np.array([k / a, -k / lam])
    return {"A": a, "dA": math.sqrt(cov[0, 0]), "lambda": lam, "dlambda": math.sqrt(cov[1, 1]),
            "mu": mu, "dmu": math.sqrt(grad_mu @ cov @ grad_mu),
            "K": k, "dK": math.sqrt(grad_k @ cov @ grad_k),
            "rms": float(np.sqrt(np.mean((janssen(h, a, lam) - sigma_w) ** 2)))}


def profile_ratios(sigma_w, tau_w, sigma_v):
    """K = sigma_w / sigma_v and the mobilised friction tau_w / sigma_w per bin (NaN where the
    denominator vanishes), and over all the bins given: sum sigma_w / sum sigma_v and
    sum tau_w / sum sigma_w (stress-weighted means)."""
    sigma_w, tau_w, sigma_v = (np.asarray(v, dtype=float) for v in (sigma_w, tau_w, sigma_v))
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.where(sigma_v > 0, sigma_w / sigma_v, np.nan)
        mob = np.where(sigma_w > 0, tau_w / sigma_w, np.nan)
    return k, mob, float(sigma_w.sum() / sigma_v.sum()), float(tau_w.sum() / sigma_w.sum())


def over_seeds(values):
    """mean, sample SD and standard error of the mean of per-seed values (SD and SE NaN for one
    seed)"""
    v = np.asarray(values, dtype=float)
    if len(v) < 2:
        return float(v.mean()), math.nan, math.nan
    sd = float(np.std(v, ddof=1))
    return float(v.mean()), sd, sd / math.sqrt(len(v))
