"""fix wall/gran/region/ellipsoid: a concave face touched in two separate places gives two
contacts. A rod (shape 6 1 1) across a pipe narrower than its length touches both sides: the
net force vanishes for the symmetric rod as between two plane walls at the same places (the
deeper contact alone gave -8627 here, and half the torque), and an elastic rod bouncing in a
pipe keeps its energy as between planes (with one contact it drifted by 9e-4 here); the same
in a sphere region (a bowl) and across a hopper (a cone)."""
import math

import numpy as np
import pytest

from conftest import new_lammps

ROD = "6 1 1"
LAW = "hertz 1e4 0"    # elastic: no damping, no friction


def rod_scene(wall, tilt, velocity=(0.0, 0.0, 0.0), spin=(0.0, 0.0, 0.0)):
    """A rod (semi-axes 3, 0.5, 0.5) at the pipe's axis (x = y = 0), its long axis tilted by
    `tilt` degrees from z towards x, in a box periodic along z; `wall` the fix's words"""
    lmp = new_lammps()
    lmp.commands_string(f"""
        units lj
        atom_style ellipsoid
        atom_modify map array
        boundary f f p
        comm_modify vel yes
        region box block -4 4 -4 4 -5 5
        create_box 1 box
        create_atoms 1 single 0 0 0
        set atom 1 shape {ROD}
        set atom 1 density 1.0
        set atom 1 quat 0 1 0 {90.0 - tilt}
        velocity all set {velocity[0]} {velocity[1]} {velocity[2]}
        pair_style granular/ellipsoid
        pair_coeff * * {LAW}
        {wall}
        fix i all nve/asphere
        compute move all ke
        compute rot all erotate/asphere
        timestep 2e-4
        """)
    if any(spin):
        lmp.command(f"set atom 1 angmom {spin[0]} {spin[1]} {spin[2]}")
    return lmp


def pipe(radius):
    return (f"region r cylinder z 0 0 {radius} INF INF\n"
            f"fix w all wall/gran/region/ellipsoid {LAW} region r")


def bowl(radius):
    return (f"region r sphere 0 0 0 {radius}\n"
            f"fix w all wall/gran/region/ellipsoid {LAW} region r")


def planes(radius):
    return f"fix w all wall/gran/ellipsoid {LAW} xplane {-radius} {radius}"


def forces(lmp):
    lmp.command("run 0 post no")
    f = np.array(lmp.numpy.extract_atom("f")[0], dtype=float).copy()
    t = np.array(lmp.numpy.extract_atom("torque")[0], dtype=float).copy()
    lmp.close()
    return f, t


def test_symmetric_rod_across_a_pipe_feels_no_net_force():
    """The rod tilted by 60 degrees reaches 2.61 either side of the axis; a pipe of radius 2.5
    holds both its ends, as two planes at x = -2.5 and 2.5 do: no net force, and the torque of
    both contacts."""
    f_pipe, t_pipe = forces(rod_scene(pipe(2.5), 60.0))
    f_planes, t_planes = forces(rod_scene(planes(2.5), 60.0))
    scale = np.abs(t_planes).max()
    assert scale > 0.0
    np.testing.assert_allclose(f_planes, 0.0, atol=1e-10 * scale)
    np.testing.assert_allclose(f_pipe, 0.0, atol=1e-10 * scale)
    # the ends' deepest points lie where the pipe touches the planes: the same torque
    np.testing.assert_allclose(t_pipe, t_planes, rtol=1e-10, atol=1e-10 * scale)


def test_symmetric_rod_in_a_bowl_feels_no_net_force():
    """The rod centred in a sphere region narrower than it: both tips, no net force (the
    deeper tip alone: 112)."""
    f, t = forces(rod_scene(bowl(2.95), 60.0))
    np.testing.assert_allclose(f, 0.0, atol=1e-7)
    np.testing.assert_allclose(t, 0.0, atol=1e-7)
    lmp = rod_scene(bowl(2.95) + " contacts", 60.0)
    lmp.command("run 0 post no")
    assert lmp.numpy.extract_fix("w", 1, 2)[0][0] == 2.0
    lmp.close()


def test_symmetric_rod_across_a_hopper_feels_no_sideways_force():
    """The rod lying across a hopper (a cone, radius 2.9 where the rod lies) at its axis: both
    tips touch the side, the sideways pushes cancel and the two lift it (the deeper tip
    alone pushed it sideways)."""
    hopper = ("region r cone z 0 0 1.9 3.9 -4 4\n"
              f"fix w all wall/gran/region/ellipsoid {LAW} region r contacts")
    lmp = rod_scene(hopper, 90.0)
    lmp.command("run 0 post no")
    assert lmp.numpy.extract_fix("w", 1, 2)[0][0] == 2.0
    f = np.array(lmp.numpy.extract_atom("f")[0], dtype=float)
    lmp.close()
    assert f[2] > 0.0
    np.testing.assert_allclose(f[:2], 0.0, atol=1e-10 * f[2])


