"""The dashpot of the tangential spring, `tangential history kt mu xt X`, against LAMMPS's
`tangential linear_history kt xt mu` (sphere limit): F_t = -kt s - xt gamma_n v_t, gamma_n the
normal damping (here hertz/material's restitution damping, LAMMPS's damping coeff_restitution),
capped at mu F_n with the spring keeping what the dashpot leaves. Pair, plane wall and region
wall; the time-step rule's tangential damping time; a restart that keeps xt, and one of the
previous version (16 law values, without xt) that still reads. Both laws have
limit_damping: without it LAMMPS caps the friction at mu |F_n| also when the damped normal
force pulls at the end of an impact, this package at mu max(F_n, 0) (the doc's difference).

LAMMPS takes the spin's part of the tangential velocity with the full radius, this package at
the contact point (r - overlap/2). Here nothing spins: the spheres move under fix nve, which
leaves omega (angmom) at zero, so both see the same v_t at every step and the comparison runs
through whole oblique impacts, sticking and sliding, step for step. The pair's torques use
r - overlap/2 in both; a wall's torque takes r in LAMMPS (doc/fix_wall_gran_ellipsoid.rst), so
for walls the forces and positions are compared.
"""
import os

import numpy as np
import pytest

import scenes
from conftest import new_lammps

E, NU, REST, KT, MU = 1.0e5, 0.3, 0.8, 2.0e4, 0.5
RADIUS, BOX = 0.5, (6.0, 6.0, 6.0)


def ours(xt):
    return f"hertz/material {E} {NU} {REST} tangential history {KT} {MU} xt {xt} limit_damping"


def lammps_law(xt):
    return (f"hertz/material {E} {REST} {NU} damping coeff_restitution "
            f"tangential linear_history {KT} {xt} {MU} limit_damping")


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def pairs():
    """Two pairs, each just apart and closing: (a) mostly head-on with some sliding speed, it
    sticks after a while; (b) a grazing one, sliding at the Coulomb limit through most of it.
    Positions and velocities per sphere."""
    pos, vel = [], []
    for centre, n, t, vn, vt in [((2.0, 2.0, 3.0), unit((1, 0, 0)), (0, 1, 0), 0.5, 0.3),
                                 ((4.0, 4.2, 3.0), unit((1, 1, 0.3)), unit((0.3, 0.0, -1)),
                                  0.15, 1.5)]:
        c, half = np.array(centre), (RADIUS + 0.001) * n
        pos += [c - half, c + half]
        v = vn * n + vt * np.asarray(t)
        vel += [v, -v]
    return pos, vel


def wall_spheres():
    """A sphere landing on the floor at a shallow angle (it slides) and one dropping nearly
    straight (it sticks)."""
    return ([(2.0, 2.0, RADIUS + 0.003), (4.0, 4.0, RADIUS + 0.002)],
            [(1.2, 0.4, -0.3), (0.05, -0.03, -0.4)])


def build(style, positions, velocities, lines):
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box(style, BOX, positions, RADIUS))
    for i, v in enumerate(velocities):
        lmp.command("set atom {} vx {!r} vy {!r} vz {!r}".format(i + 1, *map(float, v)))
    lmp.commands_string(lines + "\nfix i all nve\ntimestep 1e-4\n")
    return lmp


def per_atom(lmp, name):
    return np.array(lmp.numpy.extract_atom(name)[: lmp.get_natoms()], dtype=float).copy()


def trajectories(scene, lines, steps=(0,) + (10,) * 60):
    """forces, torques, positions after each run of `steps` for the two styles' lines"""
    out = {}
    for style in ("ellipsoid", "sphere"):
        lmp = build(style, *scene, lines[style])
        rows = []
        for n in steps:
            lmp.command(f"run {n} post no")
            rows.append((per_atom(lmp, "f"), per_atom(lmp, "torque"), per_atom(lmp, "x")))
        lmp.close()
        out[style] = [np.array(r) for r in zip(*rows)]
    return out["ellipsoid"], out["sphere"]


def pair_lines(xt):
    return {"ellipsoid": f"pair_style granular/ellipsoid\npair_coeff * * {ours(xt)}",
            "sphere": f"pair_style granular\npair_coeff * * {lammps_law(xt)}"}


def wall_lines(xt, region):
    if region:
        return {"ellipsoid": "region r cylinder z 3 3 2.9 0 6\n"
                f"fix w all wall/gran/region/ellipsoid {ours(xt)} region r",
                "sphere": "region r cylinder z 3 3 2.9 0 6\n"
                f"fix w all wall/gran/region granular {lammps_law(xt)} region r"}
    return {"ellipsoid": f"fix w all wall/gran/ellipsoid {ours(xt)} zplane 0 NULL",
            "sphere": f"fix w all wall/gran granular {lammps_law(xt)} zplane 0 NULL"}


def friction_ratios(f, x, partner):
    """|F_t| / (mu F_n) of each atom's one contact at every sample where it pushes; partner:
    the other atom's index per atom, or None for a floor below"""
    ratios = []
    for a in range(f.shape[1]):
        n = x[:, partner[a]] - x[:, a] if partner else np.tile([0.0, 0.0, -1.0], (len(f), 1))
        n /= np.linalg.norm(n, axis=1)[:, None]
        fn = -(f[:, a] * n).sum(axis=1)
        ft = np.linalg.norm(f[:, a] + fn[:, None] * n, axis=1)
        ratios += list(ft[fn > 0] / (MU * fn[fn > 0]))
    return np.array(ratios)


