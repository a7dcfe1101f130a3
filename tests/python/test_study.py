"""The deposition study end to end at a tiny size: the tiny study (workflow/config/tiny.yaml:
2 shapes) through Snakemake with its table, figures and picture; the table's statistics over
seeds; retries that keep the logs of failed attempts; the Slurm profile in a dry run. Checks
that the files exist, the numbers are sane and the PNGs are non-empty images."""
import csv
import json
import math
import os
import shutil
import subprocess

import yaml

import deposit_run
from checkpoint_helpers import kill_after_first_checkpoint
from study_helpers import PY, ROOT, SNAKEFILE, TINY, TOOLS, assert_image, lmp_env, run


def snakemake(tmp_path, *args, config=TINY):
    """the study's Snakefile on the given config, results and scratch under tmp_path"""
    return ["snakemake", "--snakefile", SNAKEFILE, "--configfile", str(config), "--cores", "2",
            "--directory", str(tmp_path / "work")] + list(args) + [
            "--config", "results=%s" % (tmp_path / "results"),
            "scratch=%s" % (tmp_path / "scratch")]


def job_counts(text):
    """{rule: jobs} from the job stats of a snakemake dry run"""
    table = text.split("Job stats:")[1].split("\n\n")[0].splitlines()[3:]
    return {w[0]: int(w[1]) for w in (line.split() for line in table) if w[0] != "total"}


def test_tiny_study_through_snakemake(tmp_path):
    run(snakemake(tmp_path, "-q"), str(tmp_path), 600)
    res = tmp_path / "results"
    table = list(csv.DictReader(open(res / "table.csv")))
    assert sorted((float(r["eta"]), float(r["zeta"])) for r in table) == [(1.0, 1.0), (1.5, 1.0)]
    for r in table:
        assert int(r["N"]) == 100 and r["law"] == "coulomb" and int(r["seeds"]) == 1
        assert 0.5 < float(r["phi_mean"]) < 0.75 and float(r["Z_mean"]) > 3.0, r
        assert math.isnan(float(r["phi_sem"]))    # one seed: no standard error
        for h in ("contact_histo", "orient_histo"):
            th, p, e = zip(*[map(float, line.split()) for line in open(res / r[h])
                             if not line.startswith("#")])
            assert len(th) == 18 and all(x >= 0 for x in p)
    deposits = list(csv.DictReader(open(res / "deposits.csv")))
    assert len(deposits) == 2 and {d["seed"] for d in deposits} == {"1"}
    for d in deposits:    # the force measures and their histograms reach the results
        assert math.isfinite(float(d["K0"])) and math.isfinite(float(d["a_f"]))
        for name in ("contact_force_histo.dat", "force_histo.dat"):
            assert (res / "points" / d["point"] / "s1" / name).stat().st_size > 0
    for name in ("fig_density_lines.png", "fig_contact_shapes.png", "fig_orient_shapes.png"):
        assert_image(str(res / "figures" / name))
    assert not (res / "figures" / "fig_density_laws.png").exists()    # one tangential law
    assert_image(str(res / "picture.png"))
    # the porous-media view of both deposits (sphere and prolate: on the lines) and its figure
    assert_image(str(res / "pores.png"))
    pores_rows = list(csv.DictReader(open(res / "pores.csv")))
    assert sorted((float(r["eta"]), float(r["zeta"])) for r in pores_rows) == [(1.0, 1.0),
                                                                               (1.5, 1.0)]
    for r in pores_rows:
        d = res / "points" / ("eta%g_zeta%g_dr0_N100_coulomb" % (float(r["eta"]),
                                                                float(r["zeta"]))) / "s1"
        saved = json.load(open(d / "pores.json"))
        packing = deposit_run.read_packing(str(d / "packing.dat"))
        assert abs(saved["porosity"] - (1 - packing["phi"])) < 1e-4    # the same slab
        assert float(r["porosity"]) == saved["porosity"] and int(r["runs"]) == 1
    # results hold small files only: dumps, logs and checkpoints stay in the scratch folder
    kept = {f for _, _, files in os.walk(res) for f in files}
    assert not any(f.endswith((".dump", ".lammps", ".log")) or f.startswith("checkpoint")
                   for f in kept), kept
    assert list((tmp_path / "scratch" / "points").glob("*/deposit.dump"))
    # finished deposits are outputs: nothing to redo; more seeds run only the new deposits
    assert "Nothing to be done" in run(snakemake(tmp_path, "-n"), str(tmp_path), 120)
    config = yaml.safe_load(open(TINY))
    config["sets"]["spheroids"]["seeds"] = [1, 2]
    (tmp_path / "more.yaml").write_text(yaml.safe_dump(config))
    text = run(snakemake(tmp_path, "-n", config=tmp_path / "more.yaml"), str(tmp_path), 120)
    assert job_counts(text) == {"deposit": 2, "table": 1, "claims": 1, "figures": 1,
                                "pores": 2, "pores_figure": 1, "all": 1}, text
    assert "seed=2" in text and "seed=1" not in text
    # a removed deposit is redone alone when the table is asked for again
    shutil.rmtree(res / "points" / "eta1.5_zeta1_dr0_N100_coulomb" / "s1")
    text = run(snakemake(tmp_path, "-n", "--forcerun", "table"), str(tmp_path), 120)
    assert job_counts(text) == {"deposit": 1, "table": 1, "claims": 1, "figures": 1,
                                "pores": 1, "pores_figure": 1, "all": 1}, text
    # ... and without --forcerun, as ./ellipsoid-dep study runs it (file age only): every
    # deposit is an input of `all`, so a missing one is made and the table follows
    text = run(snakemake(tmp_path, "-n", "--rerun-triggers", "mtime"), str(tmp_path), 120)
    counts = job_counts(text)
    assert counts["deposit"] == 1 and counts["table"] == 1, text


