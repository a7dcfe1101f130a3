"""The flow solve's k per shape and its verdicts (tools/study/study_flow_lines.py) on rows made by
hand: the pooled relative seed SD, the two error terms and the verdicts against the spheres and
against isotropy, each computed here independently."""
import math

import pytest
from scipy import stats

from study_flow_lines import (deposit_cost, deposit_row, line_trends, prolate_against_oblate,
                              scatter_check, shape_means, summary, verdicts)


def bracket(k, err):
    """an extrapolation whose bracket has the half-width err * k around k"""
    return {"k0_fixed_p": k * (1 - err), "k_finest": k * (1 + err)}


def row(eta, zeta, seed, k_zz, k_xx, err=0.01, kc=1.0e-3, err_xx=None):
    """a deposit's json as pore_flow_lines.py writes it: relative half-widths err (err_xx for
    k_xx when given), and total errors (half-width and standard errors) twice that"""
    a = k_xx / k_zz
    err_xx = err if err_xx is None else err_xx
    return deposit_row({
        "eta": eta, "zeta": zeta, "seed": seed, "porosity": 0.4,
        "flow": {"medium": {"porosity": 0.41, "kozeny_carman": kc},
                 "ratio_to_kozeny_carman": {"xx": k_xx / kc, "zz": k_zz / kc},
                 "xx": k_xx, "xx_error": 2 * err_xx * k_xx, "zz": k_zz, "zz_error": 2 * err * k_zz,
                 "anisotropy_xx_zz": a, "anisotropy_xx_zz_error": 2 * err * a,
                 "extrapolation": {"xx": bracket(k_xx, err_xx), "zz": bracket(k_zz, err),
                                   "anisotropy_xx_zz": bracket(a, err)}}})


ROWS = [row(1, 1, 4, 1.00e-3, 1.00e-3), row(1, 1, 6, 1.02e-3, 1.02e-3),
        row(2, 2, 1, 1.60e-3, 1.92e-3), row(2, 2, 2, 1.64e-3, 1.968e-3),
        row(3, 1, 1, 1.10e-3, 1.10e-3), row(3, 1, 2, 1.12e-3, 1.12e-3),
        row(1, 3, 1, 1.05e-3, 1.05e-3, err=0.03)]


def test_the_errors_of_a_shape_mean():
    means = shape_means(ROWS)
    # relative deviations from each shape's mean: +-0.01/1.01, +-0.02/1.62, +-0.01/1.11
    rel = [0.01 / 1.01, 0.02 / 1.62, 0.01 / 1.11]
    sd = math.sqrt(sum(2 * x * x for x in rel) / 3)    # 3 dof, the single seed adds none
    # every group of the study's pooling has fewer than 4 dof: one pool of all shapes
    assert means["pooled"]["k_zz"] == {"all": (pytest.approx(sd, rel=1e-12), 3)}
    m = means[(2.0, 2.0)]["k_zz"]
    assert m["mean"] == pytest.approx(1.62e-3, rel=1e-12)
    assert m["stat"] == pytest.approx(1.62e-3 * sd / math.sqrt(2), rel=1e-12)
    assert m["sys"] == pytest.approx(0.01 * 1.62e-3, rel=1e-12)
    one = means[(1.0, 3.0)]["k_zz"]    # one seed: the pooled SD alone, its own 3 %
    assert one["stat"] == pytest.approx(1.05e-3 * sd, rel=1e-12)
    assert one["sys"] == pytest.approx(0.03 * 1.05e-3, rel=1e-12)
    assert means[(1.0, 1.0)]["k_zz_over_kozeny_carman"]["mean"] == pytest.approx(1.01)
    # (2, 2)'s k_xx 1.92e-3 and 1.968e-3 over k_KC 1e-3
    assert means[(2.0, 2.0)]["k_xx_over_kozeny_carman"]["mean"] == pytest.approx(1.944)


def test_k_over_kozeny_carman_carries_its_own_direction_s_bias():
    """k_xx / k_KC takes k_xx's relative extrapolation bias (4 % here), k_zz / k_KC k_zz's (1 %)"""
    rows = [row(1, 1, 4, 1.00e-3, 1.20e-3, err_xx=0.04),
            row(1, 1, 6, 1.02e-3, 1.24e-3, err_xx=0.04)]
    m = shape_means(rows)[(1.0, 1.0)]
    assert m["k_xx_over_kozeny_carman"]["mean"] == pytest.approx(1.22)
    assert m["k_xx_over_kozeny_carman"]["sys"] == pytest.approx(0.04 * 1.22, rel=1e-12)
    assert m["k_zz_over_kozeny_carman"]["sys"] == pytest.approx(0.01 * 1.01, rel=1e-12)


