"""The servo wall of fix wall/gran/ellipsoid: `servo force|stress TARGET gain G vmax V` moves
its one wall along its normal at u = G (F_target - F), |u| <= vmax, F the particles' push on
it at the previous step, or with `filter T` that push low-pass filtered over the time T.

A sphere on a floor under a servo lid (no gravity): the lid comes down at vmax, then settles
where the Hertz contact carries the target, to 1e-6 of the target, with an overshoot of the
force below 5 % (the controller is first order: the lid has no inertia, the sphere little
against the contact's stiffness at this gain); the lid's height then equals the analytic one,
2 r - 2 xi with F = 4/3 E* sqrt(R*) xi^1.5 at each of the two contacts. With `stress` the
target is the stress times the box's cross-section, with `area A` on A: a piston in a cylinder region is
this plane servo with area pi R^2. A restart continues the servo exactly,
with or without the filter of its measure. The loop's bound at the time step's frequency (it
includes the contacts' stiffness and the particle's inertia) and the filter: below.
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


@pytest.mark.parametrize("words", ["area 0.8", "filter 1e-4 area 0.8", "area 0.8 filter 1e-4"])
def test_servo_stress_on_a_given_area(words):
    """`area A`: the stress acts on A (a piston in a cylinder), not on the box's 2 x 2
    cross-section; with or after the filter."""
    lmp = sphere_under_lid(f"servo stress {TARGET / 0.8} gain 0.05 vmax 0.5 {words}")
    lmp.command("run 12000 post no")
    force = lid_force(lmp)
    lmp.close()
    assert force == pytest.approx(TARGET, rel=1e-6)


def test_piston_in_a_cylinder_region():
    """A piston: the plane servo with `area pi R^2` above a sphere inside a cylinder region
    (fix wall/gran/region/ellipsoid, its lo cap the floor, its hi cap open): the piston
    reaches the stress on its area, the region's floor carries that force, the side nothing."""
    cylinder = 0.8
    area = math.pi * cylinder**2
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box("ellipsoid", (2, 2, 3), [(1.0, 1.0, RADIUS)],
                                              RADIUS))
    lmp.commands_string(f"""
        region can cylinder z 1 1 {cylinder} 0 2.5 open 2
        fix can all wall/gran/region/ellipsoid {LAW} region can
        fix lid all wall/gran/ellipsoid {LAW} zplane NULL 1.05 servo stress {TARGET / area} gain 0.05 vmax 0.5 area {area}
        fix i all nve/ellipsoid
        timestep 1e-4
        run 12000 post no
        """)
    pushed = lid_force(lmp)
    floor = [lmp.extract_fix("can", 0, 1, k) for k in range(3)]
    side = [lmp.extract_fix("can", 0, 1, k) for k in range(3, 6)]
    z_sphere = lmp.numpy.extract_atom("x")[0][2]
    lmp.close()
    assert pushed == pytest.approx(TARGET, rel=1e-6)
    assert floor == pytest.approx([0.0, 0.0, -TARGET], rel=1e-6, abs=1e-12)
    assert side == [0.0, 0.0, 0.0]
    assert z_sphere == pytest.approx(RADIUS - hertz_overlap(TARGET, RADIUS), rel=1e-6)


def test_three_servo_walls_press_a_sphere_into_a_corner():
    """A triaxial box: three fixes, each with one servo wall (x, y, z hi) against fixed lo
    walls, reach their own targets at once; the sphere rests where each axis's Hertz contacts
    carry its target."""
    targets = (1.0, 2.0, 3.0)
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box("ellipsoid", (3, 3, 3), [(1.0, 1.0, 1.0)], RADIUS))
    lmp.command("change_box all boundary f f f")
    for d, (dim, target) in enumerate(zip("xyz", targets)):
        lmp.commands_string(f"""
            fix lo{dim} all wall/gran/ellipsoid {LAW} {dim}plane 0.5 NULL
            fix hi{dim} all wall/gran/ellipsoid {LAW} {dim}plane NULL 1.55 servo force {target} gain 0.05 vmax 0.5
            """)
    lmp.commands_string("fix i all nve/ellipsoid\ntimestep 1e-4\nrun 15000 post no")
    pushed = [lmp.extract_fix(f"hi{dim}", 0, 1, d) for d, dim in enumerate("xyz")]
    x = lmp.numpy.extract_atom("x")[0].copy()
    lmp.close()
    assert pushed == pytest.approx(targets, rel=1e-6)
    for d, target in enumerate(targets):
        assert x[d] == pytest.approx(0.5 + RADIUS - hertz_overlap(target, RADIUS), rel=1e-6)


