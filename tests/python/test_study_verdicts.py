"""tools/study/study_stats.py and the verdicts of tools/study/study_verdicts.py and study_histograms.py
on synthetic deposits with known answers (in memory; no deposit runs).

Every shape has two seeds at +-e about its value, so its seed SD is e sqrt(2) and a pooled
SD is known exactly; histograms are P = (1 + A P2(cos theta)) / (4 pi) on 18 bins, which
cross the isotropic value and each other where P2 = 0, theta = acos(1/sqrt 3)."""
import math
import os

import numpy as np
import pytest
from scipy import stats

import study_forces
import study_histograms
import study_stats
import study_verdicts
from study_claims import Selection

MAGIC = math.acos(1 / math.sqrt(3))
THETA = (np.arange(18) + 0.5) * math.pi / 18
P2 = 0.5 * (3 * np.cos(THETA) ** 2 - 1)
WEIGHT = np.cos(THETA - math.pi / 36) - np.cos(THETA + math.pi / 36)    # a bin's solid angle


def histogram(amplitude, bump=0.0):
    """(theta, P, fraction); bump: a relative excess in the first bin (and its mirror)"""
    p = (1 + amplitude * P2) / (4 * math.pi)
    p[[0, -1]] *= 1 + bump
    return THETA.tolist(), p.tolist(), (p * 2 * math.pi * WEIGHT).tolist()


def deposit(eta, zeta, e, phi, z, qzz, amp, bump=0.0):
    """two seeds: (+e, -e) on every quantity, the histogram amplitude and the bump"""
    return [{"eta": eta, "zeta": zeta, "phi": phi + s * e, "Z": z + s * 10 * e,
             "Qzz": qzz + s * e, "fabric_anisotropy": amp / 10 + s * e,
             "Nslab": 2000, "slab": 6.0, "contact_histo": histogram(amp + s * e, bump + s * e),
             "orient_histo": histogram(-amp - s * e)} for s in (1, -1)]


def test_pooled_groups():
    shapes = {(1.0, 1.0): [0.1, 0.1], (1.2, 1.0): [0.1, 0.102], (1.0, 1.4): [0.1, 0.102],
              (1.0, 1.6): [0.1, 0.102], (1.0, 2.0): [0.1, 0.102],
              (1.2, 1.4): [0.2, 0.204], (1.4, 1.6): [0.2, 0.204], (1.2, 1.2): [0.2, 0.204],
              (1.4, 1.4): [0.2, 0.204], (1.6, 1.6): [0.2]}
    thin = {(2.0, 2.0): [0.3, 0.308], (3.0, 1.5): [0.3, 0.308], (2.5, 2.5): [0.3, 0.308],
            (3.0, 3.0): [0.3, 0.308]}
    groups, of_shape = study_stats.pooled_groups({**shapes, **thin})
    # a pair (x, x + d) has the SD d / sqrt 2
    assert groups["spheroids"] == {"sd": pytest.approx(math.sqrt(4 * 0.002 ** 2 / 2 / 5),
                                                       rel=1e-9), "dof": 5, "shapes": 5}
    assert groups["general a/c<4"]["sd"] == pytest.approx(0.004 / math.sqrt(2), rel=1e-9)
    assert groups["general a/c>=4"]["sd"] == pytest.approx(0.008 / math.sqrt(2), rel=1e-9)
    assert of_shape[(1.6, 1.6)] == "general a/c<4" and of_shape[(3.0, 1.5)] == "general a/c>=4"
    # three thin shapes: 3 degrees of freedom, fewer than MIN_DOF: both halves merge
    del thin[(3.0, 3.0)]
    groups, of_shape = study_stats.pooled_groups({**shapes, **thin})
    assert set(groups) == {"spheroids", "general"} and groups["general"]["dof"] == 7
    assert groups["general"]["sd"] == pytest.approx(
        math.sqrt((4 * 0.004 ** 2 + 3 * 0.008 ** 2) / 2 / 7), rel=1e-9)
    # a lone sphere (1 degree of freedom) takes the pool of the whole selection
    groups, of_shape = study_stats.pooled_groups({(1.0, 1.0): [0.1, 0.102], **thin,
                                                  (1.2, 1.2): [0.2, 0.204]})
    assert of_shape[(1.0, 1.0)] == "all" and groups["all"]["dof"] == 5


