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
     "Fix nve/ellipsoid requires extended particles: atom 2 has no shape"),
    ("atom_style ellipsoid", "fix i all nve/ellipsoid spin", "unknown argument spin"),
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
