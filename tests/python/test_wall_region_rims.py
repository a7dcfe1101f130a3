"""fix wall/gran/region/ellipsoid: a cylinder's or cone's side ends at its caps, open or closed
(LAMMPS's region cylinder and cone: the segment between them), and the rims of open ends meet
particles inside and beyond them, as LAMMPS's fix wall/gran/region does (sphere limit, with
friction: tangential history here is LAMMPS's tangential linear_history kt 0 mu).

What LAMMPS has and this fix does not: an open region is two-sided there (Region::match takes
every point): a particle outside a funnel's side touches its outer face. Here the outer face
is no wall (test_the_outer_face_of_an_open_side_is_no_wall, and the fix's doc page)."""
import numpy as np
import pytest

import scenes
import test_wall_region as base
from conftest import new_lammps

E, NU, REST, KT, MU = 1.0e5, 0.3, 0.8, 2.0e4, 0.5
OURS = f"wall/gran/region/ellipsoid hertz/material {E} {NU} {REST} tangential history {KT} {MU}"
LAMMPS = (f"wall/gran/region granular hertz/material {E} {REST} {NU} damping coeff_restitution "
          f"tangential linear_history {KT} 0 {MU}")
FRICTION = (OURS, LAMMPS)
R = base.RADIUS    # 0.2


def at(radial, angle, z, centre=(2.0, 2.0)):
    return (centre[0] + radial * np.cos(angle), centre[1] + radial * np.sin(angle), z)


def hopper_positions():
    """A hopper open at both ends (radius 0.6 at z = 0.5, 1.6 at z = 3.5): inside with the
    foot of its deepest point below the outlet (its rim), past the outlet inside and outside
    the side continued, above the open top outside and inside the side continued (the top
    rim), against the side, free."""
    return ("region r cone z 2 2 0.6 1.6 0.5 3.5 open 1 open 2",
            [at(0.45, 0.3, 0.52), at(0.5, 1.5, 0.4), at(0.72, 2.6, 0.35), at(1.65, 3.7, 3.6),
             at(1.5, 4.9, 3.6), at(1.0 - 0.17, 5.6, 1.7), (2.0, 2.0, 2.0)])


def pipe_positions():
    """A pipe (radius 1.5, z 0.5 to 3.5) open at both ends: above the top rim radially inside
    and outside it, below the bottom rim, against the side, free."""
    return ("region r cylinder z 2 2 1.5 0.5 3.5 open 1 open 2",
            [at(1.4, 0.4, 3.58), at(1.62, 2.0, 3.6), at(1.45, 4.1, 0.35), at(1.33, 5.0, 2.0),
             (2.0, 2.0, 2.0)])


def closed_hopper_positions():
    """The hopper closed: a sphere in the outlet's corner meets the bottom and the side's end
    (its rim), as LAMMPS's segment clamped to its end."""
    return ("region r cone z 2 2 0.6 1.6 0.5 3.5",
            [at(0.45, 0.3, 0.54), at(0.5, 2.0, 0.55), at(1.0 - 0.17, 5.6, 1.7),
             (2.0, 2.0, 2.0)])


@pytest.mark.parametrize("case", [hopper_positions, pipe_positions, closed_hopper_positions])
def test_rims_match_fix_wall_gran_region(case):
    region, positions = case()
    touching = base.compare(region, positions, steps=(0, 30, 30, 30))
    assert touching == len(positions) - 1    # all but the free one