def test_interrupted_study_resumes_its_deposit(tmp_path):
    """snakemake killed -9 in the middle of a deposit: started again, the deposit continues
    from its checkpoint instead of pouring anew"""
    config = yaml.safe_load(open(TINY))
    config["checkpoint_every"] = 2000
    cfg = tmp_path / "ckpt.yaml"
    cfg.write_text(yaml.safe_dump(config))
    target = str(tmp_path / "results" / "points" / "eta1_zeta1_dr0_N100_coulomb" / "s1" /
                 "packing.dat")
    folder = str(tmp_path / "scratch" / "points" / "eta1_zeta1_dr0_N100_coulomb_s1")
    step = kill_after_first_checkpoint(snakemake(tmp_path, target, config=cfg), folder,
                                       lmp_env(), cwd=str(tmp_path))
    run(snakemake(tmp_path, "--unlock", config=cfg), str(tmp_path), 60)    # the killed lock
    run(snakemake(tmp_path, target, config=cfg), str(tmp_path), 600)
    pk = deposit_run.read_packing(target)
    assert int(pk["resumed_from"]) >= step and int(pk["N"]) == 100
    assert os.path.exists(os.path.join(folder, "log.resume-%d.lammps" % pk["resumed_from"]))


def test_failed_deposit_is_retried_and_its_logs_kept(tmp_path):
    config = yaml.safe_load(open(TINY))
    config["laws"]["coulomb"] = "no_such_law 1.0"
    config["retries"] = 1
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump(config))
    target = str(tmp_path / "results" / "points" / "eta1_zeta1_dr0_N100_coulomb" / "s1" /
                 "packing.dat")
    text = run(snakemake(tmp_path, target, config=bad), str(tmp_path), 300, ok=False)
    assert "Trying to restart job" in text
    logs = tmp_path / "scratch" / "logs"
    for attempt in (1, 2):
        log = (logs / ("eta1_zeta1_dr0_N100_coulomb_s1.log.failed-attempt-%d" % attempt))
        assert "ERROR" in log.read_text(), attempt


