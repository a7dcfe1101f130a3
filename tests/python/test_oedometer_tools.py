"""tools/containers/oedometer_run.py's table and tools/containers/oedometer_study.py's section, without LAMMPS.

* The table: strain from the first step's piston height, the modulus of each step from the
  piston's stress, K0 of the slab, the phase split at the largest load, on made-up LEVEL
  values whose answers are worked out by hand.
* K0 is the mean horizontal stress over the vertical, (sigma_xx + sigma_yy) / (2 sigma_zz), as
  packing.dat's, not sigma_xx / sigma_zz.
* The study section (in doc/study.md between its markers) is what
  the report makes of the committed results/oedometer/oedometer.csv: a hand edit of a number or
  a csv changed without a new report fails.
* So are examples/oedometer/README.md's generated blocks (tools/containers/oedometer_container.py
  report): the container's cases beside the periodic ones, and the one periodic run's steps.
* The container's summary keeps a seed's cases of each wall friction apart.
"""
import argparse

import pytest

import oedometer_container
import oedometer_run
import oedometer_study


def level(k, load, piston, sigma, sxx, szz, syy=None):
    return {"level": k, "load": load, "target": load * 2.0, "at_rest": 1, "step": 1000 * k,
            "piston": piston, "sigma_piston": sigma, "sigma_xx": sxx,
            "sigma_yy": sxx if syy is None else syy,
            "sigma_zz": szz, "phi": 0.6, "sigma_w": 2.0, "gain": 1e-3, "gamma": 100.0}


def test_strain_modulus_and_k0_of_each_step():
    args = argparse.Namespace(N=10, eta=1.0, zeta=1.0, dr=0.0, seed=1)
    levels = [level(1, 1, 10.0, 2.0, 1.0, 4.0), level(2, 2, 9.9, 4.0, 2.0, 6.0),
              level(3, 1, 9.95, 2.0, 2.0, 4.0)]
    rows = oedometer_run.table(args, levels)
    assert [r["phase"] for r in rows] == ["load", "load", "unload"]
    assert rows[0]["eps_zz"] == 0.0 and rows[0]["M"] == ""
    assert rows[1]["eps_zz"] == pytest.approx(0.01)
    assert rows[1]["M"] == pytest.approx(2.0 / 0.01)       # 2 rho g d over 1 % strain
    assert rows[2]["eps_zz"] == pytest.approx(0.005)
    assert rows[2]["M"] == pytest.approx(-2.0 / -0.005)    # unloading: both fall
    assert [r["K0"] for r in rows] == pytest.approx([0.25, 1 / 3, 0.5])
    assert rows[0]["phi_mean"] == pytest.approx(2.0 / 10.0)    # h_s / z_p, rho = g = 1


def test_study_section_is_generated_from_the_csv():
    rows = oedometer_study.read_table()
    if not rows:
        pytest.fail("results/oedometer/oedometer.csv is missing")
    summary = oedometer_study.summarise(rows)
    with open(oedometer_study.STUDY_DOC) as f:
        committed = oedometer_study.doc_block(f.read())
    assert committed == oedometer_study.section(summary), \
        "doc/study.md's oedometer section differs from the csv: run tools/containers/oedometer_study.py report"


def test_k0_is_the_mean_horizontal_stress():
    args = argparse.Namespace(N=10, eta=1.0, zeta=1.0, dr=0.0, seed=1)
    rows = oedometer_run.table(args, [level(1, 1, 10.0, 2.0, 1.0, 4.0, syy=3.0)])
    assert rows[0]["K0"] == pytest.approx(0.5)    # (1 + 3) / 2 / 4, not 1 / 4


def test_readme_blocks_are_generated_from_the_csvs():
    with open(oedometer_container.README) as f:
        text = f.read()
    for name, block in oedometer_container.blocks().items():
        assert oedometer_container.generated(text, name) == block, \
            "examples/oedometer/README.md's %s block differs from the csvs: run " \
            "tools/containers/oedometer_container.py report" % name


def test_container_cases_of_each_wall_friction_stay_apart():
    rows = []
    for mu_w, k0 in ((0.0, 0.25), (0.5, 0.5)):
        levels = [level(1, 1, 10.0, 2.0, k0 * 4.0, 4.0), level(2, 2, 9.9, 4.0, 2.0, 6.0),
                  level(3, 1, 9.95, 2.0, 2.0, 4.0)]
        args = argparse.Namespace(N=10, eta=1.0, zeta=1.0, dr=0.0, seed=1)
        for r in oedometer_run.table(args, levels):
            rows.append({k: str(v) for k, v in dict(r, mu_w=mu_w, K0_wall=0.3,
                                                    side_share=mu_w).items()})
    cases = oedometer_container.summarise(rows, oedometer_container.side_name,
                                          oedometer_container.container_key)
    assert [c["geometry"] for c in cases] == ["side mu_w 0", "side mu_w 0.5"]
    assert [c["K0_first"] for c in cases] == pytest.approx([0.25, 0.5])
    assert [c["share_max"] for c in cases] == pytest.approx([0.0, 0.5])


def test_container_refuses_a_cylinder_narrower_than_two_lengths(tmp_path):
    # N = 100: R = 1.69 d, less than two lengths (2.8 d) of eta = zeta = 1.4
    with pytest.raises(SystemExit, match="less than two lengths of eta = zeta = 1.4"):
        oedometer_container.main(["run", "--N", "100", "--shapes", "1.4", "--runs", str(tmp_path)])
    assert not any(tmp_path.iterdir())    # refused before any run