def test_line_maximum_and_its_fit_window_systematic():
    rng = np.random.default_rng(1)
    x = np.array([1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7, 1.8, 2.0])
    m = study_stats.line_maximum(x, 0.64 - 0.1 * (x - 1.43) ** 2, [0.001] * len(x), rng)
    assert set(m["fits"]) == {"parabola 3", "parabola 5", "parabola 7", "cubic 7"}
    for f in m["fits"].values():    # a parabola: every window finds its vertex
        assert f["x_max"] == pytest.approx(1.43, abs=1e-9) and f["kept"] > 1000
    assert m["fits"]["parabola 5"]["kept"] > 1900    # the 3 points' vertex leaves more often
    assert m["x_sys"] == pytest.approx(0.0, abs=1e-9) and 0.003 < m["x_sd"] < 0.05
    y = 0.64 - 0.1 * (x - 1.43) ** 2 + 0.05 * (x - 1.43) ** 3    # skewed: the windows differ
    m = study_stats.line_maximum(x, y, None, rng)
    found = [f["x_max"] for f in m["fits"].values()]
    assert m["fits"]["cubic 7"]["x_max"] == pytest.approx(1.43, abs=1e-9)    # exact
    assert m["x_sys"] == pytest.approx((max(found) - min(found)) / 2) and m["x_sys"] > 0.005
    assert m["x_max"] == m["fits"]["parabola 5"]["x_max"] and "x_sd" not in m
    assert study_stats.line_maximum(x, -x, None, rng)["at_edge"]


def test_effective_dof_of_a_statistical_and_a_systematic_error():
    """Welch-Satterthwaite with a systematic of infinite dof: (s^2 + y^2)^2 / (s^4 / dof)"""
    assert study_stats.effective_dof(0.002, 3, 0.0) == 3
    assert study_stats.effective_dof(0.002, 3, 0.002) == pytest.approx(12.0, rel=1e-12)
    assert study_stats.effective_dof(0.002, 3, 0.001) == pytest.approx(
        (0.002 ** 2 + 0.001 ** 2) ** 2 / (0.002 ** 4 / 3), rel=1e-12)
    assert study_stats.effective_dof(0.0, 3, 0.001) is None    # no statistical part: normal
    assert study_stats.effective_dof(0.002, None, 0.001) is None


def test_seeds_needed_and_the_sign_test():
    # 0.003 against two errors 0.001 at 2 seeds: 2.1 sigma; 3 sigma when the variance
    # (2 + 2) 1e-6 / seeds is (0.003 / 3)^2: 4 seeds
    assert study_stats.seeds_needed(0.003, [(0.001, 2), (0.001, 2)]) == 4
    assert study_stats.seeds_needed(0.003, [(0.001, 2)], sys=0.0011) is None    # sys > d/3
    assert study_stats.seeds_needed(0.0, [(0.001, 2)]) is None                  # no difference
    k, n, p = study_stats.sign_test([1] * 22 + [-1] * 6)
    assert (k, n) == (22, 28)
    assert p == pytest.approx(stats.binomtest(22, 28).pvalue, rel=1e-9)
    assert study_stats.decide(2.1, 8, 2, "yes", "no")["verdict"].endswith("needs at least 8")
    assert study_stats.decide(-3.2, None, 2, "yes", "no")["verdict"] == "no"
    # the seeds said in words: one seed, several, a range
    assert study_stats.decide(1.0, 21, 1, "yes", "no")["verdict"] == (
        "undecided at 1 seed; needs at least 21")
    assert study_stats.decide(0.1, None, "1-2", "yes", "no")["verdict"].startswith(
        "undecided at 1-2 seeds; no number")
    # Student's t: 3.03 standard errors from an SD of 10 degrees of freedom are p = 0.013,
    # 2.5 sigma: undecided, and at least one seed more than now
    d = study_stats.decide(3.03, 2, 3, "yes", "no", dof=10)
    assert d["z_equivalent"] == pytest.approx(stats.norm.isf(stats.t.sf(3.03, 10)), rel=1e-9)
    assert 2.4 < d["z_equivalent"] < 2.6 and d["seeds_needed"] == 4
    assert study_stats.equivalent_sigma(3.0, 10 ** 6) == pytest.approx(3.0, abs=1e-4)


def selection(shift_qzz=0.0, asym=0.0):
    """a map of shapes at e = 0.001: phi a ridge along eta = zeta, Z asymmetric by asym and
    highest at a/c = 4 on the diagonal, Q_zz shifted by shift_qzz, fabric growing with a/c;
    the sphere's bin near the vertical is 20 % low"""
    grid = [1.0, 1.2, 1.4, 1.6, 2.0, 2.5, 3.0]
    out = []
    for eta in grid:
        for zeta in grid:
            ac = eta * zeta
            out += deposit(eta, zeta, 0.001,
                           0.64 - 0.01 * (eta - zeta) ** 2 - 0.005 * (ac - 2) ** 2,
                           6.5 + 0.1 * ac + (asym if eta > zeta else 0.0)
                           - 0.15 * max(0.0, ac - 4),
                           -0.05 * (ac - 1) + shift_qzz, 0.0 if ac == 1 else 0.1 * ac,
                           -0.2 if ac == 1 else 0.0)
    return Selection(out)


