"""rolling sds: the elastic-plastic rolling resistance (spring, dashpot, slider with history).

* Sphere limit: two overlapping spheres held in place (no integrator) with spins; the rolling
  angle grows step by step until the slider holds. granular/ellipsoid's torques and forces
  equal LAMMPS pair granular's `rolling sds` with the same coefficients at every step (no
  tangential force: LAMMPS's tangential velocity takes the spins at the full radius, this
  package's at the contact point, r - delta/2, where both put the torque arm;
  doc/pair_granular_ellipsoid.rst).
* Round-off stays round-off: a pile at rest continued from positions moved by a few units of
  their last place keeps torques that differ by round-off, as without rolling resistance;
  `rolling constant` switches its full torque on for any rolling speed (documented as the
  discontinuous model; measured here, not asserted).
"""
import numpy as np
import pytest

from conftest import new_lammps

RADIUS = 0.5
KN_G, ETA_N0 = 1.0e5, 40.0
ROLLING = "1.0e5 2.0 0.3"    # k_r gamma_r mu_r
STEPS = 40


def spheres(lmp, style):
    lmp.commands_string(f"""
        units lj
        atom_style {style}
        atom_modify map array
        newton off
        comm_modify vel yes
        boundary p p p
        region box block 0 4 0 4 0 4
        create_box 1 box
        create_atoms 1 single 1.50 2.0 2.0
        create_atoms 1 single 2.42 2.3 1.9
        timestep 1.0e-4
        """)
    size = "diameter 1.0" if style == "sphere" else "shape 1.0 1.0 1.0"
    lmp.command(f"set type 1 {size}")
    lmp.command("set type 1 density 1.0")


def torques_each_step(style):
    """(forces, torques) of the two spheres at each of STEPS steps, positions and spins held."""
    lmp = new_lammps()
    spheres(lmp, style)
    omega = np.array([[3.0, -7.0, 11.0], [-5.0, 2.0, 4.0]])
    mass = 4.0 / 3.0 * np.pi * RADIUS**3
    if style == "sphere":
        lmp.numpy.extract_atom("omega")[:2] = omega
        lmp.command("pair_style granular")
        lmp.command(f"pair_coeff * * hertz {KN_G} {ETA_N0} damping viscoelastic tangential "
                    f"linear_nohistory 0 0 rolling sds {ROLLING}")
    else:
        lmp.numpy.extract_atom("angmom")[:2] = 0.4 * mass * RADIUS**2 * omega
        r_eff, m_eff = RADIUS / 2.0, mass / 2.0
        lmp.command("pair_style granular/ellipsoid")
        lmp.command(f"pair_coeff * * hertz {KN_G * np.sqrt(r_eff)} "
                    f"{ETA_N0 * m_eff * np.sqrt(r_eff)} rolling sds {ROLLING}")
    forces, torques = [], []
    lmp.command("run 0")
    for _ in range(STEPS):
        lmp.command("run 1 pre no post no")
        forces.append(lmp.numpy.extract_atom("f")[:2].copy())
        torques.append(lmp.numpy.extract_atom("torque")[:2].copy())
    lmp.close()
    return np.array(forces), np.array(torques)


def test_sphere_limit_equals_pair_granular_rolling_sds():
    f_ref, t_ref = torques_each_step("sphere")
    f, t = torques_each_step("ellipsoid")
    scale_f, scale_t = np.abs(f_ref).max(), np.abs(t_ref).max()
    # the spring loads, then the slider holds: the torque (no tangential force: all rolling)
    # grows, then stays at mu_r R* F_n
    size = np.linalg.norm(t_ref[:, 0], axis=1)
    limit = 0.3 * RADIUS / 2 * np.linalg.norm(f_ref[:, 0], axis=1)
    assert size[0] < 0.9 * limit[0] and size[-1] == pytest.approx(limit[-1], rel=1e-12)
    np.testing.assert_allclose(f, f_ref, rtol=0, atol=1e-10 * scale_f)
    np.testing.assert_allclose(t, t_ref, rtol=0, atol=1e-10 * scale_t)


PILE = """
units lj
atom_style ellipsoid
atom_modify map array
boundary p p f
comm_modify vel yes
region box block 0 3.56 0 2.76 0 3
create_box 1 box
{atoms}
set type 1 shape 0.9 0.7 0.5
set type 1 density 1.0
pair_style granular/ellipsoid
pair_coeff * * hertz 1.0e4 50.0 tangential history 2.0e3 0.5 {rolling}
fix wall all wall/gran/ellipsoid hertz 1.0e4 50.0 tangential history 2.0e3 0.5 zplane 0.0 NULL
fix grav all gravity 1.0 vector 0 0 -1
fix integrate all nve/asphere
timestep 2.0e-4
fix settle all viscous 2.0
run 10000
unfix settle
run 2000
"""


# two layers of flat ellipsoids (semi-axes 0.45 0.35 0.25), neighbours overlapping slightly,
# the upper layer in the hollows of the lower
ATOMS = "\n".join(f"create_atoms 1 single {0.5 + 0.89 * i + 0.445 * k} {0.5 + 0.69 * j + 0.345 * k} "
                  f"{0.249 + 0.45 * k} remap yes" for i in range(4) for j in range(4) for k in range(2))


def torque_after_two_steps(rolling, perturb):
    lmp = new_lammps()
    lmp.commands_string(PILE.format(rolling=rolling, atoms=ATOMS))
    if perturb:    # every coordinate moved by a few units of its last place
        n = lmp.extract_global("nlocal")
        x = lmp.numpy.extract_atom("x")[:n]
        x += np.random.default_rng(5).choice([-2e-15, 2e-15], x.shape)
    lmp.command("run 2")
    n = lmp.extract_global("nlocal")
    order = np.argsort(lmp.numpy.extract_atom("id")[:n])
    torque = lmp.numpy.extract_atom("torque")[:n][order].copy()
    ke = lmp.get_thermo("ke")
    lmp.close()
    return torque, ke


@pytest.mark.parametrize("rolling", ["", "rolling sds 1.0e3 2.0 0.3"])
def test_round_off_stays_round_off(rolling):
    torque, ke = torque_after_two_steps(rolling, perturb=False)
    again, _ = torque_after_two_steps(rolling, perturb=True)
    assert ke < 1e-8, "the pile is not at rest"
    # a particle's weight times its smallest semi-axis: the torques' physical scale (at rest
    # the pile's net torques nearly cancel, so their own size is no scale)
    scale = 4.0 / 3.0 * np.pi * 0.45 * 0.35 * 0.25 * 1.0 * 0.25
    assert np.abs(again - torque).max() <= 1e-10 * scale


if __name__ == "__main__":    # the discontinuous model, for the documentation
    torque, _ = torque_after_two_steps("rolling constant 0.1", perturb=False)
    again, _ = torque_after_two_steps("rolling constant 0.1", perturb=True)
    print("rolling constant: largest torque", np.abs(torque).max(), "largest difference",
          np.abs(again - torque).max())
