"""A silo's discharge (tools/containers/discharge.py, examples/discharge/run_discharge.py).

* Beverloo's law fitted to rates made from a known C and k gives them back: exactly without
  noise, within their standard errors (and the errors about right) with noise, over many
  synthetic sets.
* The steady rate of a discharged-mass series with a start-up transient and noise is the
  known rate, its block standard error about the scatter of the rate over many series; a
  drifting rate is flagged by its blocks' trend, a steady one at the test's 5 %.
* A small silo (in.fill, then in.orifice through run_discharge.py): the particles fall through
  an orifice of 3.5 d and are lifted back, none lost, the rate positive.
"""
import json
import os
import sys

import numpy as np
import pytest

from conftest import root_dir

sys.path.insert(0, os.path.join(root_dir(), "examples", "discharge"))
import discharge  # noqa: E402
import run_discharge  # noqa: E402

C, K, RHO_B = 0.58, 1.45, 0.62
D0 = np.array([5.0, 6.0, 7.0, 8.0, 10.0])


def test_beverloo_fit_recovers_c_and_k_exactly():
    rate = discharge.beverloo(D0, C, K, RHO_B)
    fit = discharge.fit_beverloo(D0, rate, 0.01 * rate, RHO_B)
    assert fit["C"] == pytest.approx(C, rel=1e-12)
    assert fit["k"] == pytest.approx(K, rel=1e-12)
    assert fit["chi2"] == pytest.approx(0.0, abs=1e-18)
    # g and d enter as W = C rho_b sqrt(g) (D0 - k d)^(5/2)
    fit = discharge.fit_beverloo(D0, discharge.beverloo(D0, C, K, RHO_B, d=0.5, g=4.0),
                                 0.01 * rate, RHO_B, d=0.5, g=4.0)
    assert (fit["C"], fit["k"]) == pytest.approx((C, K), rel=1e-12)


def test_beverloo_fit_errors_cover_the_truth():
    """2 % noise on each rate: over 400 sets C and k lie within their quoted errors in about
    68 % of the sets (the errors neither too small nor too large), their means at the truth."""
    rng = np.random.default_rng(11)
    true = discharge.beverloo(D0, C, K, RHO_B)
    fits = [discharge.fit_beverloo(D0, true * (1 + 0.02 * rng.normal(size=D0.size)),
                                   0.02 * true, RHO_B) for _ in range(400)]
    for name, value in (("C", C), ("k", K)):
        got = np.array([f[name] for f in fits])
        err = np.array([f["d" + name] for f in fits])
        assert abs(got.mean() - value) < 3 * got.std() / np.sqrt(len(got))
        assert 0.6 < np.mean(abs(got - value) < err) < 0.85
        assert np.median(err) == pytest.approx(got.std(), rel=0.2)


def test_beverloo_fit_refuses_too_few_orifices():
    with pytest.raises(ValueError, match="needs >= 3 orifices"):
        discharge.fit_beverloo(D0[:2], [1.0, 2.0], [0.1, 0.1], RHO_B)


def test_steady_rate_recovers_the_rate():
    """mass = W (t - 2) after a transient (nothing before t = 2), with noise; t0 = 4"""
    rng = np.random.default_rng(5)
    t = np.arange(0.25, 40.01, 0.25)
    rates, errs = [], []
    for _ in range(200):
        mass = 3.0 * np.clip(t - 2.0, 0, None) + np.cumsum(rng.normal(0, 0.3, t.size))
        out = discharge.steady_rate(t, mass, 4.0)
        rates.append(out["rate"])
        errs.append(out["se"])
    assert np.mean(rates) == pytest.approx(3.0, abs=3 * np.std(rates) / np.sqrt(200))
    assert np.median(errs) == pytest.approx(np.std(rates), rel=0.3)
    exact = discharge.steady_rate(t, 3.0 * np.clip(t - 2.0, 0, None), 4.0)
    assert exact["rate"] == pytest.approx(3.0) and exact["se"] < 1e-12
    with pytest.raises(ValueError, match="blocks"):
        discharge.steady_rate(t[:8], t[:8], 0.0)


def test_block_trend_flags_a_drifting_rate():
    """a rate that doubles through the window is flagged, its rise exact without noise; so is a
    large rise the p test misses, and no flow; a constant rate with 5 % noise per block (the
    rise's SD 6 %, so the size bound hardly acts) is flagged in about STEADY_P of 400 windows;
    noisier windows are flagged more often: too noisy to show that they are steady"""
    ramp = discharge.block_trend([2.0, 2.5, 3.0, 3.5, 4.0])
    assert ramp["rise"] == pytest.approx(2.0 / 3.0, rel=1e-12)
    assert ramp["p"] < 1e-6 and not ramp["steady"]
    assert discharge.block_trend([3.0] * 5) == {"rise": 0.0, "p": 1.0, "steady": True}
    # +50 % across the window, too noisy for the p test: not steady by its size
    noisy = discharge.block_trend([2.0, 3.5, 2.4, 3.8, 3.0])
    assert noisy["p"] > discharge.STEADY_P and noisy["rise"] > discharge.STEADY_RISE
    assert not noisy["steady"]
    assert not discharge.block_trend([0.0] * 5)["steady"]    # a clogged orifice
    rng = np.random.default_rng(3)
    flagged = np.mean([not discharge.block_trend(3.0 + rng.normal(0, 0.15, 5))["steady"]
                       for _ in range(400)])
    assert 0.02 < flagged < 0.09    # 0.05 +- 3 binomial errors (0.011)


def test_only_steady_orifices_are_fitted():
    """examples/discharge/plot_discharge.py fits Beverloo's law to the steady windows only: an
    orifice whose blocks rise is left out, and fewer than three steady ones give no fit"""
    import plot_discharge
    rate = discharge.beverloo(D0[:4], C, K, RHO_B)
    orifices = [{"D0": d, "rate": w, "se": 0.02 * w, "blocks": [w] * 5}
                for d, w in zip(D0[:4], rate)]
    orifices[1]["rate"] *= 0.7
    orifices[1]["blocks"] = list(orifices[1]["rate"] * np.linspace(0.6, 1.4, 5))
    fill = {"rho_b": RHO_B, "N": 1, "H": 1.0}
    fit = plot_discharge.fits({"spheres": {"fill": fill, "orifices": orifices}})["spheres"]
    assert (fit["C"], fit["k"], fit["dof"]) == (pytest.approx(C), pytest.approx(K), 1)
    orifices[2]["blocks"] = [0.0] * 5    # clogged
    assert plot_discharge.fits({"spheres": {"fill": fill, "orifices": orifices}}) == {}


def test_small_silo_discharges(tmp_path):
    a = run_discharge.parse_args(["--name", "test", "--N", "300", "--R", "3", "--D0", "3.5",
                                  "--t0", "1", "--T", "3", "--chunk", "0.25"])
    a.results, a.work = str(tmp_path / "results"), str(tmp_path / "work")
    os.makedirs(a.results)
    os.makedirs(a.work)
    filled = run_discharge.fill(a)
    assert filled["N"] == 300 and 0.5 < filled["rho_b"] < 0.7
    run_discharge.orifice(a, filled, 3.5)
    out = json.load(open(tmp_path / "results" / "D3.5.json"))
    series = np.loadtxt(tmp_path / "results" / "D3.5.dat")
    assert out["count"] > 10 and out["rate"] > 0
    assert np.all(np.diff(series[:, 1]) >= 0)