def test_asymmetry_delta_r_and_fall_back():
    base, poly = selection(asym=0.05), selection(shift_qzz=0.01)
    a = study_verdicts.asymmetry(base)
    # Z's pairs differ by 0.05 exactly; each Z has the SD 0.01 sqrt 2, SE 0.01
    assert a["Z"]["n"] == 21 and a["Z"]["mean"] == pytest.approx(0.05)
    assert a["Z"]["se"] == pytest.approx(0.01 * math.sqrt(2) / math.sqrt(21), rel=1e-6)
    assert a["Z"]["positive"] == 21 and a["Z"]["verdict"].startswith("asymmetric: larger")
    assert a["phi"]["mean"] == pytest.approx(0.0, abs=1e-12)
    assert a["phi"]["verdict"].startswith("undecided")
    (d,) = study_verdicts.delta_r_effects({(0.0, "coulomb"): base, (0.6, "coulomb"): poly},
                                          "coulomb")
    q = d["Qzz"]
    assert q["n"] == 48 and q["mean"] == pytest.approx(0.01)    # the sphere left out
    assert q["se"] == pytest.approx(0.001 * math.sqrt(2) / math.sqrt(48), rel=1e-6)
    assert q["verdict"] == "larger at delta_r 0.6, N fixed" and q["seeds_needed"] is None
    assert d["depth"]["thickness_mean"] == 6.0
    f = study_verdicts.fall_back(base)
    # along eta = zeta, Z = 6.5 + 0.1 ac - 0.15 max(0, ac - 4): 6.9, 6.7875, 6.65 at eta = 2,
    # 2.5, 3; each with the SE 0.01
    assert f["peak"] == [2.0, 2.0] and f["slope_thin"] == f["slope_from_peak"]
    assert f["slope_thin"]["slope"] == pytest.approx(-0.25, rel=1e-9)
    assert f["slope_thin"]["se"] == pytest.approx(0.01 / math.sqrt(0.5), rel=1e-6)
    assert f["slope_thin"]["verdict"] == "falls"
    assert f["end_minus_peak"]["difference"] == pytest.approx(-0.25, rel=1e-9)
    assert f["end_minus_peak"]["z"] == pytest.approx(-0.25 / (0.01 * math.sqrt(2)), rel=1e-6)
    # the largest fall the data leave open at 3 sigma: the fall plus 3 standard errors
    assert f["end_minus_peak"]["largest_fall"] == pytest.approx(0.25 + 3 * 0.01 * math.sqrt(2))


def test_ridge_at_equal_aspect_ratio():
    """the diagonal against a spheroid line at equal a/c: phi linear in a/c on the line
    (exact interpolation), the diagonal 0.002 above it; shapes whose line neighbours are
    more than 0.1 apart in a/c, or outside a/c 1.4-2.2, are left out"""
    out = []
    for x in (1.0, 1.4, 1.5, 1.6, 1.7, 1.8, 1.9, 2.0, 2.4, 2.8):    # gap 2.0 -> 2.4
        out += deposit(x, 1.0, 0.001, 0.60 + 0.01 * x, 6.0, 0.0, 0.1)
    for v in (1.2, 1.3, 1.4, 1.5, 1.6):    # a/c 1.44, 1.69, 1.96, 2.25 (out), 2.56 (out)
        out += deposit(v, v, 0.001, 0.602 + 0.01 * v * v, 6.0, 0.0, 0.1)
    e = study_verdicts.equal_aspect(Selection(out), "prolate", "diagonal higher", "lower")
    assert [p["diagonal"] for p in e["per_shape"]] == [[1.2, 1.2], [1.3, 1.3], [1.4, 1.4]]
    assert [p["between"][0] for p in e["per_shape"]] == [[1.4, 1.0], [1.6, 1.0], [1.9, 1.0]]
    for p in e["per_shape"]:
        assert p["difference"] == pytest.approx(0.002, abs=1e-12)
    # every SD is 0.001 sqrt 2: a shape's SE 0.001, the interpolated line's 0.001 |(1-w, w)|
    w = [(1.44 - 1.4) / 0.1, (1.69 - 1.6) / 0.1, (1.96 - 1.9) / 0.1]
    se = [0.001 * math.sqrt(1 + (1 - k) ** 2 + k ** 2) for k in w]
    assert [p["se"] for p in e["per_shape"]] == pytest.approx(se, rel=1e-6)
    assert e["mean"]["mean"] == pytest.approx(0.002) and e["mean"]["positive"] == 3
    assert e["mean"]["se"] == pytest.approx(math.sqrt(sum(x * x for x in se)) / 3, rel=1e-6)
    assert study_verdicts.equal_aspect(Selection(out), "oblate", "higher", "lower") is None


