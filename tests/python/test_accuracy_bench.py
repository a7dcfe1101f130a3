"""The whole-deposit speed-accuracy benchmark (bench/accuracy): the table's statistics on small
made-up rows whose answers are known by hand, and in.deposit's pairkw variable reaching the
pair style.
"""
import csv
import math
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import root_dir, subprocess_env

sys.path.insert(0, os.path.join(root_dir(), "bench", "accuracy"))
import accuracy_table    # noqa: E402

BINS = accuracy_table.BINS


def test_pooled_sd_by_hand():
    # sums of squares 2 and 2 over 3 degrees of freedom
    assert accuracy_table.pooled_sd([1, 2, 3], [2, 4]) == pytest.approx(math.sqrt(4 / 3))
    assert math.isnan(accuracy_table.pooled_sd([1], [2]))


def test_leave_one_out_l1_by_hand():
    F = np.array([[1.0, 0.0], [0.0, 1.0], [0.5, 0.5]])
    # the first: the others' mean is (0.25, 0.75); the last is the others' mean
    assert accuracy_table.leave_one_out_l1(F) == pytest.approx([1.5, 1.5, 0.0])


def histogram(tilt, rng):
    """a normalised made-up histogram: more weight near theta 0 with tilt, a little noise"""
    base = 1.0 + tilt * np.cos(np.linspace(0, np.pi, BINS)) + 0.02 * rng.standard_normal(BINS)
    return base / base.sum()


def rows_of(setting, cpu, steps, phis, Zs, tilt, rng, not_converged=0):
    out = []
    for k, (phi, Z) in enumerate(zip(phis, Zs)):
        row = {"setting": setting, "keywords": setting, "seed": 100 + k, "N": 1000, "np": 1,
               "cpu_seconds": cpu[k], "wall_seconds": 2 * cpu[k], "steps": steps[k],
               "at_rest": 1, "phi": phi, "Z": Z, "Nslab": 700, "fabric_anisotropy": 0.1,
               "warnings": 0, "contacts": 1000, "iterations": 1500, "corrections": 1000,
               "not_converged": not_converged, "spurious_minima": 0, "commit": "abc1234",
               "started_utc": "2026-12-02 12:%02d" % k, "load_start": 2.0, "load_end": 3.0}
        row.update({"F%d" % b: f for b, f in enumerate(histogram(tilt, rng))})
        out.append({key: str(v) for key, v in row.items()})    # as read back from rows.csv
    return out


@pytest.fixture
def made_up_rows():
    rng = np.random.default_rng(7)
    phis, Zs = [0.650, 0.652, 0.654], [6.60, 6.62, 6.64]
    return (rows_of("default", [100, 110, 120], [30000, 32000, 31000], phis, Zs, 0.5, rng)
            # the same deposits, cheaper per step: within the spread
            + rows_of("cheap", [60, 55, 70], [30000, 31000, 33000], phis[::-1], Zs[::-1], 0.5,
                      rng)
            # the same histogram and Z, phi 10 SD higher
            + rows_of("denser", [50, 50, 50], [30000, 30000, 30000], [p + 0.02 for p in phis],
                      Zs, 0.5, rng)
            # phi and Z kept, the contact normals much more vertical
            + rows_of("tilted", [40, 40, 40], [30000, 30000, 30000], phis, Zs, 0.9, rng, 5))


def test_comparisons_of_made_up_settings(made_up_rows):
    g = {name: accuracy_table.stats(rs) for name, rs in accuracy_table.groups(made_up_rows).items()}
    assert list(g) == ["default", "cheap", "denser", "tilted"]
    d = g["default"]
    assert d["cpu"] == 110 and d["steps"] == 31000
    # medians of the per-run CPU time per particle-step: 100/30e6, 110/32e6, 120/31e6 in us
    assert d["us_per_particle_step"] == pytest.approx(110 / 32e6 * 1e6)
    assert d["iterations_per_contact"] == pytest.approx(1.5)
    cheap = accuracy_table.compare(g["cheap"], d)
    assert cheap["cpu_ratio"] == pytest.approx(60 / 110)
    # per step against the default's run of the same seed: 0.6, 0.516, 0.548
    assert cheap["step_cost_ratio"] == pytest.approx((70 / 33000) / (120 / 31000))
    assert cheap["d_phi"] == pytest.approx(0.0, abs=1e-9) and cheap["agree"]
    denser = accuracy_table.compare(g["denser"], d)
    assert denser["d_phi"] == pytest.approx(0.02 / 0.002)    # pooled SD 0.002
    assert not denser["agree_phi"] and denser["agree_Z"] and denser["agree_hist"]
    tilted = accuracy_table.compare(g["tilted"], d)
    assert tilted["agree_phi"] and tilted["agree_Z"] and not tilted["agree_hist"]
    assert tilted["hist_l1_ratio"] > 3
    own = accuracy_table.compare(d, d)
    assert own["hist_l1_ratio"] == pytest.approx(1.0) and own["agree"]
    assert own["limit_pooled_sd"] == pytest.approx(2 * math.sqrt(2 / 3))


def test_table_files(made_up_rows, tmp_path):
    accuracy_table.write(made_up_rows, str(tmp_path))
    table = (tmp_path / "table.md").read_text()
    assert "commit abc1234" in table
    assert "| denser | denser | 3 |" in table and "no (phi)" in table
    # the cheapest agreeing setting is cheap: denser and tilted are cheaper but disagree
    assert "Cheapest setting within the seed spread" in table and ": cheap (cheap), 0.55x" in table
    with open(tmp_path / "summary.csv") as f:
        summary = {r["setting"]: r for r in csv.DictReader(f)}
    assert int(summary["tilted"]["not_converged"]) == 15
    assert (tmp_path / "histograms.png").stat().st_size > 0


def test_pairkw_reaches_the_pair_style(tmp_path):
    """in.deposit passes pairkw to pair_style: a bad keyword is refused by the pair"""
    out = subprocess.run([os.environ["ELLIPSOID_DEP_LMP"], "-in", os.path.join(root_dir(), "examples", "deposit",
                                                    "in.deposit"),
                          "-log", "none", "-nocite", "-var", "N", "10", "-var", "image", "0",
                          "-var", "out", str(tmp_path), "-var", "pairkw", "iterations 0"],
                         capture_output=True, text=True, cwd=str(tmp_path), env=subprocess_env())
    assert out.returncode != 0
    assert "pair_style granular/ellipsoid iterations must be >= 1" in out.stdout + out.stderr