@pytest.mark.parametrize("servo", ["servo force 2.0 gain 0.05 vmax 0.5",
                                   "servo force 2.0 gain 0.05 vmax 0.5 filter 1e-3"])
def test_servo_restart_continues_exactly(tmp_path, servo):
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


# The step-frequency bound (doc/fix_wall_gran_ellipsoid.rst, "Servo wall"). A light sphere,
# hard damped, between the floor and the lid, both with the law F = kn xi^(3/2) + K xi^(1/2)
# dxi/dt: at the target each contact has c = K xi^(1/2) and k = 3/2 kn xi^(1/2), and the
# sphere's damping number 2 c dt / m is 1 (its own integration is stable: below 2 with both
# contacts). The force's response to the lid's velocity at the time step's frequency is
# H = (c + k dt/2) (1 - (c dt/2 + k dt^2/4)/m) / (1 - (2 c dt/2 + 2 k dt^2/4)/m), the floor's
# contact in the first bracket (velocity Verlet at z = -1), here 1.51 c: the loop chatters
# above G H = 1. G H = 0.9 and 1.1 fall on either side; G c = 0.8 keeps the old bound G c < 1
# and chatters; the filter (time constant 5 dt: the gain at the step frequency times
# (1 - e^-1/5) / (1 + e^-1/5) = 0.1) holds that gain steady.
STIFF_KN, STIFF_K, STIFF_DT = 1.0e7, 4.5e5, 1.0e-4


def stiff_contact():
    xi = (TARGET / STIFF_KN)**(2 / 3)
    c, k, m = STIFF_K * math.sqrt(xi), 1.5 * STIFF_KN * math.sqrt(xi), math.pi / 6
    floor = 1 - (c * STIFF_DT / 2 + k * STIFF_DT**2 / 4) / m
    both = 1 - (c * STIFF_DT + k * STIFF_DT**2 / 2) / m
    return c, (c + k * STIFF_DT / 2) * floor / both


def stiff_lid_forces(gain, extra="", steps=30000):
    law = f"hertz {STIFF_KN} {STIFF_K}"
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box("ellipsoid", (2, 2, 3), [(1.0, 1.0, RADIUS)],
                                              RADIUS))
    lmp.commands_string(f"""
        fix floor all wall/gran/ellipsoid {law} zplane 0.0 NULL
        fix lid all wall/gran/ellipsoid {law} zplane NULL {2 * RADIUS} &
            servo force {TARGET} gain {gain} vmax 0.5 {extra}
        fix i all nve/ellipsoid
        timestep {STIFF_DT}
        variable f equal f_lid[3]
        """)
    lmp.command("fix trace all vector 1 v_f")
    lmp.command(f"run {steps} post no")
    forces = np.array([lmp.extract_fix("trace", 0, 1, i) for i in range(steps)])
    lmp.close()
    return forces


def alternation(forces):
    """the amplitude of the forces' alternation from step to step over the last 200 steps"""
    tail = forces[-200:]
    return np.abs(tail[2:] - 2 * tail[1:-1] + tail[:-2]).max() / 4


def test_servo_step_frequency_bound_includes_stiffness_and_inertia():
    c, h = stiff_contact()
    assert h / c == pytest.approx(1.51, abs=0.01)
    below = stiff_lid_forces(0.9 / h)
    above = stiff_lid_forces(1.1 / h)
    old_bound = stiff_lid_forces(0.8 / c)
    assert below[-1] == pytest.approx(TARGET, rel=1e-6)
    assert below.max() < 1.05 * TARGET
    assert alternation(below) < 1e-6 * TARGET
    # 1.1 / H: G c = 0.73, within the old bound, and the lid chatters
    assert alternation(above) > 0.5 * TARGET
    assert alternation(old_bound) > 0.5 * TARGET