def test_delta_r_at_matched_depth_and_finite_size():
    """study_depth: the matched-depth effect beside the study-N effect on the same shapes, and
    each other box against the study's, from known shifts of phi (seeds at +-e: each point's
    SE is e, a difference's e sqrt 2)"""
    import study_depth
    e, out = 0.001, []

    def add(shapes, dr, n, width, shift, slab, force_shift=None):
        """force_shift: (a_n, a_f) added to the force measures (a_n 0.3 + 0.02 a/c, a_f 0.1 +
        0.01 a/c, K0 0.6); None: a deposit that predates them (nan)"""
        for v in shapes:
            for d in deposit(v, v, e, 0.6 + 0.01 * v + shift, 6.0, 0.0, 0.1):
                sign = 1 if d["phi"] > 0.6 + 0.01 * v + shift else -1
                f = ({"a_n": "nan", "a_f": "nan", "K0": "nan"} if force_shift is None else
                     {"a_n": 0.3 + 0.02 * v * v + force_shift[0] + sign * e,
                      "a_f": 0.1 + 0.01 * v * v + force_shift[1] + sign * e,
                      "K0": 0.6 + sign * e, "window_steps": 2400})
                out.append(dict(d, law="coulomb", delta_r=dr, N=n, width=width, slab=slab, **f))
    add((1.0, 1.4, 2.0, 3.0), 0.0, 3000, "", 0.0, 7.0, (0.0, 0.0))
    add((1.0, 1.4, 2.0, 3.0), 0.6, 3000, "", -0.100, 4.0)
    add((1.0, 1.4, 2.0), 0.6, 4327, 16.4317, 0.050, 7.0, (0.01, -0.02))
    add((1.4,), 0.0, 12000, "", 0.002, 7.0)
    add((1.4,), 0.0, 12000, 16.4317, -0.003, 40.0)
    c = study_depth.depth_claims(Selection(out), "coulomb", 3000)
    (m,) = c["matched"]
    assert m["delta_r"] == 0.6 and m["N"] == [4327] and m["width"] == [16.4317]
    assert m["shapes"] == [[1.0, 1.0], [1.4, 1.4], [2.0, 2.0]]
    assert m["matched_depth"]["phi"]["mean"] == pytest.approx(0.05)
    assert m["matched_depth"]["phi"]["n"] == 3
    # each shape's difference has the SE e sqrt 2, their mean over 3 shapes e sqrt(2 / 3)
    assert m["matched_depth"]["phi"]["se"] == pytest.approx(e * math.sqrt(2 / 3), rel=1e-6)
    assert m["study_N"]["phi"]["mean"] == pytest.approx(-0.1) and m["study_N"]["phi"]["n"] == 3
    # the forces: only where both have them (not the study-N deposits, which predate them)
    f = m["forces"]
    assert f["a_n"]["mean"] == pytest.approx(0.01) and f["a_f"]["mean"] == pytest.approx(-0.02)
    assert f["a_total"]["mean"] == pytest.approx(-0.01) and f["K0"]["mean"] == pytest.approx(0)
    assert f["a_n"]["n"] == 3 and f["a_f"]["verdict"].startswith("smaller at delta_r 0.6")
    assert f["a_total"]["se"] == pytest.approx(2 * e * math.sqrt(2 / 3), rel=1e-6)
    diagonal = m["force_trends"]["diagonal"]
    assert [r["a/c"] for r in diagonal["per_shape"]] == pytest.approx([1, 1.96, 4])
    assert diagonal["trends"]["a_total"]["slope_per_unit_a/c"]["slope"] == pytest.approx(0.03)
    assert all(r["seeds"] == 2 for r in diagonal["per_shape"])
    # delta_r 0 over the same shapes (not its whole diagonal, which reaches a/c 9 here)
    at_0 = m["force_trends_at_0"]["diagonal"]
    assert [r["a/c"] for r in at_0["per_shape"]] == pytest.approx([1, 1.96, 4])
    assert at_0["trends"]["a_total"]["slope_per_unit_a/c"]["slope"] == pytest.approx(0.03)
    kept = Selection(out).with_forces().deposits    # delta_r 0 at N 3000 and the matched ones
    assert len(kept) == 14 and {(d["delta_r"], d["N"]) for d in kept} == {(0.0, 3000),
                                                                          (0.6, 4327)}
    assert all(d["a_total"] == pytest.approx(d["a_n"] + d["a_f"]) for d in kept)
    assert m["matched_depth"]["phi"]["verdict"].startswith("larger at delta_r 0.6, matched")
    assert m["study_N"]["phi"]["verdict"].startswith("smaller at delta_r 0.6, N 3000")
    assert (m["depth"]["matched"]["thickness_mean"], m["depth"]["study_N"]["thickness_mean"],
            m["depth"]["delta_r_0"]["thickness_mean"]) == (7.0, 4.0, 7.0)
    wide, deep = c["finite_size"]
    assert (wide["N"], wide["width"], deep["N"], deep["width"]) == (12000, None, 12000, 16.4317)
    assert wide["effects"]["phi"]["mean"] == pytest.approx(0.002)
    assert deep["effects"]["phi"]["mean"] == pytest.approx(-0.003)
    assert deep["effects"]["phi"]["se"] == pytest.approx(e * math.sqrt(2), rel=1e-6)
    assert deep["depth"]["thickness_mean"] == 40.0 and wide["shapes"] == [[1.4, 1.4]]
    (h,) = wide["histograms"]    # the same histograms at both N: no difference, some scatter
    assert (h["eta"], h["zeta"]) == (1.4, 1.4)
    assert h["contact_normals"]["rms_difference"] == pytest.approx(0.0, abs=1e-15)
    assert h["contact_normals"]["rms_seed_scatter"] > 0 and h["long_axes"]["seeds"] == [2, 2]
    assert study_depth.depth_claims(Selection(out[:8]), "coulomb", 3000) is None


