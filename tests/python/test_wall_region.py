"""fix wall/gran/region/ellipsoid against LAMMPS's fix wall/gran/region (sphere limit).

Spheres placed against a region's faces (side, caps, edges and corners inside the region;
a ball, a post, a block's faces, edges and corners and a capped post's side, caps and rims
from outside; one sphere whose centre the region does not match, one free) get the forces
and torques of LAMMPS's
fix wall/gran/region with the same region and the mapped law: hertz/material E nu e here is
LAMMPS's `granular hertz/material E e nu damping coeff_restitution tangential
linear_nohistory 0 0` (doc/pair_granular_ellipsoid.rst). The wall's contact radius is
LAMMPS's (a cylinder's side -2R, a sphere's -R; from outside a block's flat everywhere, a
cylinder's 2R at its side and rims, flat on its caps), so R* and with it the Hertz stiffness and
damping agree. A moving region (move by a variable) gives the wall's velocity to the damping
as LAMMPS's does: trajectories agree step for step.
"""
import math

import numpy as np
import pytest

import scenes
from conftest import new_lammps

E, NU, REST = 1.0e5, 0.3, 0.8
RADIUS = 0.2
BOX = (4.0, 4.0, 4.0)
OURS = f"wall/gran/region/ellipsoid hertz/material {E} {NU} {REST}"
LAMMPS = (f"wall/gran/region granular hertz/material {E} {REST} {NU} damping coeff_restitution "
          "tangential linear_nohistory 0 0")


def cylinder_positions():
    """Against the side (at three angles), the bottom cap, the top cap, the side and the
    bottom at once, a free sphere and one with its centre outside the region."""
    c, big, lo, hi = 2.0, 1.5, 0.5, 3.5
    pos = []
    for k, angle in enumerate((0.3, 2.0, 4.4)):
        rho = big - RADIUS + 0.004 * (k + 1)
        pos.append((c + rho * math.cos(angle), c + rho * math.sin(angle), 2.0))
    pos += [(2.3, 1.8, lo + RADIUS - 0.006), (1.7, 2.2, hi - RADIUS + 0.003),
            (c + big - RADIUS + 0.005, c, lo + RADIUS - 0.002), (2.0, 2.0, 2.0),
            (c + big + 0.1, c, 2.0)]
    return "region r cylinder z 2 2 1.5 0.5 3.5", pos


def block_positions():
    """Against each face, along an edge, in a corner, free, and outside."""
    lo, hi = 0.5, 3.5
    d = RADIUS - 0.005
    pos = [(lo + d, 2.0, 2.1), (hi - d, 1.9, 2.0), (2.2, lo + d, 1.8), (1.8, hi - d, 2.2),
           (2.0, 2.1, lo + d + 0.002), (2.1, 2.0, hi - d), (lo + d, lo + d + 0.001, 2.0),
           (hi - d, hi - d, hi - d - 0.002), (2.0, 2.0, 2.0), (0.2, 2.0, 2.0)]
    return "region r block 0.5 3.5 0.5 3.5 0.5 3.5", pos


def sphere_positions():
    """Against the spherical wall in several directions, free, and outside."""
    rng = np.random.default_rng(7)
    pos = []
    for k in range(6):
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        pos.append(tuple(2.0 + (1.5 - RADIUS + 0.002 * (k + 1)) * u))
    pos += [(2.0, 2.0, 2.0), (2.0, 2.0, 3.8)]
    return "region r sphere 2 2 2 1.5", pos


def cone_positions():
    """A hopper (radius 0.6 at the bottom z = 0.5, 1.6 at the top z = 3.5): against the side
    at several angles and heights, the bottom, free, and outside."""
    lo, hi, rlo, rhi = 0.5, 3.5, 0.6, 1.6
    slope = (rhi - rlo) / (hi - lo)
    norm = math.hypot(1.0, slope)
    pos = []
    for k, (angle, z) in enumerate(((0.4, 1.5), (2.1, 2.2), (3.9, 2.9), (5.2, 1.1))):
        er = np.array([math.cos(angle), math.sin(angle), 0.0])
        side = np.array([2.0, 2.0, z]) + (rlo + slope * (z - lo)) * er
        inward = (slope * np.array([0.0, 0.0, 1.0]) - er) / norm
        pos.append(tuple(side + (RADIUS - 0.003 * (k + 1)) * inward))
    pos += [(2.05, 1.95, lo + RADIUS - 0.004), (2.0, 2.0, 2.5), (2.0, 2.0, 3.8)]
    return "region r cone z 2 2 0.6 1.6 0.5 3.5", pos


def outside_positions(shape):
    """Around a ball (radius 1) or a post (an infinite z cylinder, radius 0.8) from outside:
    touching at several directions, one free, and one centre inside the solid (left alone)."""
    rng = np.random.default_rng(11)
    pos = []
    for k in range(6):
        u = rng.normal(size=3)
        if shape == "post":
            u[2] = 0.0
        u /= np.linalg.norm(u)
        big = 1.0 if shape == "ball" else 0.8
        p = np.array([2.0, 2.0, 2.0 + (0.3 * k - 0.75 if shape == "post" else 0.0)])
        pos.append(tuple(p + (big + RADIUS - 0.002 * (k + 1)) * u))
    pos += [(3.6, 3.6, 3.6), (2.0, 2.1, 2.0)]
    region = ("region r sphere 2 2 2 1.0 side out" if shape == "ball"
              else "region r cylinder z 2 2 0.8 INF INF side out")
    return region, pos


