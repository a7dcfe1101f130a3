"""Force-law options at their limits: limit_damping, mixing refusals, restarts that change the
tangential model, and the Hertz contact time reported at run start.

Specification:
- without limit_damping (the default, as in LAMMPS's pair granular) a fast-separating contact
  is attractive, F_n = kn xi^3/2 + K xi^1/2 dxi/dt < 0; with it F_n = 0; for pair and wall;
- unlike types of different models are refused with both models named;
- the restart file keeps every law parameter (limit_damping included) in table order;
- a restart read by an input that adds or removes a tangential history is an ERROR;
- at run start the pair and the wall report the undamped Hertz contact time of their
  shortest contact, 2 (2/5) B(2/5, 1/2) (5 m*/(4 k))^(2/5) v^(-1/5), and warn when the
  timestep exceeds 1/10 of it;
- and the damping number dt / (m*/gamma) at that contact's deepest overlap
  xi_max = (5 m* v^2 / (4 k))^(2/5): gamma = K sqrt(xi_max) for hertz, the restitution
  damping 2 sqrt(5/6) |beta| sqrt(2 E* sqrt(R* xi_max) m*) for hertz/material; they warn when
  it exceeds 1 (velocity Verlet damps stably below 2); an undamped law reports none.
"""
import math
import os
import re

import numpy as np
import pytest
from scipy.special import beta

import ed_helpers_pour as h
import scenes
from conftest import new_lammps

KN, K = 1.0e4, 100.0
RADIUS, OVERLAP, SPEED = 0.5, 1.0e-3, 1.0
MASS = 4.0 / 3.0 * math.pi * RADIUS**3    # density 1


def two_spheres(extra_coeff="", speed=SPEED, pair_style="granular/ellipsoid", dt=1e-4,
                coeffs=None):
    """Two unit-density spheres (types 1 and 2) along x overlapping by OVERLAP; each moves
    away from the other at speed/2 (speed < 0: towards). coeffs: the pair_coeff lines
    (default: one law for all types)."""
    coeffs = coeffs or [f"* * hertz {KN} {K} {extra_coeff}"]
    lines = "\n".join("pair_coeff " + c for c in coeffs)
    return f"""
units lj
atom_style ellipsoid
atom_modify map array
comm_modify vel yes
region box block -3 3 -3 3 -3 3
create_box 2 box
create_atoms 1 single {-RADIUS + OVERLAP / 2} 0 0
create_atoms 2 single {RADIUS - OVERLAP / 2} 0 0
set type * shape {2 * RADIUS} {2 * RADIUS} {2 * RADIUS}
set type * density 1.0
set atom 1 vx {-speed / 2}
set atom 2 vx {speed / 2}
pair_style {pair_style}
{lines}
timestep {dt}
"""


def force_on_first(lmp):
    return lmp.numpy.extract_atom("f")[lmp.map_atom(1)][0]


def separating_force(extra_coeff):
    lmp = new_lammps()
    lmp.commands_string(two_spheres(extra_coeff) + "run 0\n")
    f = force_on_first(lmp)
    lmp.close()
    return f


def test_pair_limit_damping():
    # F_n on atom 1 is -f_x: without the limit, damping beats the elastic force
    expected = KN * OVERLAP**1.5 - K * OVERLAP**0.5 * SPEED
    assert expected < 0.0
    assert -separating_force("") == pytest.approx(expected, rel=1e-12)
    assert separating_force("limit_damping") == 0.0
    assert separating_force("tangential history 1e3 0.5 limit_damping") == 0.0


def wall_force_leaving(extra):
    lmp = new_lammps()
    lmp.commands_string(scenes.sphere_over_wall(RADIUS, RADIUS - OVERLAP,
                                                f"hertz {KN} {K} {extra} zplane 0 NULL",
                                                velocity=(0, 0, SPEED)) + "run 0\n")
    fz = -lmp.extract_fix("w", 0, 1, 2)    # the fix's vector is the force on the wall
    lmp.close()
    return fz


def test_wall_limit_damping():
    expected = KN * OVERLAP**1.5 - K * OVERLAP**0.5 * SPEED
    assert wall_force_leaving("") == pytest.approx(expected, rel=1e-12)
    assert wall_force_leaving("limit_damping") == 0.0


