"""The command-line tools on bad input: one clear line and a non-zero exit, never a traceback,
and never a failed run's numbers as a result.

* tools/pores/pores.py (./ellipsoid-dep pores) on hand-made run folders: a truncated dump, a
  packing.dat without its slab, voxel sizes whose image would not fit in memory (the message
  states what it would need), no atoms, a zero quaternion, overlapping particles (a negative
  porosity);
* tools/deposit/deposit_run.py (./ellipsoid-dep run): options out of range and an --out that cannot be
  created, each named in one line; a deposit too shallow for its measuring slab is refused
  before LAMMPS runs, with the smallest N for the shape (which passes the same check);
* tools/containers/oedometer_run.py refuses a deposit in its folder made with other settings;
  tools/containers/oedometer_study.py run writes nothing when it ran nothing.
No LAMMPS here (tests/python/test_deposit_slab.py runs in.deposit's side).
"""
import json
import os
import re
import subprocess
import sys

import pytest

import deposit_depth
import oedometer_run
import oedometer_study
from study_helpers import PY, TOOLS, lmp_env


def write_run_folder(folder, centres, semi, box, zlo=1.0, zhi=3.0, quats=None, packing=None):
    """deposit.dump with the runner's columns and packing.dat"""
    os.makedirs(folder, exist_ok=True)
    quats = quats or [(1, 0, 0, 0)] * len(centres)
    with open(os.path.join(folder, "deposit.dump"), "w") as f:
        f.write("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n%d\nITEM: BOX BOUNDS pp pp ff\n"
                % len(centres))
        for lo, hi in box:
            f.write("%g %g\n" % (lo, hi))
        f.write("ITEM: ATOMS id type x y z quatw quati quatj quatk semi_a_x semi_a_y semi_a_z\n")
        for i, (c, q, s) in enumerate(zip(centres, quats, semi)):
            f.write("%d 1 %r %r %r %r %r %r %r %r %r %r\n" % ((i + 1,) + tuple(c) + tuple(q)
                                                              + tuple(s)))
    with open(os.path.join(folder, "packing.dat"), "w") as f:
        f.write(packing if packing is not None else
                "# test\nN %d\neta 1\nzeta 1\nzlo %r\nzhi %r\nphi 0.5\n"
                % (len(centres), zlo, zhi))


def lattice(folder, **kw):
    """touching unit spheres on a simple cubic lattice, 4 x 4 x 4"""
    centres = [(i + 0.5, j + 0.5, k + 0.5) for i in range(4) for j in range(4) for k in range(4)]
    write_run_folder(folder, centres, [(0.5,) * 3] * len(centres), [(0, 4)] * 3, **kw)
    return folder


def run_tool(args):
    """(exit code, stdout + stderr) of a tool run as a user would"""
    r = subprocess.run([PY] + args, env=lmp_env(), stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=120)
    return r.returncode, r.stdout


def assert_one_line_error(code, out, *words):
    assert code != 0, out
    assert "Traceback" not in out, out
    lines = out.strip().splitlines()
    assert len(lines) == 1, out
    for w in words:
        assert w in lines[0], (w, out)


def pores(folder, *more):
    return run_tool([os.path.join(TOOLS, "pores", "pores.py"), str(folder), "--quiet"] + list(more))


# ---- pores.py -------------------------------------------------------------------------------


