"""The default deposit end to end at a tiny size: tools/deposit/deposit_run.py on 2 MPI ranks (split
in x and y) pours 40 particles of examples/deposit/in.deposit, stops at rest and writes its
files: the log, packing.dat (with the force measures), the histograms (also force-weighted, and
P(f/<f>)), the profile, the dump (semi-axes and quaternions) and the PNGs (dump image; matplotlib:
histograms, P(f/<f>) and the phi(z) profile). The rest criterion is 1e-2 m g d per particle (the
tiny study's), which the checks here do not depend on."""
import math
import os

import deposit_depth
import deposit_run
import pytest

from study_helpers import PY, TOOLS, assert_image, run


def test_default_deposit(tmp_path):
    out = tmp_path / "dep"
    text = run([PY, os.path.join(TOOLS, "deposit", "deposit_run.py"), "--np", "2", "--N", "40",
                "--ketol", "1e-2", "--out", str(out), "--quiet", "--var", "slabmin", "0"],
               str(tmp_path), 600)
    assert "volume fraction phi" in text
    for name in ("log.lammps", "packing.dat", "contact_histo.dat", "orient_histo.dat",
                 "contact_force_histo.dat", "force_histo.dat", "profile.dat", "deposit.dump"):
        assert (out / name).stat().st_size > 0, name
    for name in ("deposit.png", "contact_histo.png", "orient_histo.png", "force_histo.png",
                 "profile.png"):
        assert_image(str(out / name))
    pk = {}
    for line in open(out / "packing.dat"):
        if not line.startswith("#"):
            k, v = line.split(None, 1)
            pk[k] = v.strip()
    # 40 particles make a deposit about one diameter high: the measuring slab (one diameter
    # above the ground, two below the surface) may be empty, so only sanity is checked; the
    # runner refuses such a deposit unless slabmin 0 asks for no check, and packing.dat and the
    # summary still say whether the slab is empty
    assert 0.0 <= float(pk["phi"]) < 0.8
    assert pk["slabmin"] == "0"
    assert pk["slab_ok"] == ("1" if float(pk["slab_thickness"]) > 0 else "0")
    assert ("WARNING: the measuring slab is empty" in text) == (pk["slab_ok"] == "0")
    for key in ("sigma_xx", "sigma_yy", "sigma_zz", "K0", "mean_normal_force",
                "fabric_anisotropy_force", "a_n", "a_f"):
        assert math.isfinite(float(pk[key])), key
    theta, p_force, fraction, mean_force = deposit_run.read_histo(
        str(out / "contact_force_histo.dat"), 4)
    assert len(theta) == 18 and all(f >= 0.0 for f in mean_force)
    assert int(float(pk["steps"])) > 0
    # the phi(z) profile of compute packing/profile: fractions in [0, 1], some solid
    z, phi, volume = deposit_run.read_histo(str(out / "profile.dat"))
    assert len(z) > 1 and all(0.0 <= p <= 1.0 for p in phi)
    assert sum(volume) > 0
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
    # the tall box is split in x and y only, so both ranks hold particles
    assert "2 by 1 by 1 MPI processor grid" in open(out / "log.lammps").read()
    # packing.dat's box_width is the box's edge: 0.3 sqrt(40) = 1.9 d is below the least
    # edge, two neighbour cutoffs of the longest particles, 4 bmax + 2 skin
    bmax = 0.5 * 1.6 * (1.4 ** 2 * 1.8) ** (1 / 3)
    edge = max(5.0, 4 * bmax + 0.4)
    assert float(pk["box_width"]) == pytest.approx(edge, rel=1e-12)
    assert dump_edge(lines) == pytest.approx(edge, rel=1e-12)
    # the runner's depth check sizes the box as in.deposit does
    settings = deposit_run.read_settings(str(out))
    assert deposit_depth.box_width(settings) == pytest.approx(edge, rel=1e-12)


def dump_edge(lines):
    """the x edge of a dump's box (its lines)"""
    lo, hi = map(float, lines[5].split()[:2])
    return hi - lo


def test_deposit_in_a_box_of_given_width(tmp_path):
    """in.deposit's width sets the box's edge (a deeper deposit of the same N)"""
    out = tmp_path / "dep"
    run([PY, os.path.join(TOOLS, "deposit", "deposit_run.py"), "--np", "1", "--N", "40", "--ketol", "1e-2",
         "--out", str(out), "--quiet", "--no-image", "--no-plots", "--var", "width", "7.5",
         "--var", "slabmin", "0"], str(tmp_path), 600)
    lines = open(out / "deposit.dump").read().splitlines()
    assert dump_edge(lines) == pytest.approx(7.5, rel=1e-12)
    assert deposit_depth.box_width(deposit_run.read_settings(str(out))) == 7.5
    assert "box_width 7.5\n" in open(out / "packing.dat").read()


@pytest.mark.parametrize("seed", [1, 2])
def test_thin_particles_driven_through_the_ground_are_kept(tmp_path, seed):
    """Heavy particles landing on thin ones lying on the ground can drive them through it when
    the contacts are soft for the impacts (the matched-depth study's eta = zeta = 3, delta_r 0.6
    lost one in its taller box). Here the contacts are so soft (kn 10) that every pour does it:
    the box follows them down (boundary m), the ground's half-space contact pushes them back,
    and each chunk's setup warns instead of failing; before, LAMMPS stopped on lost atoms, or
    on centres on the solid side of the wall."""
    out = tmp_path / "dep"
    run([PY, os.path.join(TOOLS, "deposit", "deposit_run.py"), "--np", "1", "--N", "40", "--eta", "3",
         "--zeta", "3", "--dr", "0.6", "--seed", str(seed), "--out", str(out), "--quiet",
         "--no-image", "--no-plots", "--var", "kn", "10", "--var", "K", "1", "--var", "dt",
         "2e-3", "--var", "maxchunks", "4", "--var", "slabmin", "0"], str(tmp_path), 600)
    log = open(out / "log.lammps").read()
    assert "particle centre(s) were driven through a flat wall during the last run" in log
    assert "ERROR" not in log
    assert "N 40\n" in open(out / "packing.dat").read()