def test_unlike_models_refusal_names_both():
    lmp = new_lammps()
    try:
        with pytest.raises(Exception, match=re.escape(
                "types 1 and 2 use different models: cannot mix 'hertz, tangential none, "
                "rolling none' with 'hertz, tangential none, rolling none, limit_damping'")):
            lmp.commands_string(two_spheres(coeffs=[f"1 1 hertz {KN} {K}",
                                                    f"2 2 hertz {KN} {K} limit_damping"]) +
                                "run 0\n")
    finally:
        lmp.close()


def test_restart_keeps_every_parameter(tmp_path):
    """Unlike types mixed, limit_damping on: the forces after read_restart are the same."""
    path = tmp_path / "law.restart"
    lmp = new_lammps()
    lmp.commands_string(two_spheres(coeffs=[
        f"1 1 hertz {KN} {K} rolling constant 0.1 limit_damping",
        f"2 2 hertz {2 * KN} {K} rolling constant 0.2 limit_damping"]) + "run 0\n")
    before = force_on_first(lmp)
    lmp.command(f"write_restart {path}")
    lmp.close()
    lmp = new_lammps()
    lmp.commands_string(f"read_restart {path}\ncomm_modify vel yes\nrun 0\n")
    after = force_on_first(lmp)
    lmp.command("set atom 1 vx 0.5")    # approaching now: a repulsive, mixed-stiffness force
    lmp.command("set atom 2 vx -0.5")
    lmp.command("run 0")
    approaching = force_on_first(lmp)
    lmp.close()
    assert before == after == 0.0
    kn_mixed = math.sqrt(KN * 2 * KN)
    assert -approaching == pytest.approx(kn_mixed * OVERLAP**1.5 + K * OVERLAP**0.5 * SPEED,
                                         rel=1e-12)


def restart_then(path, written_input, read_input):
    """Runs written_input and writes a restart at its end; then, in a new instance,
    read_restart and read_input."""
    lmp = new_lammps()
    lmp.commands_string(written_input + f"fix i all nve/asphere\nrun 10\nwrite_restart {path}\n")
    lmp.close()
    lmp = new_lammps()
    try:
        lmp.commands_string(f"read_restart {path}\ncomm_modify vel yes\n" + read_input)
    finally:
        lmp.close()


@pytest.mark.parametrize("written,read", [("history 1e3 0.5", "none"),
                                          ("none", "history 1e3 0.5"),
                                          ("viscous 0.1", "history 1e3 0.5")])
def test_restart_with_another_history_size_is_refused(tmp_path, written, read):
    with pytest.raises(Exception, match=r"the restart file holds \d+ history values per pair, "
                                        r"the force laws now need \d+"):
        restart_then(tmp_path / "pair.restart", two_spheres(f"tangential {written}", speed=-SPEED),
                     f"pair_coeff * * hertz {KN} {K} tangential {read}\nrun 0\n")


def test_restart_with_the_same_history_size_continues(tmp_path):
    restart_then(tmp_path / "pair.restart",
                 two_spheres("tangential history 1e3 0.5", speed=-SPEED),
                 f"pair_coeff * * hertz {KN} {K} tangential history 2e3 0.3\nrun 0\n")


# written with the plugins of f74bd3f and 11dc32b, whose histories had 8 and 10 values per
# pair (data/in.old_layout_8, data/in.old_layout_10: three ellipsoids in a row, two contacts
# with a tangential history). 10 is also the size of this layout without a tangential history.
def old_layout(size):
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "data",
                        f"old_layout_{size}.restart")


OLD_FIX_IDS = {8: "NEIGH_HISTORY_GRANULAR_ELLIPSOID", 10: "NEIGH_HISTORY_GRANULAR_ELLIPSOID_10"}
OLD_PAIR = "pair_style granular/ellipsoid\npair_coeff * * hertz 1.0e4 20.0 tangential history 2.0e3 0.5\n"
OLD_PAIR_NO_HISTORY = "pair_style granular/ellipsoid\npair_coeff * * hertz 1.0e4 20.0\n"


@pytest.mark.parametrize("size", [8, 10])
@pytest.mark.parametrize("commands", ["", OLD_PAIR])    # pair_style again: the same instance
def test_restart_of_the_old_history_layout_is_refused(commands, size):
    lmp = new_lammps()
    try:
        with pytest.raises(Exception, match=rf"the restart file holds {size} history values per "
                                            r"pair, a layout of another version"):
            lmp.commands_string(f"read_restart {old_layout(size)}\ncomm_modify vel yes\n" +
                                commands + "run 0\n")
    finally:
        lmp.close()


def forces_by_id(lmp):
    n = lmp.extract_global("nlocal")
    ids = lmp.numpy.extract_atom("id")[:n]
    return lmp.numpy.extract_atom("f")[:n][np.argsort(ids)].copy()


