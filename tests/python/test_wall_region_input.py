"""fix wall/gran/region/ellipsoid: bad input gets an ERROR that names it,
a wall that starts inside particles a WARNING that says how many (at its first run), and the wall contacts'
history and the region's motion survive write_restart/read_restart."""
import re

import numpy as np
import pytest

import ed_helpers_pour as h
import scenes
from conftest import new_lammps

LAW = "hertz/material 1e5 0.3 0.8"
RADIUS = 0.2


def box(boundary="f f f"):
    return scenes.particle_box("ellipsoid", 0.0, 4.0, boundary=boundary) + \
        f"create_atoms 1 single 2 2 2\nset type 1 shape {2 * RADIUS} {2 * RADIUS} {2 * RADIUS}\n" \
        "set type 1 density 1.0\n"


@pytest.mark.parametrize("boundary,region,fix,message", [
    ("f f f", "region r prism 0.5 3.5 0.5 3.5 0.5 3.5 0.2 0 0", f"{LAW} region r",
     "region r is of style prism; the supported region styles are block, cylinder, cone "
     "(side in), sphere and plane"),
    ("f f f", "region r sphere 2 2 2 1.5", f"{LAW} region nope",
     "Region nope for fix wall/gran/region/ellipsoid does not exist"),
    ("p p f", "region r cylinder z 1.0 2 1.5 0.5 3.5", f"{LAW} region r",
     "region r's cylinder (radius 1.5) crosses the periodic boundary in x"),
    ("p p p", "region r sphere 2 2 2.5 1.8", f"{LAW} region r",
     "region r's sphere (radius 1.8) crosses the periodic boundary in z"),
    ("f f f", "region r cylinder z 2 2 1.5 0.5 3.5", f"{LAW} region r wiggle z 0.1 1",
     "wiggle is a keyword of fix wall/gran/ellipsoid's planes; a region wall moves with its "
     "region (region keywords move and rotate)"),
    ("f f f", "region r cylinder z 2 2 1.5 0.5 3.5", f"{LAW} region r shear x 1",
     "shear is a keyword of fix wall/gran/ellipsoid's planes"),
    ("f f f", "region r cylinder z 2 2 1.5 0.5 3.5",
     f"{LAW} region r servo force 1 gain 1 vmax 1",
     "servo is a keyword of fix wall/gran/ellipsoid's planes; a piston in this region is a "
     "plane servo with 'area A'"),
    ("f f f", "region r cylinder z 2 2 1.5 0.5 3.5", f"{LAW}", "needs region ID after the force law"),
    ("f f f", "region r cylinder z 2 2 1.5 0.5 3.5", f"{LAW} region r bogus",
     "Unknown fix wall/gran/region/ellipsoid keyword 'bogus'"),
    ("f f f", "region r block 1 3 1 3 1 3 side out open 2", f"{LAW} region r",
     "region r has side out and open faces; a region met from outside must be closed"),
    ("f f f", "region r cone z 2 2 0.5 1.5 0.5 3.5 side out", f"{LAW} region r",
     "region r is a cone with side out; a cone is supported with side in"),
    ("f f f", "variable rad equal 1.5\nregion r sphere 2 2 2 v_rad", f"{LAW} region r",
     "region r changes its shape with variables, not supported (move and rotate are)"),
])
def test_bad_input_is_an_error(boundary, region, fix, message):
    lmp = new_lammps()
    try:
        lmp.commands_string(box(boundary) + region + "\n")
        with pytest.raises(Exception, match=re.escape(message)):
            lmp.command(f"fix w all wall/gran/region/ellipsoid {fix}")
    finally:
        lmp.close()


def test_wall_inside_particles_is_a_warning_that_counts_them(tmp_path):
    """Three spheres overlap the cylinder's side, one has its centre outside the region (left
    alone, as LAMMPS's fix wall/gran/region leaves it), one is free."""
    lmp = h.new_lammps(tmp_path)
    lmp.commands_string(scenes.spheres_in_box(
        "ellipsoid", (4, 4, 4), [(3.35, 2, 2), (2, 3.36, 2), (0.66, 2, 2), (2, 0.45, 2),
                                 (2, 2, 2)], RADIUS))
    lmp.commands_string(f"""
        region r cylinder z 2 2 1.5 0.5 3.5
        fix w all wall/gran/region/ellipsoid {LAW} region r
        run 0 post no
        run 0 post no
        """)
    log = h.read_log(lmp)
    lmp.close()
    # once, at the first run (a later run continues the resting contacts)
    assert log.count("the wall starts inside 3 particle(s)") == 1
    assert "1 particle centre(s) lie outside region r" in log