def block_outside_positions():
    """Around a block (1.2 to 2.8 in x, y, z) from outside: against a face, along edges, at
    corners, one free, and one centre inside the solid (left alone)."""
    lo, hi, d = 1.2, 2.8, RADIUS - 0.006
    diagonal = d / math.sqrt(2.0)
    corner = d / math.sqrt(3.0)
    pos = [(hi + d, 2.0, 2.1), (hi + diagonal, hi + diagonal + 0.002, 2.0),
           (lo - diagonal, 1.9, hi + diagonal - 0.001), (2.3, lo - diagonal, lo - diagonal),
           (lo - corner, lo - corner, lo - corner + 0.001), (hi + corner, lo - corner, hi + corner),
           (3.6, 3.6, 3.6), (2.0, 2.1, 2.0)]
    return "region r block 1.2 2.8 1.2 2.8 1.2 2.8 side out", pos


def capped_post_positions():
    """Around a post (a z cylinder, radius 0.8, capped at z = 1 and 3) from outside: its side,
    its caps, its rims at several tilts, one free, and one centre inside the solid."""
    c, big, lo, hi, d = 2.0, 0.8, 1.0, 3.0, RADIUS - 0.005
    pos = [(c + big + d, c, 2.0), (2.1, 1.9, hi + d), (1.8, 2.2, lo - d)]
    for k, (angle, tilt) in enumerate(((0.4, 0.3), (2.2, 0.8), (3.9, 1.2), (5.3, 0.6))):
        up = 1.0 if k % 2 == 0 else -1.0
        rim = np.array([c + big * math.cos(angle), c + big * math.sin(angle),
                        hi if up > 0 else lo])
        out = np.array([math.sin(tilt) * math.cos(angle), math.sin(tilt) * math.sin(angle),
                        up * math.cos(tilt)])
        pos.append(tuple(rim + (d - 0.002 * k) * out))
    pos += [(3.6, 3.6, 3.6), (2.0, 2.1, 2.0)]
    return "region r cylinder z 2 2 0.8 1.0 3.0 side out", pos


def ball_positions():
    return outside_positions("ball")


def post_positions():
    return outside_positions("post")


def build(style, region, positions, extra="", laws=(OURS, LAMMPS)):
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box(style, BOX, positions, RADIUS))
    rng = np.random.default_rng(3)
    for i in range(len(positions)):
        v = rng.normal(0.0, 0.3, 3)
        lmp.command(f"set atom {i + 1} vx {v[0]} vy {v[1]} vz {v[2]}")
    lmp.commands_string(f"""
        {extra}
        {region}
        fix w all {laws[0] if style == "ellipsoid" else laws[1]} region r
        fix i all {"nve/sphere" if style == "sphere" else "nve/ellipsoid"}
        timestep 1e-4
        """)
    return lmp


def per_atom(lmp, name):
    return np.array(lmp.numpy.extract_atom(name)[: lmp.get_natoms()], dtype=float).copy()


def forces_after_one_step(ours, ref, rtol=1e-10):
    """run 0 and one step on both; their forces agree to rtol (of the largest); returns both"""
    for lmp in (ours, ref):
        lmp.command("run 0 post no")
        lmp.command("run 1 post no")
    f, f_ref = per_atom(ours, "f"), per_atom(ref, "f")
    np.testing.assert_allclose(f, f_ref, rtol=rtol, atol=rtol * np.abs(f_ref).max())
    return f, f_ref


def compare(region, positions, extra="", steps=(0, 20, 20, 20), laws=(OURS, LAMMPS)):
    """Forces, torques and positions after each run of `steps` (run 0: the placed spheres);
    returns the largest number of spheres touching a wall at once."""
    ours = build("ellipsoid", region, positions, extra, laws)
    ref = build("sphere", region, positions, extra, laws)
    try:
        touching, scale = 0, 0.0
        for n in steps:
            for lmp in (ours, ref):
                lmp.command(f"run {n} post no")
            f, f_ref = per_atom(ours, "f"), per_atom(ref, "f")
            scale = max(scale, np.abs(f_ref).max())    # the first step's forces: contacts
            assert scale > 0.0
            np.testing.assert_allclose(f, f_ref, rtol=1e-10, atol=1e-10 * scale)
            np.testing.assert_allclose(per_atom(ours, "torque"), per_atom(ref, "torque"),
                                       rtol=1e-10, atol=1e-10 * scale)
            np.testing.assert_allclose(per_atom(ours, "x"), per_atom(ref, "x"), rtol=1e-12)
            touching = max(touching, int((np.abs(f).sum(axis=1) > 0).sum()))
        return touching
    finally:
        ours.close()
        ref.close()


@pytest.mark.parametrize("case", [cylinder_positions, block_positions, sphere_positions,
                                  cone_positions, ball_positions, post_positions,
                                  block_outside_positions, capped_post_positions])
def test_resting_region_matches_fix_wall_gran_region(case):
    region, positions = case()
    touching = compare(region, positions)
    # every sphere but the free one and the one outside touches a wall
    assert touching == len(positions) - 2


def test_moving_region_matches_fix_wall_gran_region():
    """A cylinder moving along x by a variable (its velocity by LAMMPS's finite difference)."""
    region, positions = cylinder_positions()
    touching = compare(region + " move v_dx NULL NULL", positions,
                       extra="variable dx equal 0.5*time", steps=(0, 50, 50, 50))
    assert touching >= 3


def test_rotating_block_outside_matches_fix_wall_gran_region():
    """A block met from outside turning about z (its faces, edges and corners placed by the
    region's rotation at every step, their velocity omega x r)."""
    region, positions = block_outside_positions()
    touching = compare(region + " rotate v_theta 2 2 2 0 0 1", positions,
                       extra="variable theta equal 2.0*time", steps=(0, 50, 50, 50))
    assert touching >= 4