def test_deposit_not_at_rest_fails_its_job(tmp_path):
    """a deposit that runs out of chunks is not a result: its job fails, nothing reaches the
    results folder, and the log says why"""
    config = yaml.safe_load(open(TINY))
    config["vars"] = {"maxchunks": 1, "chunk": 100, "slabmin": 0}
    config["retries"] = 0
    short = tmp_path / "short.yaml"
    short.write_text(yaml.safe_dump(config))
    point = "eta1_zeta1_dr0_N100_coulomb"
    target = tmp_path / "results" / "points" / point / "s1" / "packing.dat"
    run(snakemake(tmp_path, str(target), config=short), str(tmp_path), 300, ok=False)
    assert not target.exists()
    log = tmp_path / "scratch" / "logs" / (point + "_s1.log.failed-attempt-1")
    assert "NOT at rest" in log.read_text()
    packing = tmp_path / "scratch" / "points" / (point + "_s1") / "packing.dat"
    assert "at_rest 0" in packing.read_text()


def test_delta_r_vars_reach_their_delta_r_only(tmp_path):
    """config delta_r_vars: the deposits at one delta_r (a number or a string key) get its
    variables over vars, a set's own vars its points; a delta_r that is not in the study, one
    given twice, a point given different vars by two sets and the old point_vars are
    refused"""
    config = yaml.safe_load(open(TINY))
    config["sets"]["spheroids"]["delta_r"] = [0, 0.3]
    config["vars"] = {"dtfrac": 0.05, "flytol": 1.0}
    config["delta_r_vars"] = {"0.3": {"dtfrac": 0.03}, 0: {"flytol": 2.0}}
    path = tmp_path / "vars.yaml"

    def dry_run(ok=True):
        path.write_text(yaml.safe_dump(config, sort_keys=False))    # keys of mixed types
        return run(snakemake(tmp_path, "-n", "-p", config=path), str(tmp_path), 300, ok=ok)

    commands = [line for line in dry_run().splitlines() if "deposit_run.py" in line]
    assert len(commands) == 5    # 2 shapes x 2 delta_r, and the picture at delta_r 0
    for line in commands:
        at_03 = " --dr 0.3 " in line
        assert ("--var dtfrac 0.03" in line) == at_03 and ("--var dtfrac 0.05" in line) != at_03
        assert ("--var flytol 1.0" in line) == at_03 and ("--var flytol 2.0" in line) != at_03
    for bad, message in (({0.6: {"dtfrac": 0.03}},
                          "delta_r_vars: delta_r 0.6 is not one of the study's ['0', '0.3']"),
                         ({0.3: {"dtfrac": 0.03}, "0.3": {"dtfrac": 0.04}},
                          "delta_r_vars: delta_r 0.3 is given twice")):
        config["delta_r_vars"] = bad
        assert message in dry_run(ok=False)
    # a set's own vars, over both, reach its points only; two sets that give one point
    # different vars are refused
    config["delta_r_vars"] = {"0.3": {"dtfrac": 0.03}}
    config["sets"]["tall"] = {"shapes": [[1.2, 1.2]], "delta_r": [0.3], "seeds": [1],
                              "width": 4.5, "vars": {"dtfrac": 0.02}}
    commands = [line for line in dry_run().splitlines() if "deposit_run.py" in line]
    tall = [line for line in commands if "_W4.5_" in line]
    assert len(tall) == 1 and "--var dtfrac 0.02" in tall[0] and "dtfrac 0.03" not in tall[0]
    assert all("--var dtfrac 0.02" not in line for line in commands if line not in tall)
    config["sets"]["taller"] = dict(config["sets"]["tall"], vars={"dtfrac": 0.01})
    assert "sets tall and taller give the point eta1.2_zeta1.2_dr0.3_N100_W4.5_coulomb " \
        "different vars" in dry_run(ok=False)
    del config["sets"]["tall"], config["sets"]["taller"], config["delta_r_vars"]
    config["point_vars"] = {"eta1_zeta1_dr0_N100_coulomb": {"dtfrac": 0.03}}
    assert "point_vars was replaced by delta_r_vars" in dry_run(ok=False)