def test_servo_filter_holds_the_gain_of_the_old_bound():
    c, _ = stiff_contact()
    forces = stiff_lid_forces(0.8 / c, f"filter {5 * STIFF_DT}")
    assert forces[-1] == pytest.approx(TARGET, rel=1e-6)
    assert forces.max() < 1.05 * TARGET
    assert alternation(forces) < 1e-6 * TARGET


@pytest.mark.parametrize("gain, vmax, speed", [(0.05, 0.5, 0.05 * TARGET), (0.05, 0.04, 0.04)])
def test_servo_without_contact_moves_at_gain_times_target(gain, vmax, speed):
    """A lid far above the sphere (F = 0) comes down at min(G F_target, vmax)."""
    lmp = sphere_under_lid(f"servo force {TARGET} gain {gain} vmax {vmax}", lid=2.5)
    lmp.command("run 1000 post no")
    lid = lmp.extract_fix("lid", 0, 1, 3)
    lmp.close()
    assert lid == pytest.approx(2.5 - speed * 1000 * 1e-4, rel=1e-12)


def test_servo_coordinate_is_intensive_under_thermo_norm(tmp_path):
    """lj units normalise extensive thermo output by the atom count (thermo_modify norm yes):
    the lid's force is divided by the 4 atoms, its coordinate is printed as it is."""
    import ed_helpers_pour as h
    lmp = h.new_lammps(tmp_path)
    lmp.commands_string(scenes.spheres_in_box(
        "ellipsoid", (2, 2, 3), [(0.5, 0.5, RADIUS), (1.5, 0.5, RADIUS), (0.5, 1.5, RADIUS),
                                 (1.5, 1.5, RADIUS)], RADIUS))
    lmp.commands_string(f"""
        fix floor all wall/gran/ellipsoid {LAW} zplane 0.0 NULL
        fix lid all wall/gran/ellipsoid {LAW} zplane NULL 0.99 servo force 8 gain 0.05 vmax 0.5
        fix i all nve/ellipsoid
        timestep 1e-4
        thermo_style custom step f_lid[3] f_lid[4]
        thermo_modify format float %.15g
        run 10
        """)
    force, lid = lmp.extract_fix("lid", 0, 1, 2), lmp.extract_fix("lid", 0, 1, 3)
    log = h.read_log(lmp)
    lmp.close()
    rows = [line.split() for line in log.splitlines() if line.split()[:1] == ["10"]]
    printed = [float(v) for v in rows[-1][1:3]]
    assert force > 0.0
    assert printed[0] == pytest.approx(force / 4, rel=1e-12)
    assert printed[1] == pytest.approx(lid, rel=1e-12)


def test_servo_stress_is_in_pressure_units():
    """metal units: a stress of 1e6 bar on a 10 x 10 A cross-section is 1e8 / nktv2p =
    62.415 eV/A (LAMMPS's force->nktv2p = 1.6021765e6): the lid without contact comes down at
    G times that."""
    lmp = new_lammps()
    lmp.commands_string("""
        units metal
        atom_style ellipsoid
        boundary p p f
        region box block 0 10 0 10 0 20
        create_box 1 box
        create_atoms 1 single 5 5 2
        set type 1 shape 2 2 2
        set type 1 density 1.0
        fix lid all wall/gran/ellipsoid hertz 1e4 10 zplane NULL 15 servo stress 1e6 gain 1e-4 vmax 1
        fix i all nve/ellipsoid
        timestep 0.001
        run 1000 post no
        """)
    lid = lmp.extract_fix("lid", 0, 1, 3)
    lmp.close()
    assert lid == pytest.approx(15 - 1e-4 * 1e8 / 1.6021765e6 * 1000 * 0.001, rel=1e-12)
