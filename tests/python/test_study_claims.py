"""tools/study/study_claims.py against a synthetic results folder with known answers.

At delta_r = 0 with the default law (coulomb):
* phi on the diagonal is a parabola with its vertex at 1.45 (two seeds, +-0.001 about it,
  except 1.6 with one seed): the fitted maximum is 1.45 within its bootstrap SD, and that SD
  is what the seed scatter gives: 0.001 pooled, about 0.01 in the position here;
* the map is symmetric except one pair that differs by 0.01, 7 of its standard errors;
* along eta = 2.2, phi over zeta is a parabola with its vertex at zeta = 2.15; every other
  eta has fewer than three values of zeta;
* the histograms are P = (1 + A P2(cos theta)) / (4 pi) on 18 bins: they cross the isotropic
  value where P2 = 0, theta = acos(1/sqrt 3) = 0.9553, falling for A > 0 (contact normals)
  and rising for A < 0 (long axes), to within the linear interpolation between bins.
Polydispersity: at delta_r = 0.3 phi is shifted by a known amount per line (seeds +-0.002,
the oblate shape +-0.004, one shape with one seed) and the histograms' seeds have amplitudes
A +- 0.05 (their mean as at delta_r 0, where the seeds differ by +-0.002 beyond pi/2 only); at
delta_r = 0.6 one shape, shifted by 0.001, with amplitude A + 0.1.
The viscous law: on the diagonal at delta_r = 0 a parabola with its vertex at 1.55 and
histograms shifted by 0.1 A, which cross where P2 = 0.1.
"""
import csv
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