def test_crossings_and_sphere_isotropy():
    base = selection()
    both = study_histograms.crossings_both(base, study_verdicts.PAPER_ANGLES)
    for key in ("contact_normals", "long_axes"):
        iso = both[key]["isotropic_level"]
        assert all(abs(r["theta"] - MAGIC) < 2e-3 for r in iso["shapes"])
        mutual = both[key]["each_other"]
        assert mutual["pairs"] > 100 and abs(mutual["median"] - MAGIC) < 2e-3
        assert mutual["median_se"] > 0
    # many contacts (counting errors negligible): the seed errors decide
    many = Selection([dict(d, Nslab=2.0e6) for d in base.deposits])
    s = study_histograms.sphere_isotropy({(0.0, "coulomb"): many}, (0.0, "coulomb"))
    assert s["deviation"][0] == pytest.approx(-0.2, abs=1e-5)
    assert s["largest"]["theta"] == s["most_significant"]["theta"] == pytest.approx(THETA[0])
    assert not s["within_10_percent"] and s["p_isotropic"] < 1e-6
    # 2000 particles: the bin near the pole holds few contacts, and its counting error, not
    # the two seeds' chance agreement, bounds its error: the -20 % is no longer decisive
    s = study_histograms.sphere_isotropy({(0.0, "coulomb"): base}, (0.0, "coulomb"))
    assert s["se"][0] == pytest.approx(s["se_counting"][0]) and s["p_isotropic"] > 0.01
    # counting: Pearson's chi^2 of the counts (fraction x Nslab Z summed over the seeds)
    # against the isotropic expectation, and each bin's error at least sqrt(counts) / expected
    sphere = base.shapes[(1.0, 1.0)]
    half = len(s["deviation"])
    counts = sum(np.array(d["contact_histo"][2][:half]) * d["Nslab"] * d["Z"] for d in sphere)
    expected = counts / (1 + np.array(s["deviation"]))
    assert s["chi2_counting"] == pytest.approx(float(np.sum((counts - expected) ** 2 / expected)))
    assert np.all(np.array(s["se"]) >= np.sqrt(counts) / expected - 1e-15)
    assert s["se_counting"] == pytest.approx((np.sqrt(counts) / expected).tolist())
    # another law's spheres (any scatter) do not enter this law's errors
    noisy_sphere = Selection(deposit(1.0, 1.0, 0.05, 0.64, 6.5, 0.0, 0.0, -0.2))
    other = {(0.0, "coulomb"): base, (0.0, "viscous"): noisy_sphere}
    assert study_histograms.sphere_isotropy(other, (0.0, "coulomb"))["se"] == s["se"]


def test_force_trends_along_the_diagonal():
    """study_forces: a_n, a_f linear in a/c (known slopes), K0 flat; deposits that predate the
    force measures (nan) and shapes off the diagonal are left out"""
    e = 0.01
    deposits = []
    for v in (1.0, 1.2, 1.4, 2.0, 3.0):
        ac = v * v
        for s in (1, -1):
            deposits.append({"eta": v, "zeta": v, "a_n": 0.4 + 0.02 * ac + s * e,
                             "a_f": 0.2 + 0.05 * ac + s * e, "K0": 0.7 + s * e,
                             "window_steps": 2400})
        deposits.append({"eta": v, "zeta": v, "a_n": "nan", "a_f": "nan", "K0": "nan"})
        # a snapshot of a ringing bed (no window): left out whatever its values
        deposits.append({"eta": v, "zeta": v, "a_n": 5.0, "a_f": 5.0, "K0": 5.0,
                         "window_steps": 0})
    deposits += [{"eta": 2.0, "zeta": 1.0, "a_n": 9.0 + s * e, "a_f": 9.0 + s * e,
                  "K0": 9.0 + s * e, "window_steps": 2400} for s in (1, -1)]
    assert list(study_forces.forces(deposits)) == ["diagonal"]    # (2, 1): one prolate shape
    f = study_forces.forces(deposits)["diagonal"]
    assert f["deposits"] == 10 and f["a_n_at_least_1"] == []    # the snapshots left out
    assert [r["a/c"] for r in f["per_shape"]] == pytest.approx([1, 1.44, 1.96, 4, 9])
    ac = np.array([1, 1.44, 1.96, 4, 9])
    se_slope = e / math.sqrt(np.sum((ac - ac.mean()) ** 2))    # each shape's SE is e
    for q, slope, spread in (("a_n", 0.02, 1), ("a_f", 0.05, 1), ("a_total", 0.07, 2),
                             ("K0", 0.0, 1)):    # a_n + a_f: +-2e about its value
        t = f["trends"][q]["slope_per_unit_a/c"]
        assert t["slope"] == pytest.approx(slope, abs=1e-12)
        assert t["se"] == pytest.approx(spread * se_slope, rel=1e-9)
    assert f["trends"]["a_f"]["slope_per_unit_a/c"]["verdict"] == "grows with a/c"
    assert f["trends"]["K0"]["slope_per_unit_a/c"]["verdict"].startswith("undecided")
    end = f["trends"]["a_n"]["thinnest_minus_roundest"]
    assert end["shapes"] == [[3.0, 3.0], [1.0, 1.0]]
    assert end["difference"] == pytest.approx(0.16) and end["se"] == pytest.approx(e * 2 ** .5)
    assert study_forces.forces(deposits[:6]) is None    # fewer than 3 shapes