def test_table_mean_and_standard_error_over_seeds(tmp_path):
    """study_table.py against numbers computed here: three seeds of one point"""
    res = tmp_path / "results"
    phis, zs = [0.60, 0.62, 0.65], [5.0, 5.5, 6.5]
    packings = []
    for seed, (phi, z) in enumerate(zip(phis, zs), 1):
        d = res / "points" / "eta1.2_zeta1.4_dr0.3_N500_viscous" / ("s%d" % seed)
        d.mkdir(parents=True)
        (d / "packing.dat").write_text(
            "N 500\neta 1.2\nzeta 1.4\ndelta_r 0.3\nseed %d\nsteps 1000\nphi %g\nZ %g\n"
            "Z_no_rattlers %g\nNslab 200\nrattlers %d\nfabric_anisotropy 0.1\nnematic_S 0.2\n"
            "Qzz -0.1\nwall_seconds 10\n" % (seed, phi, z, z, seed)
            + ("K0 %g\n" % (0.5 + 0.1 * seed) if seed > 1 else "")    # one without forces
            # the third with window means (and their errors) on 2 ranks
            + ("np 2\nwindow_steps 2400\nsigma_xx 2.1\nsigma_yy 2.2\nsigma_zz 3.5\n"
               "sigma_zz_se 0.01\nK0_se 0.002\n" if seed == 3 else ""))
        for h in ("contact_histo", "orient_histo"):
            (d / (h + ".dat")).write_text("# t\n1000 2\n1 0.5 %g 0.5\n2 1.5 %g 0.5\n"
                                          % (seed, 2 * seed))
        packings.append(str(d / "packing.dat"))
    run([PY, os.path.join(TOOLS, "study", "study_table.py"), "--results", str(res)] + packings,
        str(tmp_path), 60)
    (row,) = list(csv.DictReader(open(res / "table.csv")))
    assert row["law"] == "viscous" and int(row["seeds"]) == 3
    sem = lambda v: math.sqrt(sum((x - sum(v) / 3) ** 2 for x in v) / 2 / 3)  # noqa: E731
    assert abs(float(row["phi_mean"]) - 0.62333333) < 1e-6
    assert abs(float(row["phi_sem"]) - sem(phis)) < 1e-9
    assert abs(float(row["Z_sem"]) - sem(zs)) < 1e-9
    assert abs(float(row["rattler_fraction_mean"]) - 2 / 200) < 1e-12
    assert math.isnan(float(row["K0_mean"]))    # a deposit without the force measures
    deposits = list(csv.DictReader(open(res / "deposits.csv")))
    assert [float(d["K0"]) for d in deposits[1:]] == [0.5 + 0.1 * 2, 0.5 + 0.1 * 3]
    # the window's length (0: a snapshot), the stresses with their window errors, the ranks
    assert [int(d["window_steps"]) for d in deposits] == [0, 0, 2400]
    assert [float(d["sigma_zz"]) for d in deposits[2:]] == [3.5]
    assert float(deposits[2]["sigma_zz_se"]) == 0.01 and float(deposits[2]["K0_se"]) == 0.002
    assert math.isnan(float(deposits[1]["sigma_zz"])) and float(deposits[2]["np"]) == 2
    assert "sigma_zz_mean" in row and "K0_se_mean" not in row
    hist = [list(map(float, line.split())) for line in open(res / row["contact_histo"])
            if not line.startswith("#")]
    assert hist[0][:2] == [0.5, 2.0] and abs(hist[0][2] - sem([1, 2, 3])) < 1e-6
    assert hist[1][:2] == [1.5, 4.0] and abs(hist[1][2] - sem([2, 4, 6])) < 1e-6

    # a deposit that ran out of chunks before rest is not a result: the table refuses it
    moving = res / "points" / "eta1.2_zeta1.4_dr0.3_N500_viscous" / "s1" / "packing.dat"
    moving.write_text(moving.read_text() + "at_rest 0\n")
    failed = subprocess.run([PY, os.path.join(TOOLS, "study", "study_table.py"), "--results", str(res)]
                            + packings, capture_output=True, text=True, timeout=60)
    assert failed.returncode != 0
    assert "not at rest" in failed.stderr and str(moving.parent) in failed.stderr


