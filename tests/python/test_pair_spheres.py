"""Sphere limit: for spheres, granular/ellipsoid must give LAMMPS `pair granular`'s forces.

Mapping (doc/pair_granular_ellipsoid.rst): pair granular
  hertz kn_g eta_n0 damping viscoelastic tangential linear_nohistory 0 0
gives F = kn_g sqrt(R*) xi^3/2 + eta_n0 m* sqrt(R*) xi^1/2 dxi/dt, so
  kn = kn_g sqrt(R*),  K = eta_n0 m* sqrt(R*)
for equal spheres of radius R (R* = R/2) and mass m (m* = m/2).
"""
import numpy as np
import pytest

import geometry
from conftest import new_lammps

RADIUS = 0.5
DENSITY = 1.0
KN_G = 1.0e5
ETA_N0 = 40.0


def cluster(seed=3, n=12):
    """Random spheres in a small box, many overlapping by up to ~5 % of the radius."""
    rng = np.random.default_rng(seed)
    pos = []
    while len(pos) < n:
        p = rng.uniform(0.6, 2.9, 3)
        if all(np.linalg.norm(p - q) > 2 * RADIUS * 0.95 for q in pos):
            pos.append(p)
    vel = rng.normal(0.0, 0.3, (n, 3))
    omega = rng.normal(0.0, 0.5, (n, 3))
    quats = geometry.random_quats(rng, n)
    return np.array(pos), vel, omega, quats


def build(lmp, style, pos, vel, omega, quats, newton):
    lmp.commands_string(f"""
        units lj
        atom_style {style}
        atom_modify map array
        newton {newton}
        comm_modify vel yes
        boundary p p p
        region box block 0 3.5 0 3.5 0 3.5
        create_box 1 box
        """)
    for k, p in enumerate(pos):
        lmp.command(f"create_atoms 1 single {p[0]} {p[1]} {p[2]}")
    if style == "sphere":
        lmp.command(f"set type 1 diameter {2 * RADIUS}")
    else:
        lmp.command(f"set type 1 shape {2 * RADIUS} {2 * RADIUS} {2 * RADIUS}")
    lmp.command(f"set type 1 density {DENSITY}")
    return lmp


def run_forces(style, pos, vel, omega, quats, newton="off"):
    lmp = new_lammps()
    build(lmp, style, pos, vel, omega, quats, newton)
    mass = DENSITY * 4.0 / 3.0 * np.pi * RADIUS**3
    inertia = 0.4 * mass * RADIUS**2
    # per-atom velocities and spins through the atom arrays (ids are 1..n in order)
    nlocal = lmp.extract_global("nlocal")
    v = lmp.numpy.extract_atom("v")
    ids = lmp.numpy.extract_atom("id")[:nlocal]
    for k, tag in enumerate(ids):
        v[k][:] = vel[tag - 1]
    if style == "sphere":
        om = lmp.numpy.extract_atom("omega")
        for k, tag in enumerate(ids):
            om[k][:] = omega[tag - 1]
        lmp.command("pair_style granular")
        lmp.command(f"pair_coeff * * hertz {KN_G} {ETA_N0} damping viscoelastic "
                    "tangential linear_nohistory 0 0")
    else:
        for tag in range(1, len(pos) + 1):
            lmp.command("set atom {} quat {:.17g} {:.17g} {:.17g} {:.17g}".format(
                tag, *geometry.axis_angle(quats[tag - 1])))
        am = lmp.numpy.extract_atom("angmom")
        for k, tag in enumerate(ids):
            am[k][:] = inertia * omega[tag - 1]    # spheres: L = I omega in any frame
        r_eff = RADIUS / 2.0
        m_eff = mass / 2.0
        kn = KN_G * np.sqrt(r_eff)
        damp = ETA_N0 * m_eff * np.sqrt(r_eff)
        lmp.command("pair_style granular/ellipsoid")
        lmp.command(f"pair_coeff * * hertz {kn} {damp} tangential none")
    lmp.command("run 0")
    nlocal = lmp.extract_global("nlocal")
    ids = lmp.numpy.extract_atom("id")[:nlocal].copy()
    order = np.argsort(ids)
    f = lmp.numpy.extract_atom("f")[:nlocal][order].copy()
    t = lmp.numpy.extract_atom("torque")[:nlocal][order].copy()
    lmp.close()
    return f, t


@pytest.mark.parametrize("newton", ["off", "on"])
def test_sphere_forces_equal_pair_granular(newton):
    pos, vel, omega, quats = cluster()
    f_ref, _ = run_forces("sphere", pos, vel, omega, quats, newton)
    f, torque = run_forces("ellipsoid", pos, vel, omega, quats, newton)
    assert np.count_nonzero(np.linalg.norm(f_ref, axis=1)) >= 4, "the cluster has too few contacts"
    scale = np.abs(f_ref).max()
    np.testing.assert_allclose(f, f_ref, rtol=1e-10, atol=1e-10 * scale)
    # forces on spheres act through the centres: no torque
    assert np.abs(torque).max() <= 1e-10 * scale * RADIUS


def test_newton_on_equals_off():
    pos, vel, omega, quats = cluster(seed=3)
    f_off, t_off = run_forces("ellipsoid", pos, vel, omega, quats, "off")
    f_on, t_on = run_forces("ellipsoid", pos, vel, omega, quats, "on")
    scale = np.abs(f_off).max()
    assert scale > 0.0
    np.testing.assert_allclose(f_on, f_off, rtol=1e-12, atol=1e-12 * scale)
    np.testing.assert_allclose(t_on, t_off, rtol=1e-12, atol=1e-12 * scale)
