"""fix wall/gran/region/ellipsoid as a silo's floor with an orifice and as a hopper joined to a
cylinder (examples/discharge).

The floor with a hole of radius r0 is a cone region whose outlet is the hole (radius r0 at the
floor's height z0) and whose slope is k = 1e3 (its radius r0 + k (z - z0): a rise of 1 d per
1000 d, a plane to well under the contacts' overlaps), both ends open: particles on the floor
meet the cone's side, those over the hole its outlet's rim, and one centred in a hole wider
than it falls through untouched. A conical hopper below a cylinder: the two regions overlap
(the cone reaches above the junction, the cylinder below it) so that neither has a rim at the
junction, where a particle would meet one on top of the other's side.

The sphere limit is LAMMPS's fix wall/gran/region on the same regions. The flat cone is
ill-conditioned by its slope: its depth (rho - r0 - k s) cos(alpha) cancels about k times the
overlap, so the two codes' round-off differs by about k times the double precision's times
the height over the overlap; the forces agree to 1e-9 at the start (5e-10 seen) and the
trajectories to 1e-8 after 90 steps here (with k = 10 to 1e-10 and 1e-12 as the other
regions' tests)."""
import numpy as np
import pytest

import scenes
import test_wall_region as base
from conftest import new_lammps
from test_wall_region_rims import FRICTION, at

SLOPE = 1.0e3
LAW = "hertz 1e4 40 tangential history 2e3 0.5"


def floor(r0, z0=0.5, top=3.5):
    """the flat floor at z0 with a hole of radius r0 about (2, 2)"""
    return (f"region r cone z 2 2 {r0} {r0 + SLOPE * (top - z0)} {z0} {top} "
            "open 1 open 2")


def build(style, region, positions, radius, laws, shape=None, dt=1e-4, kick=False):
    """the particles at `positions` (given random velocities if kick) and the wall of `region`
    (laws: this fix's and LAMMPS's fix wall/gran/region's words)"""
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box(style, (4.0, 4.0, 4.0), positions, radius,
                                              boundary="f f f"))
    rng = np.random.default_rng(3)
    for i in range(len(positions) if kick else 0):
        lmp.command("set atom {} vx {} vy {} vz {}".format(i + 1, *rng.normal(0.0, 0.3, 3)))
    if shape:
        lmp.command("set type 1 shape {} {} {}".format(*shape))
    lmp.commands_string(f"""
        {region}
        fix w all {laws[0] if style == "ellipsoid" else laws[1]} region r
        fix i all {"nve/sphere" if style == "sphere" else "nve/ellipsoid"}
        timestep {dt}
        """)
    return lmp


def floor_positions(r0, z0):
    """spheres of radius 0.2 on the floor, on the hole's rim from over the hole, on the floor
    beside the rim, near the hole's middle (free) and in the hole (free)"""
    return [at(1.3, 0.3, z0 + 0.19), at(r0 - 0.1, 1.5, z0 + np.sqrt(0.19**2 - 0.01)),
            at(r0 + 0.05, 2.5, z0 + 0.195), at(0.1, 4.0, z0 + 0.02), at(0.2, 5.0, z0 - 0.2)]


def test_floor_with_a_hole_matches_fix_wall_gran_region():
    """The spheres given velocities, frictionless: the forces, torques and positions equal
    LAMMPS's over 90 steps."""
    positions = floor_positions(0.6, 0.5)
    ours, ref = (build(s, floor(0.6), positions, base.RADIUS, (base.OURS, base.LAMMPS),
                       kick=True) for s in ("ellipsoid", "sphere"))
    try:
        for n, tol in ((0, 1e-9), (30, 1e-8), (30, 1e-8), (30, 1e-8)):
            for lmp in (ours, ref):
                lmp.command(f"run {n} post no")
            f, f_ref = base.per_atom(ours, "f"), base.per_atom(ref, "f")
            scale = np.abs(f_ref).max()
            np.testing.assert_allclose(f, f_ref, rtol=tol, atol=tol * scale)
            np.testing.assert_allclose(base.per_atom(ours, "torque"),
                                       base.per_atom(ref, "torque"), rtol=tol, atol=tol * scale)
            np.testing.assert_allclose(base.per_atom(ours, "x"), base.per_atom(ref, "x"),
                                       rtol=tol)
            if n == 0:
                assert (np.abs(f).sum(axis=1) > 0).tolist() == [True] * 3 + [False] * 2
    finally:
        ours.close()
        ref.close()


