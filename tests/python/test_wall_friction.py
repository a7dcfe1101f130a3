"""Friction at walls against LAMMPS (sphere limit): fix wall/gran/ellipsoid and
fix wall/gran/region/ellipsoid with `tangential history kt mu` against LAMMPS's fix wall/gran
and fix wall/gran/region with `tangential linear_history kt 0 mu limit_damping`.

The two codes differ in one convention (doc/fix_wall_gran_ellipsoid.rst, "Force"): this
package takes the particle's velocity and applies the force at the contact point, half the
overlap inside the surface, at distance rho = R - xi/2 from the centre, while LAMMPS takes
both at the full radius R for a wall. The friction laws are otherwise the same law (the
tangential spring turned with the contact, the Coulomb limit mu max(F_n, 0), which is LAMMPS's
mu |F_n| under limit_damping). So the tests

* integrate translation only (fix nve: omega stays 0, and with it the tangential velocities
  of the two codes are equal): forces equal to round-off for whole trajectories of spheres
  falling, sliding, sticking and bouncing in resting, moving and rotating regions and on
  shearing and wiggling floors, and torques in the ratio rho / R contact by contact;
* check the rotating particle's first step against the law in closed form (F_t = -kt (v -
  omega x rho n) dt at the contact point);
* compare `rolling sds` (no tangential force: the rolling torque needs no lever arm) with
  full rotation, step for step.
"""
import numpy as np
import pytest

import scenes
import test_wall_region as regions
from test_wall_region import per_atom
from conftest import new_lammps

E, NU, REST = regions.E, regions.NU, regions.REST
RADIUS = regions.RADIUS
KT, MU = 2.0e3, 0.5
OURS = f"hertz/material {E} {NU} {REST} tangential history {KT} {MU} limit_damping"
LAMMPS = (f"granular hertz/material {E} {REST} {NU} damping coeff_restitution "
          f"tangential linear_history {KT} 0 {MU} limit_damping")
DT = 1e-4


def build(style, wall_words, positions, extra="", spin=None, seed=3):
    """Spheres with random velocities under gravity; wall_words = (ours, LAMMPS's). Without
    spin, translation only (fix nve); with spin (one omega per sphere), full rotation."""
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box(style, regions.BOX, positions, RADIUS))
    rng = np.random.default_rng(seed)
    inertia = 0.4 * (4.0 / 3.0 * np.pi * RADIUS ** 3) * RADIUS ** 2
    for i in range(len(positions)):
        v = rng.normal(0.0, 0.5, 3)
        lmp.command(f"set atom {i + 1} vx {v[0]} vy {v[1]} vz {v[2]}")
        if spin is not None:    # the sphere style holds omega, the ellipsoid one L = I omega
            w = spin[i] if style == "sphere" else inertia * np.asarray(spin[i])
            lmp.command("set atom {} {} {} {} {}".format(
                i + 1, "omega" if style == "sphere" else "angmom", *w))
    integrate = "nve"
    if spin is not None:
        integrate = "nve/sphere" if style == "sphere" else "nve/ellipsoid"
    lmp.commands_string(f"""
        {extra}
        fix g all gravity 1.0 vector 0 0 -1
        fix w all {wall_words[0] if style == "ellipsoid" else wall_words[1]}
        fix i all {integrate}
        timestep {DT}
        """)
    return lmp


def compare(wall_words, positions, extra="", steps=(1, 50, 500, 1500), spin=None,
            torque_check=None):
    """Forces and positions of the two codes after each run of `steps` (torques by
    torque_check, or equal with spin); returns the largest lateral force seen and the largest
    number of spheres touching at once"""
    ours = build("ellipsoid", wall_words, positions, extra, spin)
    ref = build("sphere", wall_words, positions, extra, spin)
    try:
        friction, touching = 0.0, 0
        for n in steps:
            for lmp in (ours, ref):
                lmp.command(f"run {n} post no")
            f, f_ref = per_atom(ours, "f"), per_atom(ref, "f")
            scale = np.abs(f_ref).max()
            np.testing.assert_allclose(f, f_ref, rtol=1e-9, atol=1e-9 * scale)
            # LAMMPS turns the spring onto the tangent plane only when its normal part exceeds
            # 1e-10 of the Coulomb force (EPSILON in gran_sub_mod_tangential.cpp), this package
            # always: differences of that size, compounded over the trajectory
            np.testing.assert_allclose(per_atom(ours, "x"), per_atom(ref, "x"), rtol=1e-8)
            lateral = np.hypot(f_ref[:, 0], f_ref[:, 1])
            friction = max(friction, lateral.max())
            t, t_ref = per_atom(ours, "torque"), per_atom(ref, "torque")
            if torque_check is not None:
                torque_check(per_atom(ours, "x"), t, t_ref)
            if spin is not None:
                np.testing.assert_allclose(t, t_ref, rtol=1e-9, atol=1e-9 * np.abs(t_ref).max())
            touching = max(touching, int((np.abs(f_ref).sum(axis=1) > 0).sum()))
        return friction, touching
    finally:
        ours.close()
        ref.close()


REGION_WORDS = (f"wall/gran/region/ellipsoid {OURS} region r",
                f"wall/gran/region {LAMMPS} region r")


def floor_torques(checked):
    """On the floor z = 0.5 of the block: the torque ratio is rho / R = 1 - xi / 2R. Appends
    the number of floor contacts checked to `checked`."""
    def check(x, t, t_ref):
        depth = x[:, 2] - 0.5
        on_floor = (depth < RADIUS) & (np.abs(t_ref).max(axis=1) > 0)
        ratio = 1.0 - (RADIUS - depth) / (2.0 * RADIUS)
        np.testing.assert_allclose(t[on_floor], t_ref[on_floor] * ratio[on_floor, None],
                                   rtol=1e-8, atol=1e-12)
        checked.append(int(on_floor.sum()))
    return check


