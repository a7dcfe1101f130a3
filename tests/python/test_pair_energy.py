"""Elastic collisions of two ellipsoids (K = 0, no friction) conserve kinetic energy.

Random orientations, an off-centre approach so that the bodies spin up, a time step that
resolves the contact in about 50 steps. Relative kinetic-energy error: below 0.1 % for a/c <= 4,
below 1 % up to a/c = 10.
"""
import json

import numpy as np
import pytest

import scenes
from conftest import new_lammps

STEPS_PER_CONTACT = 50


def head_on_pair(ratio, seed, gap=0.05):
    """Two triaxial ellipsoids (a/c = ratio, c = 0.5) with random orientations approaching
    along x at relative speed 1, slightly off-centre so that they spin up."""
    rng = np.random.default_rng(seed)
    c = 0.5
    semi = np.array([ratio * c, np.sqrt(ratio) * c, c])
    reach = semi.max()
    lmp = new_lammps()
    lmp.commands_string(scenes.particle_box("ellipsoid", -20, 20, boundary="f f f") + f"""
        create_atoms 1 single {-reach - gap} 0 0
        create_atoms 1 single {reach + gap} {0.3 * c} 0
        set type 1 mass 1.0
        set type 1 shape {2 * semi[0]} {2 * semi[1]} {2 * semi[2]}
        """)
    for tag in (1, 2):
        axis = rng.normal(size=3)
        lmp.command(f"set atom {tag} quat {axis[0]} {axis[1]} {axis[2]} {rng.uniform(0, 360)}")
    lmp.commands_string("""
        group left id 1
        group right id 2
        velocity left set 0.5 0 0
        velocity right set -0.5 0 0
        pair_style granular/ellipsoid
        pair_coeff * * hertz 1.0e4 0.0 tangential none
        fix integrate all nve/asphere
        """)
    return lmp


def collide(ratio, seed, dt, steps):
    lmp = head_on_pair(ratio, seed)
    lmp.commands_string(f"""
        compute rot all erotate/asphere
        compute tr all ke
        variable energy equal c_tr+c_rot
        compute overlap all pair/local p1
        compute deepest all reduce max c_overlap inputs local
        variable touching equal c_deepest>0
        fix touch all ave/time 1 {steps} {steps} v_touching
        variable rot equal c_rot
        variable fraction equal f_touch
        variable deepest equal c_deepest
        timestep {dt}
        thermo_style custom step v_energy c_rot c_deepest f_touch
        thermo {steps}
        run 0
        """)
    e0 = lmp.extract_variable("energy")
    lmp.command(f"run {steps}")
    # all computes were invoked by the thermo output of the last step: they are current
    e1 = lmp.extract_variable("energy")
    rot = lmp.extract_variable("rot")
    contact_steps = lmp.extract_variable("fraction") * steps
    deepest_overlap = lmp.extract_variable("deepest")
    lmp.close()
    return e0, e1, rot, contact_steps, deepest_overlap


@pytest.mark.parametrize("ratio,tolerance", [(1.5, 1e-3), (2.5, 1e-3), (4.0, 1e-3), (10.0, 1e-2)])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_elastic_collision_conserves_energy(ratio, tolerance, seed):
    # measure the contact duration, then resolve it in ~50 steps (the duration depends a
    # little on the step, so refine until it is in range)
    travel = 2.0 * ratio * 0.5 + 2.0    # worst-case gap closed and reopened at speed 1
    dt = 1e-3
    for _ in range(4):
        steps = int(travel * 1.5 / dt)
        e0, e1, rot, contact_steps, deepest = collide(ratio, seed, dt, steps)
        assert contact_steps > 3, "the bodies did not collide"
        if 40 <= contact_steps <= 60:
            break
        dt *= contact_steps / STEPS_PER_CONTACT
    assert deepest <= 0.0, "still in contact at the end"
    assert 40 <= contact_steps <= 60
    assert rot > 1e-3 * e0, "no spin-up: the collision did not test the torques"
    assert abs(e1 - e0) / e0 < tolerance, f"relative energy change {(e1 - e0) / e0:.2e}"


def test_counters_follow_the_pipeline(tmp_path):
    """compute pair exposes the pair's counters: an approach passes through bounding rejects,
    cached planes and Wang tests before the contact, and every evaluation converges. The
    counters are read by name from the pair's JSON line at the end of the run and must equal
    Pair::extract("counters/NAME") and the vector of compute pair, whose order is the JSON's
    (its last entries are the contact and damping times, Pair::extract("contact_time") and
    Pair::extract("damping_time"))."""
    lmp = head_on_pair(2.5, 77, gap=1.0)
    log = tmp_path / "log.lammps"
    lmp.commands_string(f"""
        log {log}
        compute counters all pair granular/ellipsoid
        thermo_style custom step c_counters[*]
        thermo 6000
        timestep 5e-4
        run 6000
        """)
    vector = list(lmp.numpy.extract_compute("counters", 0, 1))
    extracted = {}
    lmp.command("log none")
    lines = [line for line in log.read_text().splitlines()
             if line.startswith("granular/ellipsoid counters: ")]
    assert len(lines) == 1, lines
    c = json.loads(lines[0][len("granular/ellipsoid counters: "):])
    for name in c:
        extracted[name] = lmp.extract_pair("counters/" + name)
    assert lmp.extract_pair("counters/no_such_counter") is None
    contact_time = lmp.extract_pair("contact_time")
    damping_time = lmp.extract_pair("damping_time")
    lmp.close()
    assert extracted == c, (extracted, c)
    # the counters, then the contact and damping times of the run start
    assert vector[:-2] == list(c.values()), (vector, c)
    assert contact_time > 0 and vector[-2] == contact_time
    assert damping_time == 0 and vector[-1] == 0    # this law is undamped (K = 0)
    assert c["bounding_rejects"] > 0 and c["plane_hits"] > 0 and c["wang_calls"] > 0, c
    assert c["contacts"] > 10, c
    assert c["plane_hits"] > c["wang_calls"], "cached planes should spare most Wang tests"
    assert c["not_converged"] == 0 and c["degenerate"] == 0, c
    # every evaluation ends in exactly one of these
    assert c["pairs"] == c["bounding_rejects"] + c["plane_hits"] + c["wang_calls"] + \
        c["continued"], c
    # one collision: the onset is found by a Wang test, every later step (including the one
    # that finds the separation) continues the contact, so the two counts are equal
    assert c["continued"] == c["contacts"], c