def test_floor_with_a_hole_friction_matches_fix_wall_gran_region():
    """With friction (tangential history here, LAMMPS's linear_history): the forces after
    one step from rest in rotation equal LAMMPS's (the torques' levers differ:
    test_wall_region_rims.py)."""
    positions = floor_positions(0.6, 0.5)
    ours, ref = (build(s, floor(0.6), positions, base.RADIUS, FRICTION, kick=True)
                 for s in ("ellipsoid", "sphere"))
    try:
        f, f_ref = base.forces_after_one_step(ours, ref, rtol=1e-9)
        tangential = np.hypot(f[:3, 0], f[:3, 1])
        assert tangential.min() > 0.0
    finally:
        ours.close()
        ref.close()


def drop(r0, radius, start, steps, z0=0.5):
    """a sphere dropped from rest at `start` onto the floor with a hole of radius r0 under
    g = 1 (the law hertz 1e4 40, damped); its positions, velocities and the floor's vertical
    force after each run"""
    lmp = build("ellipsoid", floor(r0, z0), [start], radius,
                (f"wall/gran/region/ellipsoid {LAW}",), dt=2e-4)
    lmp.command("fix g all gravity 1.0 vector 0 0 -1")
    out = []
    for n in steps:
        lmp.command(f"run {n} post no")
        out.append((base.per_atom(lmp, "x")[0], base.per_atom(lmp, "v")[0],
                    lmp.extract_fix("w", 0, 1, 2)))
    mass = 4.0 / 3.0 * np.pi * radius**3
    lmp.close()
    return out, mass


def test_a_sphere_falls_through_a_hole_wider_than_it():
    """A sphere of radius 0.5 dropped from z = 2.9, 0.05 off the axis of a hole of radius
    0.6 (the floor at 1.5), falls freely through it: z = 2.9 - t^2 / 2, no force, to below
    the floor."""
    steps = [1000] * 10
    out, _ = drop(0.6, 0.5, at(0.05, 0.7, 2.9), steps, z0=1.5)
    t = np.cumsum(steps) * 2e-4
    z = np.array([o[0][2] for o in out])
    np.testing.assert_allclose(z, 2.9 - 0.5 * t**2, rtol=0, atol=1e-9)
    assert max(abs(o[2]) for o in out) == 0.0 and z[-1] < 1.5 - 0.5


def test_a_sphere_rests_on_the_rim_of_a_hole_narrower_than_it():
    """A sphere of radius 0.5 placed at rest on the middle of a hole of radius 0.3 (the floor
    at 0.5) rests on its rim: its centre stays on the axis sqrt(0.5^2 - 0.3^2) = 0.4 above the
    floor, less the overlap, and the floor carries its weight. (The rim gives one contact, at
    its deepest point: on the axis every rim point is, so the contact's angle flips from step
    to step and the sphere jitters by 1e-6 about the axis.)"""
    out, mass = drop(0.3, 0.5, (2.0, 2.0, 0.5 + 0.4 - 0.002), [10000] * 6)
    for x, v, fz in out:
        assert 0.5 + 0.4 - 0.005 < x[2] < 0.5 + 0.4 and np.hypot(x[0] - 2, x[1] - 2) < 1e-5
        assert np.linalg.norm(v) < 2e-3
    assert out[-1][2] == pytest.approx(-mass, rel=1e-3)


