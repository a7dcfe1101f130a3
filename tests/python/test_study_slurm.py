"""The study's Slurm profile for real, on a single-node Slurm cluster started for this test.

munged, slurmctld and slurmd (Debian's slurm-wlm: `apt-get install --no-install-recommends
slurmctld slurmd slurm-client munge`) run as root from a private folder (own munge socket,
ports, state and spool), so nothing of the host's set-up is used or changed. One deposit of the
tiny study on 2 ranks goes through `--profile workflow/profiles/slurm`: it must come back as
a finished Slurm job that asked for 2 tasks, the memory and the time of the config, and its
LAMMPS must have run on the 2 ranks. Skipped where Slurm is not installed or not root.
"""
import os
import re
import shutil
import socket
import subprocess
import time

import pytest
import yaml

from conftest import root_dir

ROOT = root_dir()
DAEMONS = ("munged", "slurmctld", "slurmd", "sbatch", "scontrol", "sinfo")
pytestmark = pytest.mark.skipif(
    os.geteuid() != 0 or not all(shutil.which(d) for d in DAEMONS),
    reason="needs root and Debian's slurmctld, slurmd, slurm-client and munge")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for(check, seconds, what):
    deadline = time.time() + seconds
    while not check():
        assert time.time() < deadline, "no %s within %d s" % (what, seconds)
        time.sleep(0.2)


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    d = tmp_path_factory.mktemp("slurm")
    for sub in ("state", "spool", "munge"):
        (d / sub).mkdir()
    os.chmod(d / "munge", 0o700)
    node = socket.gethostname().split(".")[0]
    sock = d / "munge" / "munge.socket"
    key = d / "munge" / "munge.key"
    key.write_bytes(os.urandom(1024))
    os.chmod(key, 0o400)
    conf = d / "slurm.conf"
    conf.write_text("\n".join([
        "ClusterName=ellipsoiddeptest", "SlurmctldHost=%s" % node, "SlurmUser=root",
        "SlurmdUser=root", "AuthType=auth/munge", "AuthInfo=socket=%s" % sock,
        "CredType=cred/munge", "StateSaveLocation=%s" % (d / "state"),
        "SlurmdSpoolDir=%s" % (d / "spool"), "SlurmctldPidFile=%s" % (d / "slurmctld.pid"),
        "SlurmdPidFile=%s" % (d / "slurmd.pid"),
        "SlurmctldLogFile=%s" % (d / "slurmctld.log"), "SlurmdLogFile=%s" % (d / "slurmd.log"),
        "SlurmctldPort=%d" % free_port(), "SlurmdPort=%d" % free_port(),
        "ProctrackType=proctrack/linuxproc", "TaskPlugin=task/none",
        "SelectType=select/cons_tres", "SelectTypeParameters=CR_Core_Memory",
        "JobAcctGatherType=jobacct_gather/none", "AccountingStorageType=accounting_storage/none",
        "MpiDefault=none", "ReturnToService=2", "MinJobAge=600",
        "NodeName=%s CPUs=2 RealMemory=2000 State=UNKNOWN" % node,
        "PartitionName=test Nodes=%s Default=YES MaxTime=INFINITE State=UP" % node, ""]))
    env = dict(os.environ, SLURM_CONF=str(conf), USER="root")
    started = []
    subprocess.run(["munged", "--force", "--socket=%s" % sock, "--key-file=%s" % key,
                    "--pid-file=%s" % (d / "munge" / "munged.pid"),
                    "--log-file=%s" % (d / "munge" / "munged.log"),
                    "--seed-file=%s" % (d / "munge" / "munged.seed")], check=True, env=env)
    started.append(d / "munge" / "munged.pid")
    try:
        for daemon, pid in (("slurmctld", "slurmctld.pid"), ("slurmd", "slurmd.pid")):
            subprocess.run([daemon, "-f", str(conf)], check=True, env=env)
            started.append(d / pid)
            wait_for((d / pid).exists, 20, daemon + " pid file")
        t0 = time.time()
        wait_for(lambda: subprocess.run(["sinfo", "-h", "-o", "%T"], env=env, text=True,
                                        stdout=subprocess.PIPE).stdout.strip() == "idle",
                 30, "idle node")
        print("Slurm cluster up %.1f s after the daemons" % (time.time() - t0))
        yield env
    finally:
        for pidfile in reversed(started):
            if pidfile.exists():
                os.kill(int(pidfile.read_text().split()[0]), 15)


def test_deposit_runs_as_a_slurm_job(cluster, tmp_path):
    config = yaml.safe_load(open(os.path.join(ROOT, "workflow", "config", "tiny.yaml")))
    config.update(ranks=2, N=60, mem_mb=700, runtime=7, retries=0)
    (tmp_path / "slurm.yaml").write_text(yaml.safe_dump(config))
    target = tmp_path / "results" / "points" / "eta1_zeta1_dr0_N60_coulomb" / "s1" / "packing.dat"
    env = dict(cluster)
    if "LAMMPS_BUILD" not in env and env.get("ELLIPSOID_DEP_LMP"):
        env["LAMMPS_BUILD"] = os.path.dirname(env["ELLIPSOID_DEP_LMP"])
    t0 = time.time()
    r = subprocess.run(
        ["snakemake", "--snakefile", os.path.join(ROOT, "workflow", "Snakefile"),
         "--configfile", str(tmp_path / "slurm.yaml"),
         "--profile", os.path.join(ROOT, "workflow", "profiles", "slurm"),
         # at most 1: Snakemake 7 turns a higher rate into one check per 33 s on Slurm
         "--max-status-checks-per-second", "1", "--latency-wait", "5",
         "--directory", str(tmp_path / "work"), str(target),
         "--config", "results=%s" % (tmp_path / "results"), "scratch=%s" % (tmp_path / "scratch")],
        env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    print(r.stdout[-2000:], "\nthrough Slurm in %.1f s" % (time.time() - t0))
    assert r.returncode == 0, r.stdout[-3000:]
    assert target.exists()
    (jobid,) = re.findall(r"submitted with SLURM jobid (\d+)", r.stdout)
    job = subprocess.run(["scontrol", "show", "job", jobid], env=env, text=True,
                         stdout=subprocess.PIPE).stdout
    assert "JobState=COMPLETED" in job, job
    assert re.search(r"NumTasks=2\b", job) and "TimeLimit=00:07:00" in job, job
    assert re.search(r"MinMemoryNode=700M\b", job), job
    # LAMMPS ran on the job's 2 ranks, split in x and y
    log = tmp_path / "scratch" / "points" / "eta1_zeta1_dr0_N60_coulomb_s1" / "log.lammps"
    assert "2 by 1 by 1 MPI processor grid" in log.read_text()
    assert list((tmp_path / "work" / ".snakemake" / "slurm_logs" / "rule_deposit").glob("*.log"))
