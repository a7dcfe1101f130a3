"""Moving walls: `wiggle dim A period` and `shear dim v` of fix wall/gran/ellipsoid, the words
and motion of LAMMPS's fix wall/gran (wall at lo + A (1 - cos(omega t)), velocity
A omega sin(omega t); a shearing wall stays in place and moves along dim at v).

Sphere limit: a sphere bouncing on a resting or a wiggling floor follows the trajectory it
follows under LAMMPS's fix wall/gran with the same motion and the mapped law (hertz/material
with damping coeff_restitution, frictionless), step for step. Shear, with friction: a sphere
resting on a floor that starts to shear is first pushed along the shear by the tangential
spring (force kt v dt after one step, from the law's closed form) and turned about the axis
normal to the shear and the floor, and on a resting floor it is not.
"""
import math

import numpy as np
import pytest

import scenes
from conftest import new_lammps

E, NU, REST = 1.0e5, 0.3, 0.8
RADIUS, DENSITY = 0.5, 1.0
DT = 1e-4


def sphere_on_floor(style, wall, motion, z0=0.62, vz=-0.5):
    """One sphere above the floor z = 0, falling; LAMMPS's sphere style and fix wall/gran
    (style 'sphere'), or this package (style 'ellipsoid')."""
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box(style, (4, 4, 6), [(2.0, 2.0, z0)], RADIUS, DENSITY))
    lmp.commands_string(f"""
        velocity all set 0.0 0.0 {vz}
        fix g all gravity 1.0 vector 0 0 -1
        {wall} zplane 0.0 NULL {motion}
        fix i all {"nve/sphere" if style == "sphere" else "nve/ellipsoid"}
        timestep {DT}
        """)
    return lmp