def test_figures_compare_tangential_laws(tmp_path):
    """a study with two laws on the diagonal (the table, and two seeds per point in
    deposits.csv with their histograms): plot_figures.py draws them against each other"""
    columns = ["point", "eta", "zeta", "delta_r", "N", "law", "seeds"] + [
        q + s for q in ("phi", "Z", "Z_no_rattlers") for s in ("_mean", "_sem")] + [
        "contact_histo", "orient_histo"]
    histo = "# histogram\n1000 16\n" + "".join("%d %g 0.08 0.001\n" % (k + 1, 0.1 + 0.2 * k)
                                                for k in range(16))
    rows, deposits = [], []
    for law in ("coulomb", "viscous"):
        for v in (1.0, 1.4, 2.0):
            for dr in (0.0, 0.3):
                point = "eta%g_zeta%g_dr%g_N3000_%s" % (v, v, dr, law)
                rows.append([point, v, v, dr, 3000, law, 2, 0.6 + 0.01 * v, 0.001, 6.0, 0.05,
                             6.0, 0.05, "histo.dat", "histo.dat"])
                for seed, noise in ((1, 0.001), (2, -0.001)):
                    folder = tmp_path / "points" / point / ("s%d" % seed)
                    folder.mkdir(parents=True)
                    for name in ("contact_histo.dat", "orient_histo.dat"):
                        (folder / name).write_text(histo)
                    deposits.append([point, v, v, dr, 3000, law, seed, 0.6 + 0.01 * v + noise,
                                     6.0 + noise, 6.0 + noise])
    for name, cols, data in (("table.csv", columns, rows), ("deposits.csv", [
            "point", "eta", "zeta", "delta_r", "N", "law", "seed", "phi", "Z", "Z_no_rattlers"],
            deposits)):
        with open(tmp_path / name, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(cols)
            w.writerows(data)
    out = run([PY, os.path.join(TOOLS, "plot", "plot_figures.py"), str(tmp_path / "table.csv")],
              str(tmp_path), 120)
    assert_image(str(tmp_path / "fig_density_laws.png"))
    assert "fig_density_laws.png" in out


def test_paper_study_definition(tmp_path):
    """the paper's study (workflow/config/paper.yaml) covers what the study must hold"""
    text = run(["snakemake", "--snakefile", SNAKEFILE, "--configfile",
                os.path.join(ROOT, "workflow", "config", "paper.yaml"), "--cores", "2", "-n", "-p",
                "--directory", str(tmp_path), "--config", "scratch=%s" % tmp_path,
                "results=%s" % (tmp_path / "results")],    # every deposit, whatever is committed
               str(tmp_path), 300)
    runs = {line.split("wildcards:")[1].strip() for line in text.splitlines()
            if "wildcards:" in line}
    points, boxes = {}, {}    # at N 3000 in its default box; at another N or box
    for w in runs:
        d = dict(kv.strip().split("=") for kv in w.split(","))
        key = (float(d["eta"]), float(d["zeta"]), float(d["dr"]), d["law"])
        assert int(d["N"]) >= 3000
        if int(d["N"]) == 3000 and not d["box"]:
            points.setdefault(key, set()).add(int(d["seed"]))
        else:
            boxes.setdefault(key + (int(d["N"]), d["box"]), set()).add(int(d["seed"]))
    # one time step for every deposit (the config's vars reach the runner) but those at
    # delta_r 0.6, whose damping needs a shorter one (delta_r_vars): 46 deposits at N 3000 and
    # the picture; the 15 at matched depth, whose taller box hits harder, a shorter one still
    # (their set's vars)
    commands = [line for line in text.splitlines() if "deposit_run.py" in line]
    damped = [line for line in commands if " --dr 0.6 " in line]
    matched = [line for line in damped if "_W16.4317_" in line]
    assert len(damped) == 62 and len(matched) == 15
    assert all("--var dt 0.00039" in line for line in matched), matched
    assert all("--var dt 0.00042" in line for line in damped if line not in matched)
    # a set's own box reaches in.deposit as its width, and only there
    assert all(("--var width 16.4317" in line) == ("_W16.4317_" in line) for line in commands)
    # the viscous law's dashpot shortens the step: its set takes in.deposit's rule (dt 0)
    viscous = [line for line in commands if "'viscous 0.5'" in line or '"viscous 0.5"' in line]
    assert len(viscous) == 22 and all("--var dt 0 " in line + " " for line in viscous), viscous
    assert all("--var dt 0.0006" in line for line in commands
               if line not in damped and line not in viscous)
    assert len(commands) > 250
    grid = [1, 1.2, 1.4, 1.6, 1.8, 2, 2.5, 3]
    for e in grid:
        for z in grid:
            assert len(points[(e, z, 0.0, "coulomb")]) >= 2
    for v in grid + [1.3, 1.5, 1.7]:
        assert len(points[(v, v, 0.0, "coulomb")]) >= (6 if v not in (1.7, 1.8) else 3)
        assert len(points[(v, v, 0.0, "viscous")]) >= 1
    for dr in (0.3, 0.6):
        for v in grid:
            for shape in ((v, v), (v, 1.0), (1.0, v)):
                assert len(points[shape + (dr, "coulomb")]) >= 2
        assert len(points[(1.6, 1.8, dr, "coulomb")]) >= 2
    for v in (3.5, 4):    # the fall-back
        assert len(points[(v, v, 0.0, "coulomb")]) >= 4
    for dr, n in ((0.3, 3250), (0.6, 4327)):    # delta_r at matched depth: N / mean volume
        for shape in ((1.0, 1.0), (1.4, 1.4), (2.0, 2.0), (3.0, 3.0), (1.6, 1.8)):
            assert len(boxes[shape + (dr, "coulomb", n, "_W16.4317")]) >= 3
    for n, box in ((12000, ""), (12000, "_W16.4317")):    # finite size: wider, deeper
        assert len(boxes[(1.4, 1.8, 0.0, "coulomb", n, box)]) >= 3
    assert len(points[(1.4, 1.8, 0.0, "coulomb")]) >= 3
    for k in range(14, 23):    # the ridge: the spheroid lines at 0.1 steps across their maxima
        for shape in ((k / 10, 1.0), (1.0, k / 10)):
            assert len(points[shape + (0.0, "coulomb")]) >= 5
    # the stresses at equilibrium (window means): the diagonal at seeds 4-6, the spheroid
    # lines at seeds 1-3
    for v in (1, 1.4, 2, 3):
        assert {4, 5, 6} <= points[(v, v, 0.0, "coulomb")]
    for v in (1.4, 2, 3):
        for shape in ((v, 1.0), (1.0, v)):
            assert {1, 2, 3} <= points[shape + (0.0, "coulomb")]


def test_slurm_profile_dry_run(tmp_path):
    """every deposit a Slurm job with its ranks, memory and time"""
    text = run(snakemake(tmp_path, "-n", "--profile",
                         os.path.join(ROOT, "workflow", "profiles", "slurm")), str(tmp_path), 120)
    blocks = [b for b in text.split("\n\n") if "rule deposit:" in b or "rule picture:" in b]
    assert len(blocks) == 3, text
    for b in blocks:
        assert "localrule" not in b
        res = dict(kv.strip().split("=") for kv in
                   b.split("resources:")[1].splitlines()[0].split(","))
        assert res["tasks"] == "1" and res["mpi"] == "mpirun" and res["cpus_per_task"] == "1"
        assert res["mem_mb"] == "500" and res["runtime"] == "10"
    assert "localrule table:" in text and "localrule figures:" in text