def assert_sticks_and_slides(ratios):
    """the impacts pass through both regimes of the law: at the Coulomb limit and below it"""
    assert (ratios > 1 - 1e-9).sum() >= 3 and (ratios < 0.9).sum() >= 3


def assert_close(a, b, scale):
    np.testing.assert_allclose(a, b, rtol=1e-10, atol=1e-10 * scale)


@pytest.mark.parametrize("xt", [0.5, 2.0])
def test_pair_matches_linear_history(xt):
    (f, t, x), (f_ref, t_ref, x_ref) = trajectories(pairs(), pair_lines(xt))
    scale = np.abs(f_ref).max()
    assert scale > 0.0
    assert_close(f, f_ref, scale)
    assert_close(t, t_ref, scale * RADIUS)
    np.testing.assert_allclose(x, x_ref, rtol=0, atol=1e-12)
    assert_sticks_and_slides(friction_ratios(f_ref, x_ref, [1, 0, 3, 2]))
    # the dashpot is felt: without it LAMMPS's forces differ far beyond the tolerance
    _, (f_plain, _, _) = trajectories(pairs(), pair_lines(0.0))
    assert np.abs(f_plain - f_ref).max() > 1e-3 * scale    # 1e7 times the tolerance


@pytest.mark.parametrize("region", [False, True], ids=["plane", "region"])
def test_walls_match_linear_history(region):
    (f, _, x), (f_ref, _, x_ref) = trajectories(wall_spheres(), wall_lines(1.0, region))
    scale = np.abs(f_ref).max()
    assert scale > 0.0
    assert_close(f, f_ref, scale)
    np.testing.assert_allclose(x, x_ref, rtol=0, atol=1e-12)
    assert_sticks_and_slides(friction_ratios(f_ref, x_ref, None))
    _, (f_plain, _, _) = trajectories(wall_spheres(), wall_lines(0.0, region))
    assert np.abs(f_plain - f_ref).max() > 1e-3 * scale    # 1e7 times the tolerance


def test_the_dashpot_bounds_the_time_step():
    """The damping time the run reports is the tangential m_t / (xt gamma_n) once it is the
    shorter: for equal spheres m_t = (2/7) m* (rotation included, 1/m_t = 2 (1 + 5/2) / m), so
    with xt 1 it is 2/7 of the normal m* / gamma_n."""
    times = []
    for xt in (0.0, 1.0):
        lmp = build("ellipsoid", *pairs(),
                    f"pair_style granular/ellipsoid impact_velocity 1.0\npair_coeff * * {ours(xt)}")
        lmp.command("run 0 post no")
        times.append(lmp.extract_pair("damping_time"))
        lmp.close()
    assert times[0] > 0.0
    assert times[1] == pytest.approx(2.0 / 7.0 * times[0], rel=1e-12)


def test_restart_keeps_xt(tmp_path):
    """A restart written mid-contact holds xt: the run continued from it gives the forces of
    the uninterrupted run (a record without xt would read xt 0 and lose the dashpot)."""
    path = tmp_path / "damped.restart"
    lmp = build("ellipsoid", *pairs(), pair_lines(1.0)["ellipsoid"])
    lmp.command("run 60 post no")
    lmp.command(f"write_restart {path}")
    lmp.command("run 40 post no")
    f_ref = per_atom(lmp, "f")
    lmp.close()
    lmp = new_lammps()
    lmp.commands_string(f"read_restart {path}\ncomm_modify vel yes\nfix i all nve\n"
                        "run 40 post no\n")
    f = per_atom(lmp, "f")
    lmp.close()
    np.testing.assert_allclose(f, f_ref, rtol=1e-13, atol=1e-13 * np.abs(f_ref).max())


DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")


def test_restart_of_the_previous_law_record_reads(tmp_path):
    """data/old_law_16.restart, written by the plugin of 826e5a5 (law record of 16 values,
    before xt was appended; data/in.old_law_16, with rolling sds), is read as a record of this
    version without xt: continued 20 steps it gives, bit for bit, the forces of the same input
    run and restarted with this version (so the record read is the law, xt 0, and the old
    version's steps are this one's)."""
    def continued(restart):
        lmp = new_lammps()
        lmp.commands_string(f"read_restart {restart}\ncomm_modify vel yes\n"
                            "fix integrate all nve/ellipsoid\nrun 20 post no\n")
        f = per_atom(lmp, "f")
        lmp.close()
        return f

    now = tmp_path / "now.restart"
    lmp = new_lammps()
    lmp.commands_string(f"variable out index {now}\n")
    lmp.file(os.path.join(DATA, "in.old_law_16"))
    lmp.close()
    f_old, f_now = continued(os.path.join(DATA, "old_law_16.restart")), continued(now)
    assert np.abs(f_now).max() > 0.0
    np.testing.assert_array_equal(f_old, f_now)
