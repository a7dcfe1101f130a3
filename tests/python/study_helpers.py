"""Running the study's tools (tools/*/*.py, Snakemake) as the user would, from the tests:
the environment of the child processes, a command that must succeed (or fail), and PNG
checks."""
import os
import struct
import subprocess
import sys

from conftest import root_dir

ROOT = root_dir()
TOOLS = os.path.join(ROOT, "tools")
PY = sys.executable
SNAKEFILE = os.path.join(ROOT, "workflow", "Snakefile")
TINY = os.path.join(ROOT, "workflow", "config", "tiny.yaml")


def lmp_env():
    env = dict(os.environ)
    if "LAMMPS_BUILD" not in env and env.get("ELLIPSOID_DEP_LMP"):
        env["LAMMPS_BUILD"] = os.path.dirname(env["ELLIPSOID_DEP_LMP"])
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    env.setdefault("OMPI_MCA_rmaps_base_oversubscribe", "1")
    env["MPLBACKEND"] = "Agg"
    env["ELLIPSOID_DEP_ROOT"] = ROOT
    return env


def png_size(path):
    """(width, height) of a PNG, checking its signature and IHDR chunk"""
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", "%s is not a PNG" % path
    assert head[12:16] == b"IHDR"
    return struct.unpack(">II", head[16:24])


def assert_image(path):
    assert os.path.getsize(path) > 1000, path
    w, h = png_size(path)
    assert w > 50 and h > 50, (path, w, h)


def run(cmd, cwd, timeout, ok=True):
    r = subprocess.run(cmd, cwd=cwd, env=lmp_env(), stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=timeout)
    assert (r.returncode == 0) == ok, r.stdout[-3000:]
    return r.stdout