def sd_by_hand():
    rel = [0.01 / 1.01, 0.02 / 1.62, 0.01 / 1.11]
    return math.sqrt(sum(2 * x * x for x in rel) / 3)


def test_verdicts_against_the_spheres_and_isotropy():
    v = {(s, q): d for s, q, d in verdicts(shape_means(ROWS))}
    high = v[((2.0, 2.0), "k_zz")]
    sd = sd_by_hand()
    stat = math.hypot(1.62e-3 * sd, 1.01e-3 * sd) / math.sqrt(2)
    sys = math.hypot(0.01 * 1.62e-3, 0.01 * 1.01e-3)
    assert high["z"] == pytest.approx(0.61e-3 / math.hypot(stat, sys), rel=1e-12)
    # Student's t with Welch-Satterthwaite's dof: the pooled SD's 3, the bias none of its own
    assert high["dof"] == pytest.approx(3 * (1 + (sys / stat) ** 2) ** 2, rel=1e-12)
    assert high["z_equivalent"] == pytest.approx(
        stats.norm.isf(stats.t.sf(high["z"], high["dof"])), rel=1e-9)
    assert high["z_equivalent"] >= 3
    assert high["verdict"] == "higher than the spheres'"
    # 10 % above the spheres with 1-2 % errors: z about 4.7, 3 sigma only because the bias,
    # half of the error, brings no sampling error (t with the pooled 3 dof alone: 2.6 sigma)
    prolate = v[((3.0, 1.0), "k_zz")]
    stat = math.hypot(1.11e-3 * sd, 1.01e-3 * sd) / math.sqrt(2)
    sys = math.hypot(0.01 * 1.11e-3, 0.01 * 1.01e-3)
    assert prolate["z"] == pytest.approx(0.10e-3 / math.hypot(stat, sys), rel=1e-12)
    assert stats.norm.isf(stats.t.sf(prolate["z"], 3)) < 3 <= prolate["z_equivalent"]
    assert prolate["verdict"] == "higher than the spheres'"
    # one seed 4 % above the spheres, its bias 3 %: z by hand, undecided
    lone = v[((1.0, 3.0), "k_zz")]
    stat = math.hypot(1.05e-3 * sd, 1.01e-3 * sd / math.sqrt(2))
    assert lone["z"] == pytest.approx(0.04e-3 / math.hypot(
        stat, math.hypot(0.03 * 1.05e-3, 0.01 * 1.01e-3)), rel=1e-12)
    assert lone["verdict"].startswith("undecided at 1-2 seeds")
    assert v[((1.0, 3.0), "k_zz")]["verdict"].startswith("undecided")
    # k_xx / k_zz = 1.2 at (2, 2): against 1, not against the spheres
    assert v[((2.0, 2.0), "anisotropy")]["verdict"] == "k_xx > k_zz"
    assert v[((1.0, 1.0), "anisotropy")]["verdict"].startswith("undecided")
    assert ((1.0, 1.0), "k_zz") not in v


def test_prolate_against_oblate_at_equal_aspect_ratio():
    """(a, 1) less (1, a) where both lines have a: here a = 3 only, the prolate pair of seeds
    against the oblate single seed, its z by hand; then a decided pair"""
    got = {(a, q): d for a, q, d in prolate_against_oblate(shape_means(ROWS))}
    assert {a for a, _ in got} == {3.0}
    sd = sd_by_hand()
    d = got[(3.0, "k_zz")]
    stat = math.hypot(1.11e-3 * sd / math.sqrt(2), 1.05e-3 * sd)
    sys = math.hypot(0.01 * 1.11e-3, 0.03 * 1.05e-3)
    assert d["difference"] == pytest.approx(0.06e-3, rel=1e-9)
    assert d["z"] == pytest.approx(0.06e-3 / math.hypot(stat, sys), rel=1e-9)
    assert d["verdict"].startswith("undecided at 1-2 seeds")
    # plates lying flat: k_xx / k_zz about 1.5 on the oblate line, 1.1 on the prolate line
    rows = ROWS[:2] + [row(2, 1, 1, 1.00e-3, 1.10e-3), row(2, 1, 2, 1.02e-3, 1.122e-3),
                       row(1, 2, 1, 0.80e-3, 1.20e-3), row(1, 2, 2, 0.82e-3, 1.25e-3)]
    got = {(a, q): d for a, q, d in prolate_against_oblate(shape_means(rows))}
    d = got[(2.0, "anisotropy")]
    assert d["difference"] == pytest.approx(1.1 - (1.5 + 1.25 / 0.82) / 2, rel=1e-9)
    assert d["stat"] > 0 and d["z"] < -3
    assert d["verdict"] == "higher on the oblate line"