def test_an_ellipsoid_on_the_floor_meets_its_tangent_plane():
    """An ellipsoid of the paper's Fig. 4 shape (eta 1.4, zeta 1.8: diameters 1.52, 1.09,
    0.60) dropped flat onto the floor 1.2 from the axis of a hole of radius 0.3 (its long
    axis radial) moves as on the floor's tangent plane there (a region plane through the
    floor at that radius, rising 1 in k outwards), to 1e-10, and lands (its centre within
    0.01 of its smallest semi-axis above the floor). On the slope the law's undamped
    tangential spring rocks it by about 3e-3 d; on a level plane it comes to rest."""
    normal = np.array([-1.0, SLOPE]) / np.hypot(1.0, SLOPE)
    tangent = "region r plane 3.2 2.0 {} {} 0.0 {}".format(0.5 + 0.9 / SLOPE, *normal)
    runs = []
    for region in (floor(0.3), tangent):
        lmp = build("ellipsoid", region, [(3.2, 2.0, 1.0)], 0.5,
                    (f"wall/gran/region/ellipsoid {LAW}",), shape=(1.5232, 1.0880, 0.6044),
                    dt=2e-4)
        lmp.command("fix g all gravity 1.0 vector 0 0 -1")
        path = []
        for _ in range(6):
            lmp.command("run 10000 post no")
            path.append(np.concatenate([base.per_atom(lmp, name)[0] for name in ("x", "v",
                                                                                "angmom")]))
        lmp.close()
        runs.append(np.array(path))
    np.testing.assert_allclose(runs[0], runs[1], rtol=0, atol=1e-10)
    assert abs(runs[0][-1, 2] - (0.5 + 0.9 / SLOPE + 0.3022)) < 0.01


def hopper_positions():
    """A hopper (outlet radius 0.5 at z = 0.5, radius 1.5 at the junction z = 2) below a
    cylinder of radius 1.5 (z 2 up): the cone reaches on to z = 2.5 (radius 1.83), the
    cylinder down to z = 1.5, so each one's rim there lies 0.28 beyond the other's side, out
    of a sphere of radius 0.2's reach; spheres at the junction touching both, on the cone
    below it, on the cylinder above it, free."""
    regions = ("region r cone z 2 2 0.5 1.833333333333 0.5 2.5 open 1 open 2",
               "region c cylinder z 2 2 1.5 1.5 3.8 open 1 open 2")
    return regions, [at(1.305, 0.4, 2.05), at(0.87, 1.9, 1.4), at(1.31, 3.3, 2.6),
                     (2.0, 2.0, 2.8)]


def hopper(style, laws):
    (cone, cylinder), positions = hopper_positions()
    lmp = build(style, cone, positions, base.RADIUS, laws, kick=True)
    lmp.commands_string(f"""{cylinder}
        fix wc all {laws[0] if style == "ellipsoid" else laws[1]} region c""")
    return lmp


def test_a_hopper_joined_to_a_cylinder_matches_fix_wall_gran_region():
    """Frictionless: the forces and positions equal LAMMPS's over 90 steps, the sphere at
    the junction touching both walls at the start."""
    ours, ref = (hopper(style, (base.OURS, base.LAMMPS)) for style in ("ellipsoid", "sphere"))
    try:
        for n in (0, 30, 30, 30):
            for lmp in (ours, ref):
                lmp.command(f"run {n} post no")
            f, f_ref = base.per_atom(ours, "f"), base.per_atom(ref, "f")
            scale = np.abs(f_ref).max()
            np.testing.assert_allclose(f, f_ref, rtol=1e-10, atol=1e-10 * scale)
            np.testing.assert_allclose(base.per_atom(ours, "x"), base.per_atom(ref, "x"),
                                       rtol=1e-12)
            if n == 0:
                assert (np.abs(f).sum(axis=1) > 0).tolist() == [True] * 3 + [False]
                assert all(np.hypot(ours.extract_fix(w, 0, 1, 0), ours.extract_fix(w, 0, 1, 1))
                           > 0 for w in ("w", "wc"))
    finally:
        ours.close()
        ref.close()


def test_a_hopper_joined_to_a_cylinder_with_friction_matches_fix_wall_gran_region():
    """With friction: the forces after one step equal LAMMPS's (as the floor's)."""
    ours, ref = hopper("ellipsoid", FRICTION), hopper("sphere", FRICTION)
    try:
        base.forces_after_one_step(ours, ref, rtol=1e-10)
    finally:
        ours.close()
        ref.close()