def test_force_trends_along_the_spheroid_lines():
    """study_forces: the prolate (zeta = 1) and oblate (eta = 1) lines start at the spheres and
    are fitted against a/c apart from each other and from the diagonal"""
    e, deposits = 0.01, []
    for v in (1.0, 1.5, 2.0):
        for s in (1, -1):
            deposits.append({"eta": v, "zeta": 1.0, "a_n": 0.1 * v + s * e, "a_f": s * e,
                             "K0": 1.0 + s * e, "window_steps": 2400})
            if v > 1:
                deposits.append({"eta": 1.0, "zeta": v, "a_n": -0.3 * v + s * e, "a_f": s * e,
                                 "K0": 1.0 + s * e, "window_steps": 2400})
    f = study_forces.forces(deposits)
    assert sorted(f) == ["oblate", "prolate"]
    assert [r["zeta"] for r in f["prolate"]["per_shape"]] == [1, 1, 1]
    assert [r["eta"] for r in f["oblate"]["per_shape"]] == [1, 1, 1]
    assert f["prolate"]["trends"]["a_n"]["slope_per_unit_a/c"]["slope"] == pytest.approx(0.1)
    oblate = f["oblate"]["per_shape"]
    assert [r["a_n"]["mean"] for r in oblate] == pytest.approx([0.1, -0.45, -0.6])


def test_force_figure_from_the_deposits_files(tmp_path):
    """plot_forces: fbar(theta) / <f> and P(f/<f>) per shape are the seeds' means of the
    deposits' files, with the per-bin pooled error (two seeds at +-e: SE e); deposits without
    the files are left out; the figure is written"""
    import plot_forces
    e, deposits = 0.01, []
    for v in (1.0, 1.4, 2.0):
        for seed, s in ((1, 1), (2, -1), (3, 0)):
            folder = tmp_path / ("eta%g_s%d" % (v, seed))
            folder.mkdir()
            deposits.append({"eta": v, "zeta": v, "folder": str(folder)})
            if seed == 3:
                continue    # predates the force measures
            (folder / "packing.dat").write_text("mean_normal_force 2.0\nwindow_steps 2400\n")
            rows = ["%d %.9f 0.1 0.05 %.9f" % (k + 1, t, 2.0 * (1 + v * P2[k]) + 2 * s * e)
                    for k, t in enumerate(THETA)]
            (folder / "contact_force_histo.dat").write_text("# h\n# h\n# h\n1000 18\n"
                                                            + "\n".join(rows) + "\n")
            f = np.arange(20) * 0.25 + 0.125
            rows = ["%d %.6f %.9f 0.05" % (k + 1, x, math.exp(-x) + s * e)
                    for k, x in enumerate(f)]
            (folder / "force_histo.dat").write_text("# h\n# h\n# h\n1000 20\n" + "\n".join(rows)
                                                    + "\n")
    per_shape = plot_forces.curves(deposits)
    direction = plot_forces.mean_and_error(per_shape, "direction")
    magnitude = plot_forces.mean_and_error(per_shape, "magnitude")
    for v in (1.0, 1.4, 2.0):
        theta, m, err = direction[(v, v)]
        np.testing.assert_allclose(m, 1 + v * P2, atol=1e-8)
        np.testing.assert_allclose(err, e, rtol=1e-5)
        f, p, err = magnitude[(v, v)]
        np.testing.assert_allclose(p, np.exp(-f), atol=1e-8)
        np.testing.assert_allclose(err, e, rtol=1e-5)
    forces = {"deposits": 6, "per_shape": [
        dict({"eta": v, "zeta": v, "a/c": v * v, "seeds": 2},
             **{q: {"mean": 0.1 * v, "se": e} for q in study_forces.MEASURES})
        for v in (1.0, 1.4, 2.0)]}
    prolate = dict(forces, per_shape=[dict(r, zeta=1.0, **{"a/c": r["eta"]})
                                      for r in forces["per_shape"]])
    path = plot_forces.figure({"forces": {"diagonal": forces, "prolate": prolate}}, deposits,
                              str(tmp_path / "f.png"), "test")
    assert os.path.getsize(path) > 10000
    assert plot_forces.figure({}, deposits, str(tmp_path / "g.png"), "test") is None