@pytest.mark.parametrize("case", [hopper_positions, pipe_positions])
def test_rim_friction_matches_fix_wall_gran_region(case):
    """Friction on: after one step from rest in rotation (no tangential force at setup, so no
    spin at the step's force evaluation) the forces equal LAMMPS's, the tangential ones the
    spring's -kt v_t dt in the rim's tangent plane, and each torque is LAMMPS's times the
    lever arm's ratio: the force acts at the contact point here, |x_c - c| = r - overlap/2
    (doc/fix_wall_gran_ellipsoid.rst), LAMMPS's wall torque takes the radius r."""
    region, positions = case()
    ours = base.build("ellipsoid", region, positions, laws=(FRICTION[0] + " contacts",
                                                            FRICTION[1]))
    ref = base.build("sphere", region, positions, laws=FRICTION)
    try:
        f, f_ref = base.forces_after_one_step(ours, ref, rtol=1e-10)
        rows = np.array(ours.numpy.extract_fix("w", 1, 2)[: len(positions)], dtype=float)
        x = base.per_atom(ours, "x")
        lever = (R + np.linalg.norm(x - rows[:, 4:7], axis=1)) / (2.0 * R)    # (r - d/2)/r
        t, t_ref = base.per_atom(ours, "torque"), base.per_atom(ref, "torque")
        touching = rows[:, 0] > 0
        assert touching.sum() == len(positions) - 1
        assert np.linalg.norm(t_ref[touching], axis=1).min() > 0.0
        np.testing.assert_allclose(t[touching], t_ref[touching] * lever[touching, None],
                                   rtol=1e-9, atol=1e-9 * np.abs(t_ref).max())
    finally:
        ours.close()
        ref.close()


def drop(style, laws, steps):
    """A sphere of radius 0.75 dropped through a hopper's outlet of radius 0.8 (the cone open
    at both ends, z 2 to 6), a little off its axis, friction on; returns (z, vz, |v_xy|)
    after each run"""
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box(style, (8.0, 8.0, 8.0), [(4.02, 4.0, 6.5)], 0.75))
    lmp.commands_string(f"""
        region r cone z 4 4 0.8 3.0 2 6 open 1 open 2
        fix w all {laws[0] if style == "ellipsoid" else laws[1]} region r
        fix g all gravity 1.0 vector 0 0 -1
        fix i all {"nve/sphere" if style == "sphere" else "nve/ellipsoid"}
        timestep 1e-3
        """)
    out = []
    for n in steps:
        lmp.command(f"run {n} post no")
        x = base.per_atom(lmp, "x")[0]
        v = base.per_atom(lmp, "v")[0]
        out.append((x[2], v[2], np.hypot(v[0], v[1])))
    lmp.close()
    return np.array(out)


def test_a_particle_falls_freely_through_an_outlet_wider_than_it():
    """The side ends at the outlet: the sphere, its centre 0.02 off the axis, passes at 0.78
    from the rim and falls freely from above the hopper (z 6.5) through it and its outlet
    (z 2) to below it, as with LAMMPS's fix wall/gran/region (the side continued past the
    outlet cut it: |F| about 105 at the outlet, 70 % of its energy lost)."""
    steps = [550] * 6
    ours = drop("ellipsoid", FRICTION, steps)
    ref = drop("sphere", FRICTION, steps)
    np.testing.assert_allclose(ours, ref, rtol=0, atol=1e-10)
    t = np.cumsum(steps) * 1e-3
    np.testing.assert_allclose(ours[:, 0], 6.5 - 0.5 * t ** 2, rtol=0, atol=1e-9)
    np.testing.assert_allclose(ours[:, 1], -t, rtol=0, atol=1e-9)
    assert ours[:, 2].max() == 0.0 and ours[-1, 0] < 2.0 - 0.75


def test_the_outer_face_of_an_open_side_is_no_wall():
    """The documented difference: a sphere outside an open funnel's side, touching its outer
    face, feels it under LAMMPS's fix wall/gran/region (an open region is two-sided there) and
    not here (the particles are inside the funnel or past its open ends)."""
    region = "region r cone z 2 2 0.6 1.6 0.5 3.5 open 1 open 2"
    outside = [at(1.1 + 0.15, 0.0, 2.0)]    # the side's radius at z = 2 is 1.1
    forces = {}
    for style in ("ellipsoid", "sphere"):
        lmp = base.build(style, region, outside, laws=FRICTION)
        lmp.command("run 0 post no")
        forces[style] = np.linalg.norm(base.per_atom(lmp, "f")[0])
        lmp.close()
    assert forces["sphere"] > 0.0
    assert forces["ellipsoid"] == 0.0