def ellipsoids_in_cylinder(lmp, law):
    """Four tilted triaxial ellipsoids falling in a cylinder that moves along x."""
    lmp.commands_string(scenes.particle_box("ellipsoid", 0.0, 4.0, boundary="f f f"))
    rng = np.random.default_rng(5)
    for k, p in enumerate([(3.2, 2.0, 0.9), (0.85, 2.2, 0.8), (2.0, 3.2, 1.2), (2.0, 0.85, 1.5)]):
        lmp.command(f"create_atoms 1 single {p[0]} {p[1]} {p[2]}")
        q = rng.normal(size=4)
        lmp.command(f"set atom {k + 1} shape 0.5 0.3 0.16")
        lmp.command(f"set atom {k + 1} quat {q[1]} {q[2]} {q[3]} {np.degrees(q[0])}")
    lmp.commands_string(f"""
        set type 1 density 1.0
        velocity all set 0.3 -0.2 -0.5
        variable dx equal 0.2*time
        region r cylinder z 2 2 1.4 0.5 3.5 move v_dx NULL NULL
        pair_style granular/ellipsoid
        pair_coeff * * {law}
        fix g all gravity 9.81 vector 0.4 0 -1
        fix i all nve/asphere
        fix w all wall/gran/region/ellipsoid {law} region r
        timestep 1e-4
        """)


def test_history_and_motion_survive_restart(tmp_path):
    """The tangential history per atom and face and the region's motion state (its previous
    displacement, from which the wall's velocity follows) continue across read_restart as if
    the run had not stopped."""
    law = "hertz 1e4 100 tangential history 1e3 0.5"
    lmp = h.new_lammps(tmp_path, "a")
    ellipsoids_in_cylinder(lmp, law)
    lmp.command("run 1500")
    restart = tmp_path / "wall.restart"
    lmp.command(f"write_restart {restart}")
    # the force on each face: the lo cap, the hi cap, the side
    touching = np.array([lmp.extract_fix("w", 0, 1, k) for k in range(9)])
    lmp.command("run 300")
    ref = h.snapshot(lmp, tmp_path, "ref")
    lmp.close()
    assert abs(touching[2]) > 0.0 and np.abs(touching[6:]).max() > 0.0    # floor and side

    lmp = h.new_lammps(tmp_path, "b")
    lmp.commands_string(f"""
        read_restart {restart}
        comm_modify vel yes
        pair_coeff * * {law}
        variable dx equal 0.2*time
        region r cylinder z 2 2 1.4 0.5 3.5 move v_dx NULL NULL
        fix g all gravity 9.81 vector 0.4 0 -1
        fix i all nve/asphere
        fix w all wall/gran/region/ellipsoid {law} region r
        timestep 1e-4
        run 300
        """)
    cont = h.snapshot(lmp, tmp_path, "cont")
    log = h.read_log(lmp)
    lmp.close()
    assert "Resetting peratom fix info from restart file" in log
    assert "inconsistent with restart file" not in log
    np.testing.assert_allclose(cont["x3"], ref["x3"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(cont["v3"], ref["v3"], rtol=0, atol=1e-10)


def test_a_particle_out_through_an_open_face_is_free():
    """A hopper open at its outlet (cone, open 1): a sphere inside feels the side, one whose
    centre has left through the outlet feels nothing, though the side's cone continued below
    the outlet would cut it (the region counts as closed for where a centre is)."""
    lmp = new_lammps()
    try:
        lmp.commands_string(scenes.spheres_in_box(
            "ellipsoid", (4, 4, 4), [(2.43, 2.0, 1.2), (2.3, 2.0, 0.7)], RADIUS))
        lmp.commands_string(f"""
            region r cone z 2 2 0.5 1.5 1.0 3.5 open 1
            fix w all wall/gran/region/ellipsoid {LAW} region r
            run 0 post no
            """)
        f = np.array(lmp.numpy.extract_atom("f")[:2])
        side = [lmp.extract_fix("w", 0, 1, k) for k in range(3, 6)]
        with pytest.raises(Exception, match="out-of-range"):    # two faces: hi cap, side
            lmp.extract_fix("w", 0, 1, 6)
    finally:
        lmp.close()
    # the side at z: rho = 0.5 + 0.4 (z - 1), the normal tilted by cos(alpha) = 0.928
    assert np.linalg.norm(f[0]) > 0.0 and np.linalg.norm(side) > 0.0    # 0.139 from the side
    assert np.linalg.norm(f[1]) == 0.0    # below the outlet, 0.074 from the side continued


@pytest.mark.parametrize("region,edge", [
    ("region r block 1 3 1 3 1 3 side out", (3.13, 3.13, 2.0)),
    ("region r cylinder z 2 2 0.8 1 3 side out", (2.93, 2.0, 3.13)),
])
def test_a_solid_met_from_outside_is_one_wall(region, edge):
    """A block or a capped post with side out (faces meeting inside the box: once an ERROR)
    is one wall, its faces, edges, corners and rims together: a sphere at an edge or a rim
    feels it, the wall's force vector has one wall's three components."""
    lmp = new_lammps()
    try:
        lmp.commands_string(scenes.spheres_in_box("ellipsoid", (4, 4, 4), [edge], RADIUS))
        lmp.commands_string(f"""
            {region}
            fix w all wall/gran/region/ellipsoid {LAW} region r
            run 0 post no
            """)
        force = [lmp.extract_fix("w", 0, 1, k) for k in range(3)]
        with pytest.raises(Exception, match="out-of-range"):
            lmp.extract_fix("w", 0, 1, 3)
    finally:
        lmp.close()
    assert np.linalg.norm(force) > 0.0