def test_mean_over_shapes_that_disagree():
    """study_verdicts.mean_of_differences: differences that agree within their errors keep
    the propagated error; one shape far off the others (the equal-a/c comparison's case)
    widens it to the scatter between shapes, sd / sqrt(n) with n - 1 degrees of freedom, and
    a mean that only that shape carries is no longer decided"""
    e = 0.0007
    agree = study_verdicts.mean_of_differences([(0.003 + x, e, 2 * e * e) for x in
                                                (-1e-4, 0, 1e-4)], "5", 50, "up", "down")
    assert agree["se"] == pytest.approx(e / math.sqrt(3)) and agree["birge_ratio"] < 1
    assert agree["dof"] == 50 and agree["verdict"] == "up"
    apart = study_verdicts.mean_of_differences([(-0.001, e, 2 * e * e), (0.001, e, 2 * e * e),
                                                (0.008, e, 2 * e * e)], "5", 50, "up", "down")
    assert apart["se"] == pytest.approx(apart["sd_over_shapes"] / math.sqrt(3), rel=1e-12)
    assert apart["se_within"] == pytest.approx(e / math.sqrt(3)) and apart["dof"] == 2
    assert apart["mean"] / apart["se_within"] > 6    # decided without the scatter
    assert apart["mean_verdict"].startswith("undecided at 5 seeds; no number of seeds")
    # their scatter is beyond chance (chi^2 about the mean 74 on 2 dof): the verdict is each
    # shape's own, the third alone decided
    assert apart["chi2_about_mean_p"] < 1e-6
    assert [r["verdict"] for r in apart["per_shape"]][2] == "up"
    assert apart["verdict"].startswith("depends on shape") and apart["verdict"].endswith(
        "up in 1, undecided in 2 of 3 shapes")


def test_course_of_a_force_measure():
    """study_forces.shape_of_trend: a measure that rises and falls again (each step decided)
    is "not monotone" whatever its slope; a decided slope whose ends do not differ says so"""
    e = 0.01

    def line(values):
        deposits = []
        for v, y in zip((1.0, 1.2, 1.4, 2.0, 3.0), values):
            deposits += [{"eta": v, "zeta": v, "a_n": 0.1 + s * e, "a_f": y + s * e,
                          "K0": 0.5 + s * e, "window_steps": 2400} for s in (1, -1)]
        return study_forces.forces(deposits)["diagonal"]["trends"]["a_f"]

    assert study_forces.shape_of_trend(line((0.0, 0.2, 0.3, 0.2, 0.1))).startswith(
        "not monotone: rises to a/c 1.96 (+0.300 +- 0.014), then falls to a/c 9 (-0.200")
    assert study_forces.shape_of_trend(line((0.3, 0.1, 0.0, 0.1, 0.2))).startswith(
        "not monotone: falls to a/c 1.96")
    assert study_forces.shape_of_trend(line((0.0, 0.02, 0.04, 0.1, 0.2))) == "grows with a/c"
    # a fall with a bump that stays below the roundest (K0 on the prolate line) neither rises
    # nor dips below the thinnest: it is not "not monotone"
    assert study_forces.shape_of_trend(line((1.0, 0.8, 0.85, 0.5, 0.0))) == "falls with a/c"
    # a decided slope whose ends are level within their errors (K0 on the diagonal)
    assert study_forces.shape_of_trend({
        "slope_per_unit_a/c": {"verdict": "grows with a/c"},
        "thinnest_minus_roundest": {"difference": 0.098, "se": 0.111,
                                    "verdict": "undecided at 3 seeds; needs at least 42"}}) == (
        "slope: grows with a/c, but the thinnest against the roundest: +0.098 +- 0.111, "
        "undecided at 3 seeds; needs at least 42")


def test_verdict_per_shape_where_the_shapes_disagree_beyond_chance():
    """study_verdicts.mean_of_differences: shapes that agree keep the mean's verdict; shapes
    that scatter beyond chance (chi^2 p < 0.0027) get each its own verdict, counted; shapes
    within chance whose mean is undecided (its error widened by the Birge ratio, 2 dof) while
    each is decided the same way say so"""
    e = 0.001
    agree = study_verdicts.mean_of_differences([(0.010, e, 2 * e * e)] * 3, "5", 50, "up",
                                               "down", [(1.0, 1.0), (1.4, 1.4), (2.0, 2.0)])
    assert agree["verdict"] == "up" and "mean_verdict" not in agree
    assert [r["shape"] for r in agree["per_shape"]] == [[1.0, 1.0], [1.4, 1.4], [2.0, 2.0]]
    apart = study_verdicts.mean_of_differences(
        [(0.010, e, 2 * e * e), (0.020, e, 2 * e * e), (-0.005, e, 2 * e * e)], "5", 50, "up",
        "down")
    assert apart["verdict"].startswith("depends on shape")
    assert apart["verdict"].endswith("up in 2, down in 1 of 3 shapes")
    assert apart["seeds_needed"] is None and apart["mean_verdict"] != apart["verdict"]
    # chi^2 about the mean 8 on 2 dof: p = 0.018, within chance; the mean 0.010 +- 2 x
    # 0.001 / sqrt 3 with 2 dof is 2.5 sigma, each shape alone 8-12 sigma with 50 dof
    close = study_verdicts.mean_of_differences(
        [(0.008, e, 2 * e * e), (0.010, e, 2 * e * e), (0.012, e, 2 * e * e)], "5", 50, "up",
        "down")
    assert close["chi2_about_mean"] == pytest.approx(8.0)
    assert close["chi2_about_mean_p"] == pytest.approx(math.exp(-4.0), rel=1e-9)
    assert close["mean_verdict"].startswith("undecided")
    assert close["verdict"] == "up in each of the 3 shapes"
    # a shape's own degrees of freedom (the fourth entry) decide its t
    few = study_verdicts.mean_of_differences(
        [(0.010, e, 2 * e * e, 2), (0.020, e, 2 * e * e, 50), (-0.005, e, 2 * e * e, 50)],
        "5", 50, "up", "down")
    assert few["per_shape"][0]["dof"] == 2 and few["per_shape"][1]["dof"] == 50