def bounce_energy(wall, steps, tilt, velocity, spin, offset):
    """The rod started at `offset` from the axis with `velocity` and angular momentum `spin`;
    returns the kinetic energy (translation and rotation) whenever no wall touches it,
    relative to the first, and the largest number of contacts seen at once (every 100
    steps)."""
    lmp = rod_scene(wall + " contacts", tilt, velocity=velocity, spin=spin)
    lmp.command("displace_atoms all move {} {} {}".format(*offset))
    energies, most = [], 0
    for _ in range(steps // 100):
        lmp.command("run 100 post no")
        touching = int(lmp.numpy.extract_fix("w", 1, 2)[0][0])
        most = max(most, touching)
        if touching == 0:
            energies.append(lmp.extract_compute("move", 0, 0) + lmp.extract_compute("rot", 0, 0))
    lmp.close()
    return np.array(energies) / energies[0] - 1.0, most


# the rod tilted 55 degrees from the pipe's axis (it reaches 2.47 either side) turning about y,
# a little off the axis and drifting sideways, in a pipe or between planes 2.6 from the axis:
# past 59 degrees both its ends reach the sides, it bounces back, turns through the axis and
# meets the other sides; in a bowl of radius 3.03 (the rod 3 long either side), moving across
# its length: both tips reach the bowl at once
TURNING = dict(tilt=55.0, velocity=(0.01, 0.004, 0.0), spin=(0.0, 5.8, 0.0),
               offset=(0.004, -0.002, 0.0))
ACROSS = dict(tilt=58.0, velocity=(0.01, 0.4, 0.0), spin=(0.0, 0.0, 0.0),
              offset=(0.002, 0.0, 0.001))


@pytest.mark.parametrize("wall,motion", [(pipe(2.6), TURNING), (planes(2.6), TURNING),
                                         (bowl(3.03), ACROSS)], ids=["pipe", "planes", "bowl"])
def test_bouncing_rod_keeps_its_energy(wall, motion):
    """pipe 2.7e-7, planes 2.5e-7, bowl 6e-9; the deeper contact alone: 9e-4 in the pipe,
    3.6e-3 in the bowl"""
    drift, most = bounce_energy(wall, 40000, **motion)
    assert most == 2    # both ends at once
    assert len(drift) >= 100
    assert np.abs(drift).max() < 1e-5, np.abs(drift).max()


def test_each_contact_region_keeps_its_own_friction_history():
    """With friction (tangential history) the rod wedged across the pipe and sliding along
    it (until it turns free): each end's contact keeps its own tangential spring. Its ends
    touch where two planes would, with the same normals, and by symmetry stay there: the
    pipe's run is the planes'."""
    law = "hertz 1e4 0 tangential history 1e3 0.5"
    runs = {}
    for name, wall in (("pipe", pipe(2.58)), ("planes", planes(2.58))):
        lmp = rod_scene(wall.replace(LAW, law), 60.0, velocity=(0.0, 0.0, 0.5))
        out = []
        for _ in range(10):
            lmp.command("run 20 post no")
            out.append(np.concatenate([np.array(lmp.numpy.extract_atom(k)[0], dtype=float)
                                       for k in ("x", "v", "angmom", "f", "torque")]))
        lmp.close()
        runs[name] = np.array(out)
    scale = np.abs(runs["planes"]).max(axis=0)
    assert np.abs(runs["planes"][0, 9:12]).max() > 0.0    # the walls push
    assert runs["planes"][-1, 5] < 0.49    # friction slows the slide
    np.testing.assert_allclose(runs["pipe"], runs["planes"], rtol=0, atol=1e-9 * scale.max())


def test_contact_regions_history_survives_restart(tmp_path):
    """The wedged rod sliding with friction, written to a restart file while both ends touch:
    read back (the region and fix given again), each end's slot (its normal and tangential
    spring) continues as if the run had not stopped."""
    law = "hertz 1e4 0 tangential history 1e3 0.5"
    restart = tmp_path / "rod.restart"

    def state(lmp):
        return np.concatenate([np.array(lmp.numpy.extract_atom(k)[0], dtype=float)
                               for k in ("x", "v", "angmom")])

    lmp = rod_scene(pipe(2.58).replace(LAW, law) + " contacts", 60.0, velocity=(0.0, 0.0, 0.5))
    lmp.command("run 40 post no")
    assert lmp.numpy.extract_fix("w", 1, 2)[0][0] == 2.0    # both ends touch
    lmp.command(f"write_restart {restart}")
    lmp.command("run 60 post no")
    ref = state(lmp)
    lmp.close()

    lmp = new_lammps()
    lmp.commands_string(f"""
        read_restart {restart}
        comm_modify vel yes
        pair_coeff * * {LAW}
        {pipe(2.58).replace(LAW, law)}
        fix i all nve/asphere
        timestep 2e-4
        run 60 post no
        """)
    cont = state(lmp)
    lmp.close()
    np.testing.assert_allclose(cont, ref, rtol=0, atol=1e-12 * np.abs(ref).max())
