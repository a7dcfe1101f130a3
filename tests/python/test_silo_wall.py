"""The silo's wall-stress analysis (tools/containers/silo_wall.py, examples/silo/run_silo.py).

* Synthetic contacts on a cylinder's wall whose stresses follow Janssen's profile with a known
  K and mobilised friction: the binning gives the stresses back exactly (the normal from the
  contact point's radial direction, the vertical and azimuthal shear apart) and the fit of
  the wall stress recovers K and mu (exactly without noise, within its errors with noise).
* A small real silo (examples/silo/in.silo, 1.5 d radius, Fig. 3 ellipsoids) at rest: the
  floor's and the side's vertical forces are, with the weight, all the forces on the pile
  (their sum is the atoms' net force, to 1e-9), and carry the weight to 2e-3 averaged over the
  window (each sample to 1e-2: the resting pile still rings); the side's contacts array sums
  to the side's force vector, and the slices' vertical stress from above and from below differ
  by the net force alone.
"""
import math
import os
import sys

import numpy as np
import pytest

from conftest import root_dir

sys.path.insert(0, os.path.join(root_dir(), "examples", "silo"))
import run_silo  # noqa: E402
import silo_wall  # noqa: E402

R, CENTRE, RHO_G, K, MU, H = 4.0, (5.0, 5.0), 0.6, 0.4, 0.3, 30.0


def synthetic_contacts(rng, sigma_of_h, edges, per_bin=40):
    """contacts-array rows on the wall (radius R about CENTRE) whose normal stress in each bin
    is sigma_of_h at the bin's mid depth and whose vertical shear is MU times it; random
    azimuths, heights in the bin, force splits and azimuthal shears"""
    rows = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        area = 2 * math.pi * R * (hi - lo)
        share = rng.exponential(size=per_bin)
        normal = sigma_of_h(H - 0.5 * (lo + hi)) * area * share / share.sum()
        phi = rng.uniform(0, 2 * math.pi, per_bin)
        er = np.column_stack([np.cos(phi), np.sin(phi)])
        et = np.column_stack([-np.sin(phi), np.cos(phi)])
        azimuthal = rng.normal(size=per_bin)
        force = np.zeros((per_bin, 3))
        force[:, :2] = -normal[:, None] * er + azimuthal[:, None] * et
        force[:, 2] = MU * normal
        point = np.column_stack([CENTRE[0] + R * er[:, 0], CENTRE[1] + R * er[:, 1],
                                 rng.uniform(lo, hi, per_bin)])
        rows.append(np.column_stack([np.ones(per_bin), force, point, np.full(per_bin, 0.5)]))
    return np.vstack(rows + [np.zeros((5, 8))])    # particles without a contact: zero rows


def janssen_wall(h):
    return silo_wall.janssen(h, RHO_G * R / (2 * MU), R / (2 * K * MU))


def test_synthetic_janssen_wall_gives_k_and_mu_back():
    rng = np.random.default_rng(7)
    edges = np.arange(0.0, H + 1e-9, 1.0)
    bins = silo_wall.wall_bins(synthetic_contacts(rng, janssen_wall, edges), CENTRE, R, edges)
    h = H - 0.5 * (edges[1:] + edges[:-1])
    assert np.allclose(bins["sigma_w"], janssen_wall(h), rtol=1e-12)
    assert np.allclose(bins["tau_w"], MU * janssen_wall(h), rtol=1e-12)
    assert np.all(bins["count"] == 40)
    _, mob, _, mob_mean = silo_wall.profile_ratios(bins["sigma_w"], bins["tau_w"],
                                                   janssen_wall(h) / K)
    assert np.allclose(mob, MU) and mob_mean == pytest.approx(MU, rel=1e-12)
    fit = silo_wall.fit_janssen(h, bins["sigma_w"], RHO_G, R)
    assert fit["K"] == pytest.approx(K, rel=1e-6) and fit["mu"] == pytest.approx(MU, rel=1e-6)
    assert fit["rms"] < 1e-8


def test_noisy_janssen_wall_fits_within_its_errors():
    rng = np.random.default_rng(11)
    h = np.arange(0.5, H, 1.0)
    hits = 0
    for _ in range(20):
        noisy = janssen_wall(h) * (1 + 0.03 * rng.normal(size=len(h)))
        fit = silo_wall.fit_janssen(h, noisy, RHO_G, R)
        hits += abs(fit["K"] - K) < 2 * fit["dK"] and abs(fit["mu"] - MU) < 2 * fit["dmu"]
        assert fit["dK"] < 0.2 * K
    assert hits >= 15    # about 95 % expected within two standard errors


def test_seed_statistics():
    assert silo_wall.over_seeds([1.0, 2.0, 3.0]) == pytest.approx((2.0, 1.0, 1 / math.sqrt(3)))
    assert math.isnan(silo_wall.over_seeds([1.0])[2])


def test_small_silo_carries_its_weight_at_rest(tmp_path):
    a = run_silo.parse_args(["--R", "1.5", "--stages", "1", "--per", "24", "--samples", "4",
                             "--every", "250", "--wait", "1000", "--out", str(tmp_path)])
    lmp = run_silo.open_silo(a)
    rows, rested = run_silo.fill(lmp, a, 7)
    assert rested
    edges = np.arange(0.0, rows[-1][2] + 1.0, 1.0)
    window = run_silo.measure(lmp, a.R, edges, a.samples, a.every, a.wait)
    lmp.close()
    weight = window[0]["weight"]
    imbalance = np.array([s["floor"] + s["side"] - s["weight"] for s in window])
    assert np.allclose(imbalance, [s["net"] for s in window], rtol=0, atol=1e-9 * weight)
    assert abs(imbalance.mean()) < 2e-3 * weight and np.all(abs(imbalance) < 1e-2 * weight)
    for s in window:
        assert s["fz"] == pytest.approx(s["side"], rel=1e-10, abs=1e-10)
        assert np.sum(s["tau_w"]) * 2 * math.pi * a.R == pytest.approx(s["fz"], rel=1e-10)
        assert np.all(s["sigma_w"] >= 0) and np.sum(s["count"]) > 0
        gap = np.abs(s["sigma_v"] - s["sigma_v_below"]) * math.pi * a.R**2
        assert np.all(gap <= abs(s["floor"] + s["side"] - s["weight"]) + 1e-9)