def test_floor_friction_equals_lammps_forces_and_lever_ratio():
    """Spheres on a block's floor, away from its sides, with random velocities: they slide,
    stick, bounce and rest."""
    region, _ = regions.block_positions()
    floor = [(1.0 + 0.45 * k, 1.2 + 0.35 * (k % 3), 0.5 + RADIUS - 0.002) for k in range(6)]
    checked = []
    friction, touching = compare(REGION_WORDS, floor, extra=region,
                                 torque_check=floor_torques(checked))
    assert touching == 6
    assert sum(checked) >= 6
    assert friction > 1e-3    # the friction acted (the spheres start sliding)


@pytest.mark.parametrize("case, motion", [
    (regions.cylinder_positions, ""),
    (regions.cone_positions, ""),
    (regions.sphere_positions, ""),
    (regions.cylinder_positions, " move v_dx NULL NULL"),
    (regions.block_outside_positions, " rotate v_theta 2 2 2 0 0 1"),
    (regions.capped_post_positions, " rotate v_theta 2 2 2 0 0 1"),
])
def test_region_friction_equals_lammps(case, motion):
    """Faces, edges, rims, inside and outside, resting, moving and turning regions: the friction
    force of each contact equals LAMMPS's along the whole trajectory."""
    region, positions = case()
    extra = "variable dx equal 0.5*time\nvariable theta equal 2.0*time\n" + region + motion
    friction, touching = compare(REGION_WORDS, positions, extra=extra)
    assert touching >= 3
    assert friction > 1e-3


@pytest.mark.parametrize("motion", ["", "shear x 0.3", "wiggle z 0.02 0.01", "shear y -0.2"])
def test_plane_wall_friction_equals_fix_wall_gran(motion):
    """Spheres sliding on a resting, shearing and wiggling floor and against side walls."""
    positions = [(1.0 + 0.5 * k, 1.0 + 0.3 * k, RADIUS + 0.01 * k) for k in range(5)]
    words = (f"wall/gran/ellipsoid {OURS} zplane 0.0 NULL {motion}",
             f"wall/gran {LAMMPS} zplane 0.0 NULL {motion}")
    friction, touching = compare(words, positions)
    assert touching == 5
    assert friction > 1e-3


def test_spinning_sphere_first_step_is_the_law_at_the_contact_point():
    """A spinning sphere on the floor: after one step the tangential force is -kt (v_c) dt with
    v_c the velocity of the material point at rho = R - xi/2 below the centre."""
    z0 = RADIUS - 0.004
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box("ellipsoid", (4, 4, 4), [(2.0, 2.0, z0)], RADIUS))
    v, omega = np.array([0.3, -0.1, 0.0]), np.array([0.7, 1.3, -0.4])
    lmp.commands_string(f"""
        velocity all set {v[0]} {v[1]} {v[2]}
        fix w all wall/gran/ellipsoid {OURS} zplane 0.0 NULL
        fix i all nve/ellipsoid
        timestep {DT}
        """)
    # nve/ellipsoid reads the angular momentum: for a sphere L = I omega
    mass = 4.0 / 3.0 * np.pi * RADIUS ** 3
    angmom = 0.4 * mass * RADIUS ** 2 * omega
    lmp.command("set atom 1 angmom {} {} {}".format(*angmom))
    # LAMMPS's walls do not advance the history at a run's set-up: the first step does, with
    # the half-step velocities, which the set-up's normal force leaves unchanged along the
    # floor (and the spin: no torque without friction)
    lmp.command("run 1 post no")
    f0 = per_atom(lmp, "f")[0]
    z1 = per_atom(lmp, "x")[0][2]
    lmp.close()
    xi = RADIUS - z1
    n = np.array([0.0, 0.0, -1.0])                 # from the centre to the wall
    rho = RADIUS - xi / 2.0
    v_c = v + np.cross(omega, rho * n)
    v_t = v_c - v_c.dot(n) * n
    expected = -KT * v_t * DT
    assert np.linalg.norm(expected) < MU * abs(f0[2])   # in the spring's range, not sliding
    np.testing.assert_allclose(f0[:2], expected[:2], rtol=1e-10, atol=1e-14)
    # LAMMPS's lever R instead of rho would differ by more than the tolerance
    assert abs(np.cross(omega, xi / 2.0 * n)[0] * KT * DT) > 1e3 * 1e-10 * abs(expected[0])


def test_rolling_sds_on_walls_equals_lammps_with_rotation():
    """rolling sds without tangential force, spinning spheres on a floor: the rolling torque
    (lever R*, no contact point) matches LAMMPS's step for step, forces and torques."""
    kr, gr, mur = 50.0, 0.5, 0.3
    region, _ = regions.block_positions()
    floor = [(1.0 + 0.45 * k, 1.2 + 0.35 * (k % 3), 0.5 + RADIUS - 0.003) for k in range(6)]
    spin = [(0.5 * i - 1.0, 1.0 - 0.3 * i, 0.2) for i in range(6)]
    words = (f"wall/gran/region/ellipsoid hertz/material {E} {NU} {REST} "
             f"rolling sds {kr} {gr} {mur} limit_damping region r",
             f"wall/gran/region granular hertz/material {E} {REST} {NU} damping "
             f"coeff_restitution tangential linear_nohistory 0 0 rolling sds {kr} {gr} {mur} "
             "limit_damping region r")
    _, touching = compare(words, floor, extra=region, spin=spin)
    assert touching >= 6