def test_pores_truncated_dump(tmp_path):
    folder = lattice(str(tmp_path / "run"))
    path = os.path.join(folder, "deposit.dump")
    text = open(path).read()
    open(path, "w").write(text[:len(text) // 2])    # a kill while the dump was written
    assert_one_line_error(*pores(folder), "truncated dump", "of 64")
    open(path, "w").write(text[:60])    # in the header
    assert_one_line_error(*pores(folder), "truncated")


def test_pores_packing_without_slab(tmp_path):
    folder = lattice(str(tmp_path / "run"), packing="# test\nN 64\nphi 0.5\n")
    assert_one_line_error(*pores(folder), "no zlo or zhi", "packing.dat")
    lattice(folder, packing="# test\nN 64\nzlo 2.0\nzhi 2.0\nphi 0\n")    # an empty slab
    assert_one_line_error(*pores(folder), "empty slab")
    lattice(folder, packing="# test\nN 64\nzlo\n")    # cut in the middle of a line
    assert_one_line_error(*pores(folder), "line 3", "not a 'key value' line")


@pytest.mark.parametrize("option,value", [("--voxel", "2e-3"), ("--flow-voxel", "1e-4")])
def test_pores_voxels_beyond_memory(tmp_path, option, value):
    """the image's memory is stated and refused before numpy allocates it"""
    folder = lattice(str(tmp_path / "run"))
    more = [option, value] + (["--flow"] if option == "--flow-voxel" else [])
    code, out = pores(folder, *more)
    assert_one_line_error(code, out, option + " " + "%.4g" % float(value), "would need about",
                          "more than this machine's")
    need = re.search(r"about ([0-9.e+]+) (GiB|TiB)", out)
    assert need, out
    # the 4 x 4 x 2 slab (the flow's image has no margin) at 1e-4: 3.2e13 voxels of 16 bytes
    if option == "--flow-voxel":
        assert need.group(2) == "TiB" and float(need.group(1)) == pytest.approx(
            4e4 * 4e4 * 2e4 * 16 / 2 ** 40, rel=1e-2)


def test_pores_no_atoms_zero_quaternion_and_overlap(tmp_path):
    empty = str(tmp_path / "empty")
    write_run_folder(empty, [], [], [(0, 4)] * 3)
    assert_one_line_error(*pores(empty), "no atoms")
    turned = str(tmp_path / "quat")
    lattice(turned)
    lines = open(os.path.join(turned, "deposit.dump")).read().splitlines()
    lines[12] = lines[12].replace(" 1 0 0 0 ", " 0 0 0 0 ")
    open(os.path.join(turned, "deposit.dump"), "w").write("\n".join(lines) + "\n")
    assert_one_line_error(*pores(turned), "zero quaternion", "row 4")
    # ten spheres of radius 1.5 on one centre: 141 volume units in a slab of 32
    overlap = str(tmp_path / "overlap")
    write_run_folder(overlap, [(2, 2, 2)] * 10, [(1.5,) * 3] * 10, [(0, 4)] * 3)
    assert_one_line_error(*pores(overlap), "overlap", "porosity -")
    assert not os.path.exists(os.path.join(overlap, "pores.json"))


# ---- deposit_run.py -------------------------------------------------------------------------


def deposit_run(*args):
    return run_tool([os.path.join(TOOLS, "deposit", "deposit_run.py")] + list(args))


@pytest.mark.parametrize("args,named", [
    (["--N", "-5"], "--N -5"), (["--eta", "0"], "--eta 0"), (["--zeta", "-1"], "--zeta -1"),
    (["--dr", "1.5"], "--dr 1.5"), (["--np", "0"], "--np 0"), (["--seed", "0"], "--seed 0"),
    (["--ketol", "0"], "--ketol 0"), (["--normal", "hooke 1 2"], "--normal"),
    (["--var", "slabmin", "one"], "--var slabmin one")])
def test_deposit_run_bad_options(tmp_path, args, named):
    code, out = deposit_run(*(args + ["--out", str(tmp_path / "run")]))
    assert_one_line_error(code, out, named)
    assert not os.path.exists(tmp_path / "run")


def test_deposit_run_out_cannot_be_created(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder\n")
    code, out = deposit_run("--out", str(blocker / "run"))
    assert_one_line_error(code, out, "--out", "cannot create the run folder")


@pytest.mark.parametrize("args", [["--N", "100"], ["--N", "500", "--eta", "5", "--zeta", "5",
                                                   "--dr", "0.6"],
                                  ["--N", "200", "--eta", "1.4", "--zeta", "1.4", "--dr", "0.8"]])
def test_deposit_too_shallow_is_refused_with_the_smallest_n(tmp_path, args):
    """before: phi 0.0000 and Z 0 of an empty slab (or a slab of 23 particles), exit 0"""
    code, out = deposit_run(*(args + ["--out", str(tmp_path / "run")]))
    assert_one_line_error(code, out, "too few", "measuring slab")
    assert not os.path.exists(tmp_path / "run")
    smallest = int(re.search(r"give --N (\d+) or more", out).group(1))
    settings = {"N": int(args[1]), "eta": 1.4, "zeta": 1.8, "dr": 0.6, "vars": {}}
    for k in range(2, len(args), 2):
        settings[args[k][2:]] = float(args[k + 1])
    assert deposit_depth.too_shallow(dict(settings, N=smallest)) is None
    assert deposit_depth.too_shallow(dict(settings, N=smallest - 1)) is not None
    # a box of given width: the depth grows with N
    wide = dict(settings, vars={"width": "12"})
    n = int(re.search(r"give --N (\d+)", deposit_depth.too_shallow(wide)).group(1))
    assert deposit_depth.too_shallow(dict(wide, N=n)) is None
    # slabmin 0 runs without a slab (the tests' tiny deposits)
    assert deposit_depth.too_shallow(dict(settings, vars={"slabmin": "0"})) is None


def test_the_default_deposit_and_the_study_are_deep_enough():
    """the default N = 1000 and the study's N = 3000 shapes pass"""
    for eta, zeta, dr, n in ((1.4, 1.8, 0.6, 1000), (3, 3, 0, 3000), (3, 3, 0.6, 3000),
                             (1, 1, 0, 3000), (3, 1, 0.6, 3000), (1, 3, 0.6, 3000)):
        assert deposit_depth.too_shallow({"N": n, "eta": eta, "zeta": zeta, "dr": dr,
                                          "vars": {}}) is None, (eta, zeta, dr)


def test_size_moments_of_the_pour():
    """mono-sized: pi/6 and 1; the mean volume is below pi/6 d^3 (Jensen, as
    doc/fix_pour_ellipsoid.rst says) and falls with delta_r; the midpoint rule has converged"""
    v, d = deposit_depth.size_moments(0.0)
    assert v == pytest.approx(3.141592653589793 / 6) and d == 1.0
    previous = v
    for dr in (0.3, 0.6, 0.8):
        v, d = deposit_depth.size_moments(dr)
        assert v < previous and d < 1.0
        assert deposit_depth.size_moments(dr, nodes=20000)[0] == pytest.approx(v, rel=1e-7)
        previous = v


# ---- the oedometer's runners ----------------------------------------------------------------


def test_oedometer_refuses_another_deposit(tmp_path, capsys):
    """the deposit in OUT/deposit is reused only if it is the one asked for: before, a spheres'
    deposit was loaded and labelled eta 3 in the csv"""
    folder = tmp_path / "oedo" / "deposit"
    folder.mkdir(parents=True)
    (folder / "deposit.restart").write_text("a restart file\n")
    stored = {"N": 500, "eta": 1.0, "zeta": 1.0, "dr": 0.0, "seed": 4928, "vars": {},
              "tangential": "history 2.0e3 0.5", "normal": "hertz"}
    (folder / "settings.json").write_text(json.dumps(stored))
    args = oedometer_run.parse_args(["--N", "500", "--eta", "3", "--zeta", "3",
                                     "--out", str(tmp_path / "oedo")])
    with pytest.raises(SystemExit) as e:
        oedometer_run.make_deposit(args, str(folder))
    assert "eta 1.0 (asked 3.0)" in str(e.value) and "zeta 1.0 (asked 3.0)" in str(e.value)
    for other in (["--seed", "4929"], ["--N", "1000"], ["--dr", "0.6"]):
        args = oedometer_run.parse_args(["--N", "500", "--out", "x"] + other)
        with pytest.raises(SystemExit):
            oedometer_run.make_deposit(args, str(folder))
    (folder / "settings.json").write_text(json.dumps(dict(stored, normal="hertz/material glass")))
    with pytest.raises(SystemExit) as e:
        oedometer_run.make_deposit(oedometer_run.parse_args(["--N", "500", "--out", "x"]),
                                   str(folder))
    assert "normal hertz/material (asked hertz)" in str(e.value)
    (folder / "settings.json").unlink()
    with pytest.raises(SystemExit) as e:
        oedometer_run.make_deposit(oedometer_run.parse_args(["--N", "500", "--out", "x"]),
                                   str(folder))
    assert "no settings.json" in str(e.value)
    # the asked deposit is reused
    (folder / "settings.json").write_text(json.dumps(stored))
    restart, settings = oedometer_run.make_deposit(
        oedometer_run.parse_args(["--N", "500", "--out", "x"]), str(folder))
    assert restart == str(folder / "deposit.restart") and settings == stored


def test_oedometer_study_run_without_cases_writes_nothing(tmp_path, monkeypatch, capsys):
    results = tmp_path / "results"
    results.mkdir()
    table = results / "oedometer.csv"
    rows = [{c: "1" for c in oedometer_run.COLUMNS}]
    rows[0].update(N="500", eta="1", zeta="1", seed="4928")
    table.write_text(",".join(oedometer_run.COLUMNS) + "\n"
                     + ",".join(rows[0][c] for c in oedometer_run.COLUMNS) + "\n")
    doc = tmp_path / "study.md"
    doc.write_text("the study page\n")
    for name, value in (("RESULTS", results), ("TABLE", table),
                        ("SUMMARY", results / "summary.csv"),
                        ("FIGURE", results / "modulus_k0.png"), ("STUDY_DOC", doc)):
        monkeypatch.setattr(oedometer_study, name, str(value))
    monkeypatch.setattr(oedometer_run, "main", lambda argv: pytest.fail("ran %s" % argv))
    oedometer_study.main(["run", "--seeds", "4928", "--shapes", "1", "--N", "500",
                          "--runs", str(tmp_path / "runs")])
    assert "nothing ran, nothing written" in capsys.readouterr().out
    assert sorted(os.listdir(results)) == ["oedometer.csv"]
    assert doc.read_text() == "the study page\n"


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-v"]))