@pytest.mark.parametrize("size, pair", [(8, OLD_PAIR), (10, OLD_PAIR), (10, OLD_PAIR_NO_HISTORY)])
def test_pair_style_replaced_after_an_old_restart_starts_the_contacts_afresh(tmp_path, size,
                                                                            pair):
    """A pair style replaced after read_restart (pair_style none, then granular/ellipsoid: a
    new instance, without the file's pair record) cannot see the old layout; the history
    fix's ID names its layout and size, so the file's 8 or 10 values per pair stay unused
    (LAMMPS logs them) instead of being read as this layout's 13, or as its 10 without a
    tangential history: the forces are those of the same positions read from a data file,
    where every contact starts afresh."""
    data = tmp_path / "old.data"
    lmp = h.new_lammps(tmp_path, "again")
    lmp.commands_string(f"read_restart {old_layout(size)}\ncomm_modify vel yes\n"
                        "pair_style none\n" + pair + "fix i all nve/ellipsoid\nrun 0\n")
    again = forces_by_id(lmp)
    log = h.read_log(lmp)
    lmp.command(f"write_data {data}")
    lmp.close()
    assert re.search(r"Unused restart file peratom fix info:\n\s+fix style: NEIGH_HISTORY, "
                     rf"fix ID: {OLD_FIX_IDS[size]}\n", log), log[-2000:]
    lmp = h.new_lammps(tmp_path, "data")
    lmp.commands_string(f"atom_style ellipsoid\ncomm_modify vel yes\nread_data {data}\n" +
                        pair + "fix i all nve/ellipsoid\nrun 0\n")
    fresh = forces_by_id(lmp)
    lmp.close()
    assert np.count_nonzero(np.abs(fresh).sum(axis=1)) == 3    # both contacts
    np.testing.assert_allclose(again, fresh, rtol=1e-12, atol=0)


# ---- the Hertz contact time -----------------------------------------------------------------

def hertz_time(stiffness, m_eff, speed):
    integral = 0.4 * beta(0.4, 0.5)
    return 2 * integral * (5 * m_eff * speed**2 / (4 * stiffness))**0.4 / speed


def pair_contact_time(tmp_path, dt, extra_style=""):
    lmp = h.new_lammps(tmp_path)
    lmp.commands_string(two_spheres(speed=-SPEED, dt=dt,
                                    pair_style=f"granular/ellipsoid {extra_style}") + "run 0\n")
    t = lmp.extract_pair("contact_time")
    log = h.read_log(lmp)
    lmp.close()
    return t, log


def test_pair_contact_time_and_warning(tmp_path):
    # the two spheres approach at SPEED: twice the fastest atom
    expected = hertz_time(KN, MASS / 2, SPEED)
    t, log = pair_contact_time(tmp_path, dt=expected / 50)
    assert t == pytest.approx(expected, rel=1e-12)
    assert "Pair granular/ellipsoid: Hertz contact time" in log
    assert "exceeds" not in log
    t, log = pair_contact_time(tmp_path, dt=expected / 5)
    assert re.search(r"WARNING: Pair granular/ellipsoid: timestep \S+ exceeds 0.1 of the Hertz "
                     r"contact time", log)
    t, _ = pair_contact_time(tmp_path, dt=1e-4, extra_style="impact_velocity 32")
    assert t == pytest.approx(expected / 2, rel=1e-12)    # v^(-1/5)


def wall_log(tmp_path, law, dt):
    """the log of run 0 of a sphere falling at SPEED onto a wall of this law"""
    lmp = h.new_lammps(tmp_path)
    lmp.commands_string(scenes.sphere_over_wall(RADIUS, 1.0, f"{law} zplane 0 NULL",
                                                velocity=(0, 0, -SPEED)) +
                        f"timestep {dt}\nrun 0\n")
    log = h.read_log(lmp)
    lmp.close()
    return log


def test_wall_contact_time_and_warning(tmp_path):
    def run(dt):
        return wall_log(tmp_path, f"hertz {KN} {K}", dt)

    expected = hertz_time(KN, MASS, SPEED)
    log = run(expected / 50)
    found = re.search(r"Fix wall/gran/ellipsoid: Hertz contact time (\S+) \(type 1", log)
    assert found and float(found.group(1)) == pytest.approx(expected, rel=1e-5)
    assert "exceeds" not in log
    assert re.search(r"WARNING: Fix wall/gran/ellipsoid: timestep \S+ exceeds 0.1",
                     run(expected / 5))


