"""fix wall/gran/region/ellipsoid and the region as it is at each run and each step: a region
deleted and defined again between runs gives the walls its new faces (looked up by its ID at
every run, as LAMMPS's fix wall/gran/region does), and a region whose walls reach across a
periodic boundary (at rest, or moved there by `move`) is an ERROR naming it, the dimension and
the step, where walls that are the same at every shift along the dimension are fine."""
import re

import numpy as np
import pytest

import ed_helpers_pour as h
import scenes
from conftest import new_lammps

LAW = "hertz 1e4 300 tangential history 1e3 0.5"
RADIUS = 0.4


def particle_in_cup(lmp, floor, extra=""):
    """A sphere resting on the floor of a block region under gravity, box z from -3."""
    lmp.commands_string(scenes.particle_box("ellipsoid", -3.0, 5.0, boundary="f f f") + f"""
        create_atoms 1 single 2 2 {floor + RADIUS + 0.05}
        set type 1 shape {2 * RADIUS} {2 * RADIUS} {2 * RADIUS}
        set type 1 density 1.0
        velocity all set 0.3 0 0
        region cup block 0.5 3.5 0.5 3.5 {floor} 4.5
        fix g all gravity 1.0 vector 0 0 -1
        fix i all nve/ellipsoid
        fix w all wall/gran/region/ellipsoid {LAW} region cup {extra}
        timestep 1e-3
        run 1500 post no
        """)


@pytest.mark.parametrize("spacer", ["", "region spacer sphere 0 0 0 1"])
def test_a_region_defined_again_gives_its_new_faces(tmp_path, spacer):
    """The floor lowered from 0 to -2 by deleting and defining the region again (at the freed
    address, or at another one with a region in between): the sphere falls to the new floor."""
    lmp = h.new_lammps(tmp_path)
    particle_in_cup(lmp, 0.0)
    resting = lmp.numpy.extract_atom("x")[0][2]
    lmp.commands_string(f"""
        region cup delete
        {spacer}
        region cup block 0.5 3.5 0.5 3.5 -2.0 4.5
        run 3000 post no
        """)
    z = lmp.numpy.extract_atom("x")[0][2]
    log = h.read_log(lmp)
    lmp.close()
    assert resting == pytest.approx(RADIUS, abs=0.01)
    assert -2.0 + RADIUS - 0.05 < z < -2.0 + RADIUS + 0.05
    assert "Region cup for fix wall/gran/region/ellipsoid was defined again between runs: its " \
           "walls are rebuilt, the wall contacts' histories restart" in log


def test_a_region_defined_again_as_it_was_changes_nothing(tmp_path):
    """The same region defined again: the sliding sphere's friction history and its path go
    on exactly as without it."""
    paths = []
    for again in (False, True):
        lmp = h.new_lammps(tmp_path, f"again{again}")
        particle_in_cup(lmp, 0.0)
        if again:
            lmp.commands_string("region cup delete\nregion cup block 0.5 3.5 0.5 3.5 0.0 4.5")
        lmp.command("run 500 post no")
        paths.append(np.array(lmp.numpy.extract_atom("x")[0]))
        lmp.close()
    np.testing.assert_array_equal(paths[0], paths[1])


@pytest.mark.parametrize("commands, message", [
    (["region cup delete", "region cup sphere 2 2 2 1.5", "run 0"],
     "region cup now has 1 faces, not 6; define the fix again"),
    (["region cup delete", "run 0"],
     "Region cup for fix wall/gran/region/ellipsoid does not exist"),
    (["region cup delete", "write_restart wall.restart noinit"],
     "Region cup for fix wall/gran/region/ellipsoid does not exist"),
    (["region cup delete", "region cup prism 0 4 0 4 0 4 0.1 0 0", "run 0"],
     "region cup is of style prism"),
])
def test_a_region_gone_or_of_another_kind_is_an_error(tmp_path, commands, message):
    lmp = h.new_lammps(tmp_path)
    try:
        particle_in_cup(lmp, 0.0)
        with pytest.raises(Exception, match=re.escape(message)):
            for c in commands:
                lmp.command(c)
    finally:
        lmp.close()


