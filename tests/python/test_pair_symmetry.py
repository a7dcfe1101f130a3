"""The same physics whatever the atom order, and under atom_style ellipsoid superellipsoid."""
import numpy as np

import geometry
from conftest import new_lammps

SEMI = (0.7, 0.5, 0.36)


def configuration(seed=8, n=40):
    """Random positions in a small periodic box (many overlaps), orientations, velocities."""
    rng = np.random.default_rng(seed)
    pos = rng.uniform(0.0, 3.2, (n, 3))
    quat = geometry.random_quats(rng, n)
    vel = rng.normal(0.0, 0.5, (n, 3))
    angmom = rng.normal(0.0, 0.05, (n, 3))
    return pos, quat, vel, angmom


def forces(order, atom_style="ellipsoid", tangential="viscous 0.3"):
    """Forces and torques (rows in the configuration's order) with atoms created in `order`."""
    pos, quat, vel, angmom = configuration()
    lmp = new_lammps()
    lmp.commands_string(f"""
        units lj
        atom_style {atom_style}
        atom_modify map array
        comm_modify vel yes
        boundary p p p
        region box block 0 3.2 0 3.2 0 3.2
        create_box 1 box
        """)
    for k in order:
        lmp.command("create_atoms 1 single {} {} {}".format(*pos[k]))
    lmp.command("set type 1 mass 1.0")
    lmp.command("set type 1 shape {} {} {}".format(*(2 * np.array(SEMI))))
    if "superellipsoid" in atom_style:
        lmp.command("set type 1 block 2.0 2.0")
    for tag, k in enumerate(order, start=1):
        lmp.command("set atom {} quat {:.17g} {:.17g} {:.17g} {:.17g}".format(
            tag, *geometry.axis_angle(quat[k])))
    nlocal = lmp.extract_global("nlocal")
    ids = lmp.numpy.extract_atom("id")[:nlocal]
    v = lmp.numpy.extract_atom("v")
    am = lmp.numpy.extract_atom("angmom")
    for row, tag in enumerate(ids):
        v[row][:] = vel[order[tag - 1]]
        am[row][:] = angmom[order[tag - 1]]
    lmp.command("pair_style granular/ellipsoid")
    lmp.command(f"pair_coeff * * hertz 1e4 30 tangential {tangential}")
    lmp.command("run 0")
    out = np.zeros((len(order), 6))
    f = lmp.numpy.extract_atom("f")
    t = lmp.numpy.extract_atom("torque")
    for row, tag in enumerate(ids):
        out[order[tag - 1], :3] = f[row]
        out[order[tag - 1], 3:] = t[row]
    lmp.close()
    return out


def test_atom_order_does_not_matter():
    n = len(configuration()[0])
    forward = forces(list(range(n)))
    backward = forces(list(reversed(range(n))))
    scale = np.abs(forward).max()
    assert np.count_nonzero(np.abs(forward[:, :3]).sum(axis=1)) > n // 2, "too few contacts"
    np.testing.assert_allclose(backward, forward, rtol=0, atol=1e-12 * scale)


def test_superellipsoid_block_2_is_the_same_ellipsoid():
    """One configuration under atom_style ellipsoid and ellipsoid superellipsoid (block 2 2):
    the pair reads the same shapes, orientations and (stored) inertia."""
    n = len(configuration()[0])
    plain = forces(list(range(n)))
    superellipsoid = forces(list(range(n)), atom_style="ellipsoid superellipsoid")
    scale = np.abs(plain).max()
    np.testing.assert_allclose(superellipsoid, plain, rtol=0, atol=1e-12 * scale)