def test_without_an_error_estimate_undecided():
    """one seed per shape (no scatter to pool) or no bracket (one voxel): no verdict"""
    single = [ROWS[0], ROWS[2]]
    assert all(d["verdict"] == "undecided: no error estimate"
               for _, _, d in verdicts(shape_means(single)))
    one_voxel = [dict(r, k_zz_bias="", k_xx_bias="", anisotropy_bias="") for r in ROWS]
    assert all(d["verdict"] == "undecided: no error estimate"
               for _, _, d in verdicts(shape_means(one_voxel)))


def test_without_spheres_no_comparison_with_them():
    v = verdicts(shape_means(ROWS[2:]))
    assert {q for _, q, _ in v} == {"anisotropy"}


def test_the_summary_groups_shapes_by_verdict():
    """the verdicts above (worked out by hand there) grouped per quantity, undecided last"""
    got = summary(verdicts(shape_means(ROWS)))
    assert list(got) == ["k_zz", "k_xx", "anisotropy", "k_zz_over_kozeny_carman",
                         "k_xx_over_kozeny_carman"]
    assert got["k_zz"] == [("higher than the spheres'", [(2.0, 2.0), (3.0, 1.0)]),
                           ("undecided", [(1.0, 3.0)])]
    assert got["anisotropy"] == [("k_xx > k_zz", [(2.0, 2.0)]),
                                 ("undecided", [(1.0, 1.0), (1.0, 3.0), (3.0, 1.0)])]
    # every row has the same k_KC, so k / k_KC is k scaled, with k's relative errors: the same
    # verdicts as k in each direction
    assert got["k_zz_over_kozeny_carman"] == got["k_zz"]
    assert got["k_xx_over_kozeny_carman"] == got["k_xx"]


def test_the_cost_sums_every_solve_once():
    """each resolution's seconds (already summed over its offsets) over directions and
    resolutions: a run resumed solve by solve reads its earlier solves' times from the kept
    solves, so no segment is lost; without the solves there is no cost, not a zero"""
    resolutions = [{"seconds": {"xx": 300.0, "zz": 200.0},
                    "solver_cpu_seconds": {"xx": 250.0, "zz": 150.0}},
                   {"seconds": {"xx": 900.0, "zz": 700.0},
                    "solver_cpu_seconds": {"xx": 400.0, "zz": 380.0}}]
    assert deposit_cost({"resolutions": resolutions}) == {
        "solve_seconds": 2100.0, "solver_cpu_seconds": 1180.0}
    assert deposit_cost({}) == {"solve_seconds": "", "solver_cpu_seconds": ""}
    assert ROWS[0]["solve_seconds"] == ""


