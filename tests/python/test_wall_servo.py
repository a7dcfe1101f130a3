"""The servo wall of fix wall/gran/ellipsoid: `servo force|stress TARGET gain G vmax V` moves
its one wall along its normal at u = G (F_target - F), |u| <= vmax, F the particles' push on
it at the previous step.

A sphere on a floor under a servo lid (no gravity): the lid comes down at vmax, then settles
where the Hertz contact carries the target, to 1e-6 of the target, with an overshoot of the
force below 5 % (the controller is first order: the lid has no inertia, the sphere little
against the contact's stiffness at this gain); the lid's height then equals the analytic one,
2 r - 2 xi with F = 4/3 E* sqrt(R*) xi^1.5 at each of the two contacts. With `stress` the
target is the stress times the box's cross-section. A restart continues the servo exactly.
Bad servo words: test_wall_motion.py.
"""
import math

import numpy as np
import pytest

import scenes
from conftest import new_lammps

E, NU, REST = 1.0e5, 0.3, 0.5
RADIUS = 0.5
TARGET = 2.0
LAW = f"hertz/material {E} {NU} {REST}"


def sphere_under_lid(servo, lid=1.05, extra=""):
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box("ellipsoid", (2, 2, 3), [(1.0, 1.0, RADIUS)],
                                              RADIUS))
    lmp.commands_string(f"""
        fix floor all wall/gran/ellipsoid {LAW} zplane 0.0 NULL
        fix lid all wall/gran/ellipsoid {LAW} zplane NULL {lid} {servo} {extra}
        fix i all nve/ellipsoid
        timestep 1e-4
        """)
    return lmp


def lid_force(lmp):
    # the lid's vector: the force of the particles on it; they push it up (+z)
    return lmp.extract_fix("lid", 0, 1, 2)


def hertz_overlap(force, radius):
    e_star = E / (2 * (1 - NU**2))
    return (force / (4 / 3 * e_star * math.sqrt(radius)))**(2 / 3)


@pytest.mark.parametrize("kind, target", [("force", TARGET), ("stress", TARGET / 4.0)])
def test_servo_lid_reaches_the_target(kind, target):
    lmp = sphere_under_lid(f"servo {kind} {target} gain 0.05 vmax 0.5")
    forces = []
    for _ in range(120):
        lmp.command("run 100 post no")
        forces.append(lid_force(lmp))
    z_sphere = lmp.numpy.extract_atom("x")[0][2]
    lmp.close()
    forces = np.array(forces)
    assert forces[-1] == pytest.approx(TARGET, rel=1e-6)
    assert forces.max() < 1.05 * TARGET
    # force balance: the floor carries what the lid pushes, both contacts xi deep (R* = r)
    xi = hertz_overlap(TARGET, RADIUS)
    assert z_sphere == pytest.approx(RADIUS - xi, rel=1e-6)


def test_servo_restart_continues_exactly(tmp_path):
    servo = "servo force 2.0 gain 0.05 vmax 0.5"
    lmp = sphere_under_lid(servo)
    lmp.command("run 6000 post no")
    lmp.command(f"write_restart {tmp_path}/servo.restart")
    lmp.command("run 1500 post no")
    straight = (lmp.numpy.extract_atom("x")[0][2], lid_force(lmp))
    lmp.close()
    lmp = new_lammps()
    lmp.commands_string(f"""
        atom_style ellipsoid
        read_restart {tmp_path}/servo.restart
        comm_modify vel yes
        fix floor all wall/gran/ellipsoid {LAW} zplane 0.0 NULL
        fix lid all wall/gran/ellipsoid {LAW} zplane NULL 1.05 {servo}
        fix i all nve/ellipsoid
        timestep 1e-4
        run 1500 post no
        """)
    continued = (lmp.numpy.extract_atom("x")[0][2], lid_force(lmp))
    lmp.close()
    assert straight[1] > 0.5 * 2.0    # in contact, the servo acting
    assert continued[0] == pytest.approx(straight[0], rel=1e-12)
    assert continued[1] == pytest.approx(straight[1], rel=1e-9)