def trajectory(lmp, steps, every):
    z, vz = [], []
    for _ in range(steps // every):
        lmp.command(f"run {every} post no")
        z.append(lmp.numpy.extract_atom("x")[0][2])
        vz.append(lmp.numpy.extract_atom("v")[0][2])
    return np.array(z), np.array(vz)


@pytest.mark.parametrize("motion", ["", "wiggle z 0.05 0.02", "wiggle z 0.02 0.005"])
def test_sphere_on_a_moving_floor_follows_fix_wall_gran(motion):
    ours = sphere_on_floor("ellipsoid", f"fix w all wall/gran/ellipsoid hertz/material {E} {NU} "
                           f"{REST}", motion)
    ref = sphere_on_floor("sphere", f"fix w all wall/gran granular hertz/material {E} {REST} {NU} "
                          "damping coeff_restitution tangential linear_nohistory 0 0", motion)
    z, vz = trajectory(ours, 6000, 200)
    z_ref, vz_ref = trajectory(ref, 6000, 200)
    ours.close()
    ref.close()
    # the sphere touched the floor (its lowest point below the floor's highest position)
    assert z.min() < RADIUS + (0.1 if "wiggle" in motion else 0.0)
    np.testing.assert_allclose(z, z_ref, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(vz, vz_ref, rtol=1e-8, atol=1e-10)


def test_wiggling_floor_moves_as_fix_wall_gran_says():
    """A sphere resting on a floor that wiggles slowly follows the floor: its height minus the
    resting height is A (1 - cos(omega t)) to within the contact's compliance."""
    amplitude, period = 0.02, 2.0
    lmp = sphere_on_floor("ellipsoid", f"fix w all wall/gran/ellipsoid hertz/material {E} {NU} "
                          f"{REST}", f"wiggle z {amplitude} {period}", z0=RADIUS, vz=0.0)
    lmp.command("run 5000 post no")    # settles at its resting overlap (floor nearly still)
    t0 = 5000 * DT
    rest = lmp.numpy.extract_atom("x")[0][2] - amplitude * (1 - math.cos(2 * math.pi * t0 / period))
    heights, expected = [], []
    for k in range(1, 11):
        lmp.command("run 1000 post no")
        t = t0 + k * 1000 * DT
        heights.append(lmp.numpy.extract_atom("x")[0][2])
        expected.append(rest + amplitude * (1 - math.cos(2 * math.pi * t / period)))
    lmp.close()
    # the floor accelerates by up to A omega^2 (0.2 g here): the contact's compliance lets the
    # sphere lag by a part of its resting Hertz overlap, and no more
    e_star = E / (2 * (1 - NU**2))
    mass = DENSITY * 4 / 3 * math.pi * RADIUS**3
    resting_overlap = (mass / (4 / 3 * e_star * math.sqrt(RADIUS)))**(2 / 3)
    np.testing.assert_allclose(heights, expected, atol=resting_overlap)
    assert max(heights) - min(heights) > 0.5 * amplitude


@pytest.mark.parametrize("vshear", [0.0, 0.3])
def test_shearing_floor_drags_a_resting_sphere(vshear):
    kt, mu = 2.0e3, 0.5
    lmp = sphere_on_floor("ellipsoid", f"fix w all wall/gran/ellipsoid hertz/material {E} {NU} "
                          f"{REST} tangential history {kt} {mu}", f"shear x {vshear}", z0=RADIUS,
                          vz=0.0)
    lmp.command("unfix g")    # resting on the floor without gravity: no normal force changes
    lmp.command("set atom 1 z 0.499")
    lmp.command("run 1 post no")
    f = lmp.numpy.extract_atom("f")[0].copy()
    tq = lmp.numpy.extract_atom("torque")[0].copy()
    lmp.close()
    # the tangential spring after one step: kt times the floor's slip v dt, against the slip
    # of the sphere relative to the floor (the floor moves +x under the sphere): along +x. The
    # setup force does not advance the spring, so the sphere did not move before that step
    assert f[0] == pytest.approx(kt * vshear * DT, rel=1e-12, abs=1e-15)
    assert f[1] == pytest.approx(0.0, abs=1e-12)
    # the drag at the sphere's bottom turns it about -y (torque = r x f, r pointing down)
    assert tq[1] == pytest.approx(-f[0] * (RADIUS - 0.0005), rel=1e-3, abs=1e-12)


@pytest.mark.parametrize("args, pattern", [
    ("zplane 0 NULL wiggle z 0.1", "Illegal|missing|Expected"),
    ("zplane 0 NULL wiggle q 0.1 1", "dimension must be x, y or z"),
    ("zplane 0 NULL wiggle z 0.1 0", "period must be > 0"),
    ("zplane 0 NULL shear z 0.5", "shear along z"),
    ("zplane 0 NULL shear x 0.5 wiggle z 0.1 1", "one of wiggle, shear and servo"),
    # the servo (test_wall_servo.py)
    ("zplane NULL 1.3 servo force -1 gain 0.1 vmax 1", "target force must be > 0"),
    ("zplane NULL 1.3 servo force 1 gain 0 vmax 1", "gain must be > 0"),
    ("zplane NULL 1.3 servo force 1 gain 0.1 vmax 0", "vmax must be > 0"),
    ("zplane NULL 1.3 servo pressure 1 gain 0.1 vmax 1", "expected force or stress"),
    ("zplane NULL 1.3 servo force 1 vmax 0.1 gain 1", "expected 'servo force VALUE gain G vmax V'"),
    ("zplane NULL 1.3 servo force 1 gain 0.1 vmax 1 wiggle z 0.1 1", "one of wiggle, shear and servo"),
    ("zplane 0 1.3 servo force 1 gain 0.1 vmax 1", "servo moves one wall"),
    ("zplane NULL 1.3 servo force 1 gain 0.1 vmax 1 filter -1", "filter time must be >= 0"),
    ("zplane NULL 1.3 servo stress 1 gain 0.1 vmax 1 area 0", "area must be > 0"),
    ("zplane NULL 1.3 servo force 1 gain 0.1 vmax 1 area 2", "area needs a stress target"),
    ("zplane NULL 1.3 servo stress 1 gain 0.1 vmax 1 area", "Illegal fix wall/gran/ellipsoid servo area"),
])
def test_bad_motion_is_refused(args, pattern):
    lmp = new_lammps()
    lmp.commands_string("""
        units lj
        atom_style ellipsoid
        boundary p p f
        region box block 0 4 0 4 0 6
        create_box 1 box
        """)
    with pytest.raises(Exception, match=pattern):
        lmp.command(f"fix w all wall/gran/ellipsoid hertz 1e4 10 {args}")
    lmp.close()


def test_contacts_array_as_fix_wall_gran():
    """`contacts`: fix wall/gran's per-atom array (8 columns). A sphere pressed into the floor
    by 1e-3 and one above it (no contact): the first row holds 1 (in contact), the Hertz force
    of the wall on the sphere, 4/3 E* sqrt(r) xi^1.5 along +z, the point on the wall below the
    centre and R* = r; the second row is zero. The fix's own vector (the force on the wall)
    is the negated force."""
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box("ellipsoid", (4, 4, 6),
                                              [(1.2, 1.7, RADIUS - 1e-3), (3.0, 3.0, 2.0)],
                                              RADIUS, DENSITY))
    lmp.commands_string(f"""
        fix w all wall/gran/ellipsoid hertz/material {E} {NU} {REST} zplane 0.0 NULL contacts
        run 0
        """)
    rows = np.array(lmp.numpy.extract_fix("w", 1, 2)).reshape(-1, 8)[:2].copy()
    ids = lmp.numpy.extract_atom("id")[:2].copy()
    wall = [lmp.extract_fix("w", 0, 1, k) for k in range(3)]
    lmp.close()
    touching, free = rows[ids == 1][0], rows[ids == 2][0]
    e_star = E / (2 * (1 - NU**2))
    hertz = 4 / 3 * e_star * math.sqrt(RADIUS) * 1e-3**1.5
    assert touching[0] == 1.0
    np.testing.assert_allclose(touching[1:4], [0.0, 0.0, hertz], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(touching[4:7], [1.2, 1.7, 0.0], atol=1e-12)
    assert touching[7] == pytest.approx(RADIUS, rel=1e-12)
    assert np.all(free == 0.0)
    np.testing.assert_allclose(wall, -touching[1:4], rtol=1e-12, atol=1e-15)


def test_restart_keeps_the_commands_walls_for_shear(tmp_path):
    """A shearing floor moved from z = 0 to z = -0.5 when the fix is given again after
    read_restart is at -0.5 (the restart file holds the moving walls' state; only a servo's
    position is state): the sphere resting on the old floor is free."""
    restart = tmp_path / "shear.restart"
    lmp = sphere_on_floor("ellipsoid", f"fix w all wall/gran/ellipsoid hertz/material {E} {NU} "
                          f"{REST}", "shear x 0.1", z0=0.499, vz=0.0)
    lmp.command("run 0 post no")
    resting = lmp.extract_fix("w", 0, 1, 2)
    lmp.command(f"write_restart {restart}")
    lmp.close()
    lmp = new_lammps()
    lmp.commands_string(f"""
        atom_style ellipsoid
        read_restart {restart}
        comm_modify vel yes
        fix w all wall/gran/ellipsoid hertz/material {E} {NU} {REST} zplane -0.5 NULL shear x 0.1
        run 0 post no
        """)
    moved = lmp.extract_fix("w", 0, 1, 2)
    lmp.close()
    assert resting < 0.0    # pressed down by the sphere
    assert moved == 0.0


def test_wiggle_keeps_its_phase_when_the_timestep_changes():
    """A sphere resting on a slowly wiggling floor (amplitude 0.01, period 1: its acceleration
    0.39 below gravity's 1, so it stays in contact): 2000 steps of 1e-4, then 2000 of 5e-5.
    The floor (the contact point on it, column 7 of contacts) is at A (1 - cos(omega t)) at
    the time t = 0.3, not at the phase of 4000 steps of the new timestep."""
    lmp = sphere_on_floor("ellipsoid", f"fix w all wall/gran/ellipsoid hertz/material {E} {NU} "
                          f"{REST}", "wiggle z 0.01 1.0 contacts", z0=0.499, vz=0.0)
    lmp.command("run 2000 post no")
    lmp.command(f"timestep {DT / 2}")
    lmp.command("run 2000 post no")
    row = np.array(lmp.numpy.extract_fix("w", 1, 2)[0]).copy()
    lmp.close()
    assert row[0] == 1.0
    assert row[6] == pytest.approx(0.01 * (1 - math.cos(2 * math.pi * 0.3)), rel=1e-9)