def particle_box(boundary, position=(2.0, 2.0, 2.0)):
    return scenes.particle_box("ellipsoid", 0.0, 4.0, boundary=boundary) + \
        "create_atoms 1 single {} {} {}\n".format(*position) + \
        "set type 1 shape 0.4 0.4 0.4\nset type 1 density 1.0\n" \
        "fix i all nve/ellipsoid\ntimestep 1e-3\n"


@pytest.mark.parametrize("boundary, region, dim", [
    ("p p f", "region r block 1 5 1 3 0.5 3.5", "x"),               # planes beyond the box
    ("p p p", "region r cylinder z 2 2 1.5 1.0 5.0 open 1 open 2", "z"),    # open faces
    ("p p f", "region r plane 2 2 2 1 0 0", "x"),                   # a half-space along x
    ("p p f", "region r cylinder x 2 2 1.5 0.5 3.5 rotate v_a 2 2 2 0 0 1", "x"),
])
def test_walls_across_a_periodic_boundary_are_an_error(boundary, region, dim):
    lmp = new_lammps()
    try:
        lmp.commands_string(particle_box(boundary) + "variable a equal 0.5\n" + region + "\n")
        with pytest.raises(Exception, match=re.escape(f"crosses the periodic boundary in {dim}")):
            lmp.command(f"fix w all wall/gran/region/ellipsoid {LAW} region r")
            lmp.command("run 0 post no")
    finally:
        lmp.close()


@pytest.mark.parametrize("boundary, region", [
    ("p p f", "region r block INF INF INF INF 0.5 3.5"),
    ("p p p", "region r cylinder z 2 2 1.5 INF INF"),
    ("p p p", "region r block 1 3 1 3 INF INF side out"),
    # a drum turning about its axis next to the boundaries (its bounding box's corners would
    # reach across them)
    ("p p p", "region r cylinder z 2 2 1.9 INF INF rotate v_a 2 2 0 0 0 1"),
])
def test_walls_the_same_along_a_periodic_dimension_are_fine(boundary, region):
    lmp = new_lammps()
    try:
        position = (0.5, 0.5, 2.0) if "side out" in region else (2.0, 2.0, 2.0)
        lmp.commands_string(particle_box(boundary, position) + "variable a equal 3*time\n" +
                            region + "\n")
        lmp.command(f"fix w all wall/gran/region/ellipsoid {LAW} region r")
        lmp.command("run 300 post no")
    finally:
        lmp.close()


def test_a_region_moved_across_a_periodic_boundary_is_an_error():
    """A ball (sphere, side out, radius 0.9) moved along x at speed 1 from x = 1.5 through a
    box periodic in x: its walls reach a particle centre 0.2 (the particle's radius) beyond
    its surface, so they reach x = 4 when the ball has moved by 1.4, at step 1400."""
    lmp = new_lammps()
    try:
        lmp.commands_string(particle_box("p p f", (3.5, 2.0, 2.0)) + """
            variable dx equal 1.0*time
            region ball sphere 1.5 2 2 0.9 side out move v_dx NULL NULL
            """)
        lmp.command(f"fix w all wall/gran/region/ellipsoid {LAW} region ball")
        with pytest.raises(Exception) as refused:
            lmp.command("run 2000 post no")
        pushed = lmp.numpy.extract_atom("v")[0][0]
    finally:
        lmp.close()
    found = re.search(r"region ball's sphere \(radius 0.9\) crosses the periodic boundary in x "
                      r"at step (\d+)", str(refused.value))
    assert found and int(found.group(1)) in (1400, 1401)
    assert pushed > 0.5    # the ball (speed 1) met the particle in its path on the way