def test_the_summary_rows_of_the_findings(monkeypatch):
    """study.md's summary of findings: per quantity each line's most aspherical shape (the
    spheres too against isotropy) with its difference from the reference, the combined error
    and the verdict's z; the shapes counted by verdict; the prolate against the oblate
    anisotropy at equal a"""
    import study_doc_flow
    rows = ROWS + [row(2, 1, 1, 1.00e-3, 1.10e-3), row(2, 1, 2, 1.02e-3, 1.122e-3),
                   row(1, 2, 1, 0.80e-3, 1.20e-3), row(1, 2, 2, 0.82e-3, 1.25e-3)]
    monkeypatch.setattr(study_doc_flow, "flow_rows", lambda results: rows)
    got = {r[0].split(" (flow solve")[0]: r[1:] for r in study_doc_flow.summary_rows("x")}
    cells, verdict = got["k_zz - the spheres' in 1e-4 d^2"]
    cells = cells.split("; ")
    assert [c.split(" ")[0] + c.split(" ")[1] for c in cells] == ["(2,2)", "(3,1)", "(1,3)"]
    m, ref = shape_means(rows)[(2.0, 2.0)]["k_zz"], shape_means(rows)[(1.0, 1.0)]["k_zz"]
    err = math.hypot(math.hypot(m["stat"], ref["stat"]), math.hypot(m["sys"], ref["sys"]))
    assert cells[0].startswith("(2, 2) %+.2f +- %.2f (" % (1e4 * (m["mean"] - ref["mean"]),
                                                          1e4 * err))
    assert verdict == ("lower than the spheres' at (1, 2); higher than the spheres' at (2, 2), "
                       "(3, 1); undecided in 2 of 5 shapes")
    cells, verdict = got["k_xx / k_zz - 1"]
    assert cells.startswith("the spheres +0.000 +- ")
    assert verdict == "k_xx > k_zz at (1, 2), (2, 1), (2, 2); undecided in 3 of 6 shapes"
    cells, verdict = got["k_xx / k_zz: prolate (a, 1) - oblate (1, a)"]
    assert cells.startswith("a = 2 -0.41") and cells.split("; ")[1].startswith("a = 3 ")
    assert verdict == "higher on the oblate line at a = 2; undecided in 1 of 2 aspect ratios"
    monkeypatch.setattr(study_doc_flow, "flow_rows", lambda results: [])
    assert study_doc_flow.summary_rows("x") == []


def test_the_trend_along_a_line():
    """k_zz exactly linear in a/c on the prolate line (1.0, 1.2, 1.4e-3 at a/c 1, 2, 3, the
    seeds 1 % either side): the slope 0.2e-3, its statistical and systematic parts propagated
    apart by hand, Welch-Satterthwaite's dof, "grows with a/c"; a line of two shapes has none"""
    rows = [row(e, 1, seed, k * f, k * f) for e, k in ((1, 1.0e-3), (2, 1.2e-3), (3, 1.4e-3))
            for seed, f in ((1, 0.99), (2, 1.01))]
    means = shape_means(rows)
    t = {(line, q): d for line, q, d in line_trends(means)}
    assert {line for line, _ in t} == {"prolate"}
    d = t[("prolate", "k_zz")]
    (sd, dof), = means["pooled"]["k_zz"].values()    # one group: the spheroids
    assert sd == pytest.approx(0.01 * math.sqrt(2), rel=1e-9) and dof == 3
    k = [1.0e-3, 1.2e-3, 1.4e-3]
    stat = [v * sd / math.sqrt(2) for v in k]
    sys = [0.01 * v for v in k]
    w = [1 / (a * a + b * b) for a, b in zip(stat, sys)]
    xm = sum(wi * x for wi, x in zip(w, (1, 2, 3))) / sum(w)
    sxx = sum(wi * (x - xm) ** 2 for wi, x in zip(w, (1, 2, 3)))
    c = [wi * (x - xm) / sxx for wi, x in zip(w, (1, 2, 3))]
    stat_slope = math.sqrt(sum((ci * a) ** 2 for ci, a in zip(c, stat)))
    sys_slope = math.sqrt(sum((ci * b) ** 2 for ci, b in zip(c, sys)))
    assert d["slope"] == pytest.approx(0.2e-3, rel=1e-9)
    assert d["se"] == pytest.approx(math.sqrt(1 / sxx), rel=1e-9)
    assert (d["stat"], d["sys"]) == (pytest.approx(stat_slope, rel=1e-9),
                                     pytest.approx(sys_slope, rel=1e-9))
    assert d["dof"] == pytest.approx(3 * (1 + (sys_slope / stat_slope) ** 2) ** 2, rel=1e-9)
    assert not d["lack_of_fit"] and d["verdict"] == "grows with a/c"
    assert line_trends(shape_means(rows[:4])) == []