def test_slope_counts_its_lack_of_fit():
    """study_stats.line_fit: points on a line keep the slope's error from their own; points
    that leave the line beyond chance widen it by the Birge ratio with n - 2 dof, and the
    force trend's verdict follows (no number of seeds decides a slope the points do not
    follow)"""
    x = np.array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    line = study_stats.line_fit(x, 0.5 + 0.01 * x, [0.01] * 6)
    assert line["slope"] == pytest.approx(0.01) and not line["lack_of_fit"]
    assert line["se"] == line["se_fit"] == pytest.approx(0.01 / math.sqrt(17.5))
    zigzag = 0.5 + 0.01 * x + 0.05 * np.array([1, -1, 1, -1, 1, -1])
    bad = study_stats.line_fit(x, zigzag, [0.01] * 6)
    assert bad["lack_of_fit"] and bad["chi2_dof"] == 4 and bad["chi2_p"] < 0.0027
    assert bad["se"] == pytest.approx(bad["se_fit"] * math.sqrt(bad["chi2"] / 4))
    e, deposits = 0.01, []
    for v, k0 in zip((1.0, 1.2, 1.4, 2.0, 3.0), (0.50, 0.75, 0.52, 0.80, 0.70)):
        deposits += [{"eta": v, "zeta": v, "a_n": 0.1 + s * e, "a_f": 0.1 + s * e,
                      "K0": k0 + s * e, "window_steps": 2400} for s in (1, -1)]
    t = study_forces.forces(deposits)["diagonal"]["trends"]["K0"]["slope_per_unit_a/c"]
    assert t["lack_of_fit"] and t["dof"] == 3 and t["seeds_needed"] is None
    assert abs(t["slope"] / t["se_fit"]) > 3 > abs(t["z_equivalent"])
    assert t["verdict"].startswith("undecided") and "no number of seeds" in t["verdict"]
    assert t["verdict"].endswith("the shapes leave the line beyond chance")


def test_force_measures_from_window_means_with_one_error_per_shape():
    """study_forces: deposits without window means (window_steps 0 or absent: snapshots of a
    ringing bed) are left out; the seed SD is pooled over the selection, so the sphere on the
    prolate and on the oblate line has one error; K0 mirrors a_f seed by seed (r < 0)"""
    deposits = []
    for v, spread in ((1.0, 0.01), (1.4, 0.01), (2.0, 0.01), (3.0, 0.03)):
        for shape in {(v, 1.0), (1.0, v)}:
            for s in (1, -1, 0):
                deposits.append({"eta": shape[0], "zeta": shape[1], "a_n": 0.1 * v,
                                 "a_f": 0.2 + s * spread, "K0": 0.6 - s * spread + 0.001 * s * s,
                                 "window_steps": 2400})
            deposits.append({"eta": shape[0], "zeta": shape[1], "a_n": 3.0, "a_f": 3.0,
                             "K0": 3.0, "window_steps": 0})
            deposits.append({"eta": shape[0], "zeta": shape[1], "a_n": 3.0, "a_f": 3.0,
                             "K0": 3.0})
    f = study_forces.forces(deposits)
    for line in ("prolate", "oblate"):
        rows = f[line]["per_shape"]
        assert [r["seeds"] for r in rows] == [3, 3, 3, 3]
        assert [r["K0"]["mean"] for r in rows] == pytest.approx([0.6 + 0.002 / 3] * 4)
    sphere = [f[line]["per_shape"][0]["K0"]["se"] for line in ("prolate", "oblate")]
    assert sphere[0] == sphere[1]
    m = study_forces.mirror(deposits)
    assert m["deposits"] == 21 and m["shapes"] == 7 and m["r"] < -0.99 and m["p"] < 1e-6
    assert study_forces.mirror(deposits[:5]) is None