def test_wall_restart_with_other_walls_is_refused(tmp_path):
    """The wall's per-atom tangential history: 3 values per wall; another number of walls
    after read_restart is an ERROR, the same walls continue."""
    path = tmp_path / "wall.restart"
    law = f"hertz {KN} {K} tangential history 1e3 0.5"
    scene = scenes.sphere_over_wall(RADIUS, RADIUS - OVERLAP, f"{law} zplane 0 NULL",
                                    velocity=(SPEED, 0, 0))
    restart_then(path, scene, f"fix w all wall/gran/ellipsoid {law} zplane 0 NULL\nrun 0\n")
    with pytest.raises(Exception, match=r"the restart file holds 3 history values per atom, "
                                        r"this fix needs 6"):
        restart_then(path, scene, f"fix w all wall/gran/ellipsoid {law} zplane 0 4\nrun 0\n")


# ---- the damping number ---------------------------------------------------------------------

def max_overlap(stiffness, m_eff, speed):
    return (5 * m_eff * speed**2 / (4 * stiffness))**0.4


DAMPING_LINE = re.compile(r"Pair granular/ellipsoid: damping number (\S+) \(types \d \d, "
                          r"impact speed \S+\): the time step over the damping time m\*/gamma "
                          r"(\S+) at the deepest overlap")


def test_pair_damping_number_and_warning(tmp_path):
    strong = 20 * K    # damping time well below the contact time, so only the damping warns
    m_eff = MASS / 2
    expected = m_eff / (strong * math.sqrt(max_overlap(KN, m_eff, SPEED)))
    assert expected < 0.1 * hertz_time(KN, m_eff, SPEED) / 1.5

    def run(dt):
        lmp = h.new_lammps(tmp_path)
        lmp.commands_string(two_spheres(speed=-SPEED, dt=dt, coeffs=[f"* * hertz {KN} {strong}"])
                            + "run 0\n")
        t = lmp.extract_pair("damping_time")
        log = h.read_log(lmp)
        lmp.close()
        return t, log

    t, log = run(expected / 2)
    assert t == pytest.approx(expected, rel=1e-12)
    number, reported = DAMPING_LINE.search(log).groups()
    assert float(number) == pytest.approx(0.5, rel=1e-3)
    assert float(reported) == pytest.approx(expected, rel=1e-5)
    assert "exceeds" not in log
    _, log = run(1.5 * expected)
    warnings = re.findall(r"^WARNING.*exceeds.*", log, re.M)
    assert len(warnings) == 1, warnings
    assert re.search(r"WARNING: Pair granular/ellipsoid: damping number 1.5 \(types 1 1, impact "
                     r"speed 1\) exceeds 1", warnings[0]), warnings


def test_wall_damping_time_of_the_restitution_law(tmp_path):
    youngs, poisson, restitution = 1.0e5, 0.3, 0.5
    reduced = youngs / (2 * (1 - poisson**2))
    stiffness = 4.0 / 3.0 * reduced * math.sqrt(RADIUS)
    xi = max_overlap(stiffness, MASS, SPEED)
    log_e = math.log(restitution)
    beta_e = log_e / math.sqrt(log_e**2 + math.pi**2)
    gamma = -2 * math.sqrt(5 / 6) * beta_e * math.sqrt(2 * reduced * math.sqrt(RADIUS * xi) * MASS)
    expected = MASS / gamma

    def run(law, dt):
        return wall_log(tmp_path, law, dt)

    log = run(f"hertz/material {youngs} {poisson} {restitution}", expected / 4)
    found = re.search(r"Fix wall/gran/ellipsoid: damping number (\S+) \(type 1, impact speed 1\): "
                      r"the time step over the damping time m\*/gamma (\S+) ", log)
    assert found, log
    assert float(found.group(1)) == pytest.approx(0.25, rel=1e-3)
    assert float(found.group(2)) == pytest.approx(expected, rel=1e-5)
    # (at e = 0.5 the damping time is close to the contact time: only that one warns here)
    assert not re.search(r"damping number \S+ \(.*exceeds", log)
    assert re.search(r"WARNING: Fix wall/gran/ellipsoid: damping number 1.2 \(type 1, impact speed "
                     r"1\) exceeds 1", run(f"hertz/material {youngs} {poisson} {restitution}",
                                           1.2 * expected))
    # an elastic law (e = 1) has no damping to report or warn about
    elastic = run(f"hertz/material {youngs} {poisson} 1.0", expected)
    assert "damping number" not in elastic