def test_a_trend_that_is_not_a_line():
    """k_zz 1.0, 1.6, 1.2e-3 at a/c 1, 2, 3: chi^2 about the line beyond chance, so the
    slope's error (both parts) is scaled by the Birge ratio, its dof are the line's n - 2 = 1,
    and no number of seeds decides it"""
    rows = [row(e, 1, seed, k * f, k * f) for e, k in ((1, 1.0e-3), (2, 1.6e-3), (3, 1.2e-3))
            for seed, f in ((1, 0.99), (2, 1.01))]
    d = {(line, q): t for line, q, t in line_trends(shape_means(rows))}[("prolate", "k_zz")]
    assert d["lack_of_fit"] and d["chi2_p"] < 0.0027
    birge = math.sqrt(d["chi2"] / 1)
    assert d["se"] == pytest.approx(d["se_fit"] * birge, rel=1e-12)
    assert math.hypot(d["stat"], d["sys"]) == pytest.approx(d["se"], rel=1e-9)
    assert d["dof"] == 1 and d["seeds_needed"] is None
    assert d["verdict"] == ("undecided at 2 seeds; no number of seeds decides it: the shapes "
                            "leave the line beyond chance")


def test_the_block_of_study_md(monkeypatch):
    """the whole generated block on hand-made rows: its sentences in order, the comparisons
    counted with what chance would decide, the four tables, and no cost without solves"""
    import study_doc_flow
    from study_stats import CHANCE_P
    rows = ROWS + [row(2, 1, 1, 1.00e-3, 1.10e-3), row(2, 1, 2, 1.02e-3, 1.122e-3),
                   row(1, 2, 1, 0.80e-3, 1.20e-3), row(1, 2, 2, 0.82e-3, 1.25e-3)]
    monkeypatch.setattr(study_doc_flow, "flow_rows", lambda results: rows)
    parts = study_doc_flow.flow_lines_block("x").split("\n\n")
    assert [p.split(" ")[0] for p in parts[:4]] == ["Summary", "Prolate", "Along", "Deposits"]
    means = shape_means(rows)
    tests = (len(verdicts(means)) + len(prolate_against_oblate(means))
             + len(line_trends(means)))
    assert "Deposits solved: 11 of the 20 planned" in parts[3]
    assert "%d comparisons" % tests in parts[3] and "%.2f of them" % (tests * CHANCE_P) in parts[3]
    assert "No solve's cost recorded." in parts[3]
    assert "Bartlett's test that the shapes scatter alike" in parts[3]
    assert len(parts) == 8 and all(p.startswith("| ") for p in parts[4:])


def test_the_shapes_scatter_alike_bartlett_by_hand():
    """each shape's own relative seed SD and Bartlett's statistic written out: k = 3 shapes of
    two seeds (the lone seed has no SD), variances of the values over their shape's mean"""
    c = scatter_check(ROWS)["k_zz"]
    own = {(1.0, 1.0): (1.00, 1.02), (2.0, 2.0): (1.60, 1.64), (3.0, 1.0): (1.10, 1.12)}
    var = {s: 2 * ((a - b) / (a + b)) ** 2 for s, (a, b) in own.items()}    # (n - 1) = 1
    assert set(c["own"]) == set(own)
    for s, v in var.items():
        assert c["own"][s] == pytest.approx(math.sqrt(v), rel=1e-9)
    k, n = 3, 6
    pooled = sum(var.values()) / (n - k)
    t = ((n - k) * math.log(pooled) - sum(math.log(v) for v in var.values())) / (
        1 + (k * 1 - 1 / (n - k)) / (3 * (k - 1)))
    assert c["bartlett_p"] == pytest.approx(stats.chi2.sf(t, k - 1), rel=1e-9)
    assert scatter_check(ROWS[:1] + ROWS[6:])["k_zz"]["bartlett_p"] is None
    twice = scatter_check(ROWS + [ROWS[6]])["k_zz"]    # the lone seed counted twice
    assert twice["identical"] == [(1.0, 3.0)] and twice["bartlett_p"] is None


def test_a_deposit_solved_before_the_domain_medium_is_named():
    """a json without the flow domain's own medium (solved before it was recorded): a clear
    error naming the folder and what to run, not a KeyError"""
    old = {"folder": "runs/x", "eta": 1, "zeta": 1, "seed": 1, "porosity": 0.4,
           "flow": {"xx": 1e-3, "zz": 1e-3, "anisotropy_xx_zz": 1.0}}
    with pytest.raises(ValueError, match="runs/x: solved before .*pore_flow_lines.py"):
        deposit_row(old)
