"""Checkpoints of the deposit runner survive kill -9 (tools/deposit/deposit_run.py).

A small deposit (100 spheres, one rank) writes a restart checkpoint every 1000 steps. It is
killed with SIGKILL (runner and LAMMPS) after its first complete checkpoint, while the pour is
still inserting; the other checkpoint file is replaced by a torn copy, as a kill in the middle
of a write leaves it. `deposit_run.py --resume DIR` must pick the intact checkpoint, read it
(not start a new pour), insert the particles still missing and finish the deposit with every
particle present, a sane volume fraction and `resumed_from STEP` in packing.dat, whose
wall_seconds counts the killed segment too (its loop times, summed here from its log).
"""
import json
import os
import subprocess
import sys

import pytest

import deposit_run
from checkpoint_helpers import kill_after_first_checkpoint
from conftest import root_dir

ROOT = root_dir()
RUNNER = os.path.join(ROOT, "tools", "deposit", "deposit_run.py")
N = 100
EVERY = 1000    # the pour's second batch comes between steps 1000 and 2000 (at dt 3e-4)
# an insertion region sized for volume fraction 0.6, more than random insertion reaches, so the
# pour takes several batches and the first checkpoint falls while it is still inserting
SETTINGS = ["--N", str(N), "--eta", "1", "--zeta", "1", "--dr", "0", "--ketol", "1e-2",
            "--no-image", "--var", "fins", "0.6", "--var", "dt", "3e-4", "--var", "slabmin",
            "0", "--checkpoint-every", str(EVERY)]
QUIET = ["--np", "1", "--no-plots", "--quiet"]


def runner_env():
    env = dict(os.environ)
    if "LAMMPS_BUILD" not in env and env.get("ELLIPSOID_DEP_LMP"):
        env["LAMMPS_BUILD"] = os.path.dirname(env["ELLIPSOID_DEP_LMP"])
    return env


def first_thermo_row(log):
    """{column: value} of the first thermo row of a LAMMPS log"""
    lines = log.splitlines()
    k = next(i for i, line in enumerate(lines) if line.split()[:1] == ["Step"])
    return dict(zip(lines[k].split(), (float(x) for x in lines[k + 1].split())))


@pytest.fixture(scope="module")
def killed(tmp_path_factory):
    """a run folder whose deposit was killed -9 after its first checkpoint"""
    out = str(tmp_path_factory.mktemp("ckpt") / "run")
    kill_after_first_checkpoint([sys.executable, RUNNER, "--out", out] + SETTINGS + QUIET, out,
                                runner_env())
    return out


def test_killed_run_left_a_checkpoint_and_no_result(killed):
    path, step = deposit_run.newest_checkpoint(killed)
    assert step is not None and step > 0 and step % EVERY == 0, step
    assert not os.path.exists(os.path.join(killed, "packing.dat"))
    stored = json.load(open(os.path.join(killed, "settings.json")))
    assert stored["N"] == N and stored["checkpoint_every"] == EVERY


