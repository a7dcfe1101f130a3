"""The deposition study end to end at a tiny size: the default deposit (tools/deposit_run.py on
2 MPI ranks) and a sweep of 2 shapes (tools/sweep.py) with its figures
(tools/plot_figures.py). Checks that the files exist, the numbers are sane and the PNGs are
non-empty images."""
import csv
import os
import struct
import subprocess
import sys


ROOT = os.environ.get("ELLIPSOID_DEP_ROOT",
                      os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
TOOLS = os.path.join(ROOT, "tools")
PY = sys.executable


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


def run(cmd, cwd, timeout):
    r = subprocess.run(cmd, cwd=cwd, env=lmp_env(), stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=timeout)
    assert r.returncode == 0, r.stdout[-3000:]
    return r.stdout


def test_default_deposit(tmp_path):
    out = tmp_path / "dep"
    text = run([PY, os.path.join(TOOLS, "deposit_run.py"), "--np", "2", "--N", "40",
                "--ketol", "1e-3", "--out", str(out), "--quiet"], str(tmp_path), 600)
    assert "volume fraction phi" in text
    for name in ("log.lammps", "packing.dat", "contact_histo.dat", "orient_histo.dat",
                 "deposit.dump"):
        assert (out / name).stat().st_size > 0, name
    for name in ("deposit.png", "contact_histo.png", "orient_histo.png"):
        assert_image(str(out / name))
    pk = {}
    for line in open(out / "packing.dat"):
        if not line.startswith("#"):
            k, v = line.split(None, 1)
            pk[k] = v.strip()
    # 40 particles make a deposit about one diameter high: the measuring slab (one diameter
    # above the ground, two below the surface) may be empty, so only sanity is checked
    assert 0.0 <= float(pk["phi"]) < 0.8
    assert int(float(pk["steps"])) > 0
    # the dump holds 40 particles with semi-axes and quaternions
    lines = open(out / "deposit.dump").read().splitlines()
    assert lines[3].strip() == "40"
    cols = lines[8].split()[2:]
    assert cols[:9] == ["id", "type", "x", "y", "z", "quatw", "quati", "quatj", "quatk"]
    assert cols[9:12] == ["semi_a_x", "semi_a_y", "semi_a_z"]
    row = [float(x) for x in lines[9].split()]
    q = row[5:9]
    assert abs(sum(x * x for x in q) - 1.0) < 1e-6
    a, b, c = row[9:12]
    assert a >= b >= c > 0    # eta = 1.4, zeta = 1.8: semi-axes a > b > c along x, y, z
    assert abs(a / b - 1.4) < 1e-6 and abs(b / c - 1.8) < 1e-6


def test_tiny_sweep_and_figures(tmp_path):
    out = tmp_path / "sweep"
    args = [PY, os.path.join(TOOLS, "sweep.py"), "--eta", "1.0", "1.5", "--zeta", "1.0",
            "--dr", "0", "--seeds", "1", "--N", "150", "--ketol", "1e-3", "--jobs", "2", "--out", str(out)]
    text = run(args, str(tmp_path), 900)
    assert "2 finished points" in text
    rows = list(csv.DictReader(open(out / "results.csv")))
    assert len(rows) == 2
    for r in rows:
        assert 0.4 < float(r["phi"]) < 0.85 and float(r["Z"]) > 2.0
        assert (out / r["contact_histo"]).exists() and (out / r["orient_histo"]).exists()
        assert float(r["run_seconds"]) > 0
    # resumable: a second call runs nothing
    text = run(args, str(tmp_path), 120)
    assert "0 to run" in text
    text = run([PY, os.path.join(TOOLS, "plot_figures.py"), str(out / "results.csv")],
               str(tmp_path), 300)
    for name in ("fig_density_lines.png", "fig_contact_shapes.png", "fig_orient_shapes.png"):
        assert_image(str(out / name))