ROOT = os.environ.get("ELLIPSOID_DEP_ROOT",
                      os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
TOOL = os.path.join(ROOT, "tools", "study", "study_claims.py")
MAGIC = math.acos(1 / math.sqrt(3))
THETA = (np.arange(18) + 0.5) * math.pi / 18
P2 = 0.5 * (3 * np.cos(THETA) ** 2 - 1)
DIAGONAL = [1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7, 1.8, 2]
CONSTANT_ETA = [(2.2, z) for z in (1.7, 1.9, 2.1, 2.3, 2.5)]
SHIFT_03 = {"diagonal": 0.004, "prolate": 0.006, "oblate": 0.002, "other": 0.008}
SEED_AMPLITUDE = 0.05    # the histograms' seed scatter at delta_r > 0
SEED_TAIL = 0.002        # and at delta_r 0, beyond pi/2
VISCOUS_OFFSET = -0.1    # P = (1 + A (P2 + offset)) / (4 pi): crosses where P2 = -offset


def histo(path, amplitude, offset=0.0, tail=0.0):
    """tail: added to P beyond pi/2, where no crossing is sought"""
    p = (1 + amplitude * (P2 + offset)) / (4 * math.pi) + np.where(THETA > math.pi / 2, tail, 0)
    with open(path, "w") as f:
        f.write("# Time-averaged data\n# TimeStep Number-of-rows\n# Row c_h[1] c_h[2] c_h[3]\n")
        f.write("1000 18\n")
        for k, (t, v) in enumerate(zip(THETA, p), 1):
            f.write("%d %.9f %.9e %.6f\n" % (k, t, v, 0.05))


def coulomb_phi(eta, zeta):
    if eta == zeta:
        return 0.63 - 0.1 * (eta - 1.45) ** 2
    if eta == 2.2:
        return 0.60 - 0.2 * (zeta - 2.15) ** 2
    return {(1.6, 1.2): 0.63, (1.3, 1.0): 0.615, (1.0, 1.4): 0.625}.get((eta, zeta), 0.62)


def viscous_phi(eta):
    return 0.62 - 0.1 * (eta - 1.55) ** 2


def amplitude(eta, zeta):
    return 0.0 if eta == zeta == 1 else 0.3 * (eta * zeta - 1)


def write_results(root, polydisperse_and_viscous=True):
    """the synthetic study; without its polydisperse and viscous deposits on request"""
    rows = []

    def deposit(eta, zeta, dr, law, seeds, phi, amp, offset=0.0):
        """seeds: ((seed, phi noise, histogram amplitude noise[, tail]), ...)"""
        point = "eta%g_zeta%g_dr%g_N3000_%s" % (eta, zeta, dr, law)
        for seed, noise, amp_noise, *tail in seeds:
            folder = os.path.join(root, "points", point, "s%d" % seed)
            os.makedirs(folder)
            histo(os.path.join(folder, "contact_histo.dat"), amp + amp_noise, offset, *tail)
            histo(os.path.join(folder, "orient_histo.dat"), -amp - amp_noise, offset, *tail)
            rows.append({"point": point, "eta": eta, "zeta": zeta, "delta_r": dr, "N": 3000,
                         "law": law, "seed": seed, "phi": phi + noise})

    shapes = ([(v, v) for v in DIAGONAL] + [(1.4, 2.0), (2.0, 1.4), (1.2, 1.6), (1.6, 1.2)]
              + CONSTANT_ETA + [(1.3, 1.0), (1.0, 1.4)])
    for eta, zeta in shapes:
        seeds = ((1, 0.0, 0.0),) if (eta, zeta) == (1.6, 1.6) else (
            (1, 0.001, 0.0, SEED_TAIL), (2, -0.001, 0.0, -SEED_TAIL))
        deposit(eta, zeta, 0, "coulomb", seeds, coulomb_phi(eta, zeta), amplitude(eta, zeta))
    if polydisperse_and_viscous:
        scatter = ((1, 0.002, SEED_AMPLITUDE), (2, -0.002, -SEED_AMPLITUDE))
        scatter_oblate = ((1, 0.004, SEED_AMPLITUDE), (2, -0.004, -SEED_AMPLITUDE))
        for eta, zeta in [(v, v) for v in DIAGONAL] + [(1.3, 1.0), (1.0, 1.4), (1.4, 2.0)]:
            line = {(1.3, 1.0): "prolate", (1.0, 1.4): "oblate", (1.4, 2.0): "other"}.get(
                (eta, zeta), "diagonal")
            seeds = {"other": ((1, 0.0, 0.0),), "oblate": scatter_oblate}.get(line, scatter)
            deposit(eta, zeta, 0.3, "coulomb", seeds, coulomb_phi(eta, zeta) + SHIFT_03[line],
                    amplitude(eta, zeta))
        deposit(1.6, 1.8, 0.3, "coulomb", scatter, 0.5, 0.5)    # not at delta_r 0
        deposit(1.4, 1.4, 0.6, "coulomb", ((1, 0.003, SEED_AMPLITUDE),
                                           (2, -0.003, -SEED_AMPLITUDE)),
                coulomb_phi(1.4, 1.4) + 0.001, amplitude(1.4, 1.4) + 0.1)
        for v in DIAGONAL:
            deposit(v, v, 0, "viscous", ((1, 0.001, 0.0), (2, -0.001, 0.0)), viscous_phi(v),
                    amplitude(v, v), VISCOUS_OFFSET)
    with open(os.path.join(root, "deposits.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def run_tool(root):
    out = subprocess.run([sys.executable, TOOL, str(root)], capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 0, out.stderr
    return json.load(open(os.path.join(str(root), "claims.json"))), out.stdout


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    root = tmp_path_factory.mktemp("study")
    write_results(str(root))
    return run_tool(root)


def test_claims_of_a_synthetic_study(study):
    c, stdout = study
    assert c["forces"] is None    # no deposit with the force measures
    m = c["maxima"]["diagonal"]
    assert m["x_highest"] in (1.4, 1.5)
    assert m["seed_sd"] == pytest.approx(0.001 * math.sqrt(2), rel=1e-9)
    assert 0.002 < m["x_max_sd"] < 0.05
    assert m["bootstrap_kept"] > 0.95 * m["bootstrap_draws"]
    assert abs(m["x_max"] - 1.45) < 3 * m["x_max_sd"]
    assert m["phi_max"] == pytest.approx(0.63, abs=0.002)
    assert set(c["maxima"]) == {"diagonal"}    # prolate and oblate: two points each
    s = c["symmetry"]
    assert s["pairs"] == 2 and s["pairs_with_errors"] == 2
    # seeds +-0.001 everywhere: pooled SD 0.001 sqrt(2), SE of a two-seed point 0.001, of a
    # difference 0.001 sqrt(2); one pair equal, the other 0.01 apart: chi2 = (0 + 0.01^2 /
    # 2e-6) / 2
    assert s["chi2_per_pair"] == pytest.approx(25.0, rel=1e-6)
    assert s["mean_difference"] == pytest.approx(-0.005, abs=1e-12)
    for key in ("contact_normals", "long_axes"):
        crossings = c["crossings"][key]
        # every shape at delta_r 0 with the default law but the (flat) sphere
        assert len(crossings) == len({(r["eta"], r["zeta"]) for r in crossings}) == 19
        for r in crossings:
            # the zero lies 0.0046 from a bin centre: a crossing without the interpolation
            # between bins would be off by that much
            assert abs(r["theta"] - MAGIC) < 1e-3, r
            if (r["eta"], r["zeta"]) == (1.6, 1.6):
                assert r["seeds"] == 1 and r["sem"] is None
            else:
                assert r["seeds"] == 2 and r["sem"] == pytest.approx(0.0, abs=1e-12)
    assert c["crossings"]["summary"]["contact"]["shapes"] == 19
    assert c["deposits"] == 2 * 20 - 1
    assert "fitted maximum" in stdout


def test_maximum_along_constant_eta(study):
    c, stdout = study
    (m,) = c["constant_eta"]    # the only eta with three values of zeta or more
    assert m["eta"] == 2.2 and m["zetas"] == 5 and m["x_highest"] == 2.1
    assert m["x_max"] == pytest.approx(2.15, abs=1e-9)    # the seed means lie on the parabola
    assert m["phi_max"] == pytest.approx(0.60, abs=1e-9)
    assert m["seed_sd"] == pytest.approx(0.001 * math.sqrt(2), rel=1e-9)
    assert 0 < m["x_max_sd"] < 0.05
    assert "| 2.2 | 5 |" in stdout and "-0.050" in stdout


def mean_and_sem(diffs_sems):
    d = [x for x, _ in diffs_sems]
    return np.mean(d), math.sqrt(sum(s * s for _, s in diffs_sems)) / len(d)


# the seed SD at delta_r 0.3 pooled over its 12 shapes with two seeds, one of them the oblate
# shape (a pair +-x has the variance 2 x^2): the spheroids' (sphere, prolate and oblate shape:
# 3 degrees of freedom, fewer than study_stats.MIN_DOF) take it; the general shapes pool their
# own 9 (all +-0.002: the thin (2, 2) alone has 1 and merges with the rest)
POOLED_03 = math.sqrt((11 * 2 * 0.002 ** 2 + 2 * 0.004 ** 2) / 12)
GENERAL_03 = 0.002 * math.sqrt(2)


def se_03(line, shape):
    """the standard error of a shape's phi at delta_r 0.3"""
    if line in ("prolate", "oblate") or shape == (1.0, 1.0):
        return POOLED_03 / math.sqrt(2)
    return GENERAL_03 / (1 if line == "other" else math.sqrt(2))


def test_polydisperse_density(study):
    c, stdout = study
    by_dr = {p["delta_r"]: p for p in c["polydispersity"]["density"]}
    assert sorted(by_dr) == [0.3, 0.6]
    p = by_dr[0.3]
    per_line = p["phi_difference"]["per_shape"]
    assert {k: len(v) for k, v in per_line.items()} == {"diagonal": 9, "prolate": 1,
                                                        "oblate": 1, "other": 1}
    expected = []    # (difference, its standard error)
    for line, rows in per_line.items():
        for r in rows:
            assert r["difference"] == pytest.approx(SHIFT_03[line], abs=1e-12), r
            shape = (r["eta"], r["zeta"])
            # a point's SE: its group's pooled SD at its own delta_r / sqrt(its seeds),
            # whatever its own scatter (the oblate shape's is twice the others')
            se_0 = 0.001 * math.sqrt(2) if shape == (1.6, 1.6) else 0.001
            assert r["sem"] == pytest.approx(math.hypot(se_03(line, shape), se_0),
                                             rel=1e-6), r
            assert r["seeds"] == [1 if line == "other" else 2, 1 if shape == (1.6, 1.6) else 2]
            expected.append((r["difference"], r["sem"]))
        mean = p["phi_difference"]["mean"][line]
        assert mean["shapes"] == len(rows)
        assert mean["mean"] == pytest.approx(SHIFT_03[line], abs=1e-12)
    total = p["phi_difference"]["mean"]["all"]
    mean, sem = mean_and_sem(expected)
    assert total["shapes"] == 12
    assert total["mean"] == pytest.approx((9 * 0.004 + 0.006 + 0.002 + 0.008) / 12, abs=1e-12)
    assert total["mean"] == pytest.approx(mean, abs=1e-12)
    assert total["sem"] == pytest.approx(sem, rel=1e-9)
    m = p["diagonal_maximum"]    # the delta_r 0 parabola raised by 0.004
    assert m["seed_sd"] == pytest.approx(GENERAL_03, rel=1e-9)    # its highest point's
    assert abs(m["x_max"] - 1.45) < 3 * m["x_max_sd"]
    assert m["phi_max"] == pytest.approx(0.634, abs=0.002)
    q = by_dr[0.6]
    (r,) = q["phi_difference"]["per_shape"]["diagonal"]
    assert (r["eta"], r["zeta"]) == (1.4, 1.4)
    assert r["difference"] == pytest.approx(0.001, abs=1e-12)
    assert r["sem"] == pytest.approx(math.hypot(0.003, 0.001), rel=1e-6)
    assert q["diagonal_maximum"] is None    # one point on the diagonal
    assert "polydispersity" in stdout


def test_histograms_against_delta_r(study):
    c, stdout = study
    hist = {(h["eta"], h["zeta"]): h for h in c["polydispersity"]["histograms"]}
    # the shapes at delta_r 0.3 and 0: 9 diagonal, prolate, oblate and (1.4, 2); not (1.6, 1.8)
    assert sorted(hist) == sorted([(v, v) for v in DIAGONAL] + [(1.3, 1.0), (1.0, 1.4),
                                                                (1.4, 2.0)])
    # seed-mean histograms as at delta_r 0; the seeds' amplitudes +-0.05 give a standard
    # error of 0.05 |P2| / (4 pi) per bin at delta_r 0.3, their tails +-0.002 at 0 beyond pi/2
    se_03 = SEED_AMPLITUDE * np.abs(P2) / (4 * math.pi)
    se_0 = np.where(THETA > math.pi / 2, SEED_TAIL, 0.0)
    scatter = math.sqrt(np.mean(se_03 ** 2 + se_0 ** 2))
    for shape, h in hist.items():
        drs = [p["delta_r"] for p in h["per_delta_r"]]
        assert drs == ([0.0, 0.3, 0.6] if shape == (1.4, 1.4) else [0.0, 0.3])
        for p in h["per_delta_r"]:
            for key in ("contact_normals", "long_axes"):
                if shape == (1.0, 1.0) and p["delta_r"] == 0.0:
                    assert p[key] is None    # flat: no crossing
                else:
                    assert abs(p[key]["theta"] - MAGIC) < 1e-3, (shape, p)
        d = {x["delta_r"]: x for x in h["differences"]}
        assert sorted(d) == drs[1:]    # against delta_r 0, not itself
        for key in ("contact_normals", "long_axes"):
            x = d[0.3][key]
            assert x["rms_difference"] < 1e-8, (shape, x)
            if shape in ((1.6, 1.6), (1.4, 2.0)):    # one seed at delta_r 0 or at 0.3
                assert x["rms_seed_scatter"] is None
            else:
                assert x["rms_seed_scatter"] == pytest.approx(scatter, rel=1e-5), (shape, x)
        if shape == (1.4, 1.4):    # amplitude 0.1 higher at delta_r 0.6
            for key in ("contact_normals", "long_axes"):
                assert d[0.6][key]["rms_difference"] == pytest.approx(
                    0.1 * math.sqrt(np.mean(P2 ** 2)) / (4 * math.pi), rel=1e-5)
                assert d[0.6][key]["rms_seed_scatter"] == pytest.approx(scatter, rel=1e-5)
    assert scatter > 1.1 * math.sqrt(np.mean(se_03 ** 2))    # the tails count
    assert "one seed" in stdout


def test_viscous_law(study):
    c, stdout = study
    (law,) = c["laws"]
    assert law["law"] == "viscous" and law["delta_r"] == 0.0 and law["deposits"] == 18
    m = law["diagonal_maximum"]
    assert m["x_max"] == pytest.approx(1.55, abs=1e-9) and m["phi_max"] == pytest.approx(0.62,
                                                                                         abs=1e-9)
    assert m["seed_sd"] == pytest.approx(0.001 * math.sqrt(2), rel=1e-9) and m["x_max_sd"] > 0
    per_line = law["phi_difference"]["per_shape"]
    assert [len(per_line[k]) for k in ("prolate", "oblate", "other")] == [0, 0, 0]
    expected = []
    for r in per_line["diagonal"]:
        e = r["eta"]
        assert r["difference"] == pytest.approx(viscous_phi(e) - coulomb_phi(e, e), abs=1e-12)
        se_0 = 0.001 * math.sqrt(2) if e == 1.6 else 0.001
        assert r["sem"] == pytest.approx(math.hypot(0.001, se_0), rel=1e-6)
        expected.append((r["difference"], r["sem"]))
    mean, sem = mean_and_sem(expected)
    assert len(expected) == 9
    assert law["phi_difference"]["mean"]["all"]["mean"] == pytest.approx(mean, abs=1e-12)
    assert law["phi_difference"]["mean"]["all"]["sem"] == pytest.approx(sem, rel=1e-9)
    # its curves cross where P2 = 0.1: theta = 0.886, within the linear interpolation's
    # 1.4e-3 there (the default law's cross at 0.955)
    crossing = math.acos(math.sqrt((1 - 2 * VISCOUS_OFFSET) / 3))    # P2 = -offset
    for key in ("contact", "orient"):
        summary = law["crossings"]["summary"][key]
        assert summary["shapes"] == 8    # the diagonal but the sphere
        assert abs(summary["mean"] - crossing) < 2e-3, summary
    assert "tangential laws against coulomb" in stdout and "| viscous | 0 |" in stdout


def test_without_the_polydisperse_and_viscous_sets(tmp_path, study):
    """a study with only its delta_r 0 deposits of the default law: the same numbers there,
    the new sections empty"""
    write_results(str(tmp_path), polydisperse_and_viscous=False)
    c, stdout = run_tool(tmp_path)
    full = study[0]
    for key in ("deposits", "maxima", "symmetry", "crossings", "constant_eta"):
        assert c[key] == full[key], key
    assert c["polydispersity"] == {"density": [], "histograms": []} and c["laws"] == []
    assert "polydispersity" not in stdout and "tangential laws" not in stdout