def test_torn_checkpoint_is_not_chosen(killed, tmp_path):
    path, step = deposit_run.newest_checkpoint(killed)
    data = open(path, "rb").read()
    torn = str(tmp_path / "torn")
    with open(torn, "wb") as f:
        f.write(data[: len(data) // 2])
    assert deposit_run.checkpoint_step(path) == step
    assert deposit_run.checkpoint_step(torn) is None
    with open(torn, "wb") as f:
        f.write(b"not a restart file")
    assert deposit_run.checkpoint_step(torn) is None


def test_continue_resumes_only_the_same_settings(killed):
    path, step = deposit_run.newest_checkpoint(killed)
    same = deposit_run.parse_args(["--out", killed, "--continue"] + SETTINGS)
    assert deposit_run.plan(same)[2:] == (path, step)
    other = deposit_run.parse_args(["--out", killed, "--continue"] + SETTINGS[:-2]
                                   + ["--checkpoint-every", "3000"])
    assert deposit_run.plan(other)[2:] == (None, None)


def test_resume_refuses_other_settings(killed):
    r = subprocess.run([sys.executable, RUNNER, "--resume", killed, "--N", "200"] + QUIET,
                       env=runner_env(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=60)
    assert r.returncode != 0 and "settings" in r.stdout and "'N': 200" in r.stdout, r.stdout


@pytest.fixture(scope="module")
def resumed(killed):
    path, step = deposit_run.newest_checkpoint(killed)
    # the other file as a kill in the middle of writing the next checkpoint leaves it
    other = [os.path.join(killed, n) for n in deposit_run.CHECKPOINTS
             if os.path.join(killed, n) != path][0]
    with open(path, "rb") as f, open(other, "wb") as g:
        g.write(f.read()[:5000])
    r = subprocess.run([sys.executable, RUNNER, "--resume", killed] + QUIET, env=runner_env(),
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    assert r.returncode == 0, r.stdout[-3000:]
    return {"step": step, "path": path, "stdout": r.stdout,
            "log": open(os.path.join(killed, "log.resume-%d.lammps" % step)).read(),
            "killed_log": open(os.path.join(killed, "log.lammps")).read(),
            "packing": deposit_run.read_packing(os.path.join(killed, "packing.dat")),
            "dump": open(os.path.join(killed, "deposit.dump")).read().splitlines(),
            "files": os.listdir(killed)}


def test_resume_reads_the_intact_checkpoint(resumed):
    assert "resuming" in resumed["stdout"] and "from step %d" % resumed["step"] in resumed["stdout"]
    log = resumed["log"]
    assert "read_restart %s" % resumed["path"] in log
    assert "Reading restart file" in log and "Created orthogonal box" not in log
    assert "Resetting global fix info from restart file" in log
    # the kill came while the pour was still inserting: its schedule continued after resume
    row = first_thermo_row(log)
    assert row["Step"] == resumed["step"] and 0 < row["f_pour"] < N, row


def test_resumed_deposit_is_complete(resumed):
    pk = resumed["packing"]
    assert int(pk["resumed_from"]) == resumed["step"]
    assert int(pk["N"]) == N and int(pk["steps"]) > resumed["step"]
    assert 0.5 < pk["phi"] < 0.7 and pk["Nslab"] > 20 and pk["Z"] > 3.0, pk
    dump = resumed["dump"]
    assert int(dump[3]) == N
    ids = sorted(int(line.split()[0]) for line in dump[9:9 + N])
    assert ids == list(range(1, N + 1))
    # finished: the checkpoints are gone, nothing left to resume
    assert not any(n in resumed["files"] for n in deposit_run.CHECKPOINTS)


def test_resumed_cost_counts_the_killed_segment(resumed):
    """wall_seconds = this segment's wall time + the killed segment's run commands' loop times"""
    loops = [float(line.split()[3]) for line in resumed["killed_log"].splitlines()
             if line.startswith("Loop time of ")]
    pk = resumed["packing"]
    assert loops and pk["earlier_segments_seconds"] == pytest.approx(sum(loops), abs=0.01)
    assert pk["wall_seconds"] > pk["earlier_segments_seconds"] > 0


def test_segment_logs_are_named_apart_and_cleared_by_a_fresh_start(tmp_path):
    """a second resume from the same checkpoint keeps the first one's log (log.resume-STEP-2);
    no earlier log gives None (not counted), not 0; a fresh start removes an earlier run's logs"""
    out = str(tmp_path)
    assert deposit_run.resume_log(out, 1000) == "log.resume-1000.lammps"
    assert deposit_run.earlier_segments_seconds(out, "log.resume-1000.lammps") is None
    loop = "Loop time of 2.5 on 1 procs for 1000 steps with 100 atoms\n"
    for name in ("log.lammps", "log.resume-1000.lammps"):
        (tmp_path / name).write_text(loop)
    second = deposit_run.resume_log(out, 1000)
    assert second == "log.resume-1000-2.lammps"
    (tmp_path / second).write_text(loop)
    assert deposit_run.earlier_segments_seconds(out, second) == pytest.approx(5.0)
    deposit_run.start_fresh(out)
    assert os.listdir(out) == []
