"""fix damping/cundall/ellipsoid: Cundall's local damping for ellipsoids (a settling aid).

Each component of an atom's force (torque) is scaled by 1 - gamma_l (gamma_a) where it drives
the motion, f_k v_k >= 0 (t_k omega_k >= 0), and by 1 + gamma where it brakes it: LAMMPS's
fix damping/cundall, which needs atom attribute omega and so refuses atom_style ellipsoid.
Here omega comes from the angular momentum, omega = R I^-1 R^T L.

- Triaxial ellipsoids in contact (pair, floor, friction, gravity; random orientations,
  velocities and angular momenta): the damped forces and torques after run 0 are the undamped
  ones scaled by that rule, omega computed here from the quaternions set and the moments
  m (b^2 + c^2) / 5.
- Spheres against LAMMPS's fix damping/cundall (atom_style sphere, the same pair and wall
  laws, no friction: nothing spins, so the two styles' spin velocities cannot differ): the
  trajectories agree step for step, and differ from undamped ones.
- in.deposit's cundall variable: the damping is switched on once the batch has landed (never
  during the fall and the impacts), off when the rest criterion first holds, and the deposit
  is at rest on undamped samples at least two chunks later.
- Bad input: a gamma outside [0, 1], an extra word, atom_style sphere.
"""
import re

import numpy as np
import pytest

import ed_helpers_pour as h
import geometry
import scenes
from conftest import new_lammps

GAMMA_L, GAMMA_A = 0.3, 0.6
SEMI = (0.5, 0.35, 0.25)
LAW = "hertz 1e4 20 tangential history 2e3 0.5"


def ellipsoid_cluster(damping):
    rng = np.random.default_rng(7)
    positions = [(1.0, 1.0, 0.3), (1.75, 1.0, 0.3), (1.35, 1.5, 0.75), (2.6, 2.4, 0.35)]
    quats = geometry.random_quats(rng, len(positions))
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box("ellipsoid", (4.0, 4.0, 4.0), positions, 0.5))
    lmp.command("set type 1 shape {} {} {}".format(*(2 * np.array(SEMI))))
    for i, q in enumerate(quats):
        lmp.command("set atom {} quat {!r} {!r} {!r} {!r}".format(i + 1, *geometry.axis_angle(q)))
    v = lmp.numpy.extract_atom("v")
    angmom = lmp.numpy.extract_atom("angmom")
    for i in range(len(positions)):
        v[i][:] = rng.normal(0.0, 0.5, 3)
        angmom[i][:] = rng.normal(0.0, 0.05, 3)
    lmp.commands_string(f"""
        pair_style granular/ellipsoid
        pair_coeff * * {LAW}
        fix floor all wall/gran/ellipsoid {LAW} zplane 0 NULL
        fix g all gravity 1.0 vector 0 0 -1
        fix i all nve/ellipsoid
        {"fix d all damping/cundall/ellipsoid %g %g" % (GAMMA_L, GAMMA_A) if damping else ""}
        timestep 1e-4
        run 0 post no
        """)
    n = len(positions)
    out = {name: np.array(lmp.numpy.extract_atom(name)[:n], dtype=float)
           for name in ("f", "torque", "v", "angmom", "rmass")}
    lmp.close()
    out["quat"] = quats
    return out


def expected_omega(state):
    """omega = R I^-1 R^T L per atom"""
    a, b, c = SEMI
    omega = []
    for q, m, L in zip(state["quat"], state["rmass"], state["angmom"]):
        moments = m / 5.0 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
        r = geometry.rotation(q)
        omega.append(r @ ((r.T @ L) / moments))
    return np.array(omega)


def scaled(value, velocity, gamma):
    return value * (1.0 - gamma * np.where(value * velocity >= 0.0, 1.0, -1.0))


def test_forces_and_torques_follow_the_rule_for_ellipsoids():
    plain, damped = ellipsoid_cluster(False), ellipsoid_cluster(True)
    omega = expected_omega(plain)
    scale_f, scale_t = np.abs(plain["f"]).max(), np.abs(plain["torque"]).max()
    assert scale_t > 0.0
    np.testing.assert_allclose(damped["f"], scaled(plain["f"], plain["v"], GAMMA_L),
                               rtol=1e-12, atol=1e-12 * scale_f)
    np.testing.assert_allclose(damped["torque"], scaled(plain["torque"], omega, GAMMA_A),
                               rtol=1e-12, atol=1e-12 * scale_t)
    # both branches of the rule are exercised, for forces and for torques
    for value, velocity in ((plain["f"], plain["v"]), (plain["torque"], omega)):
        product = (value * velocity)[np.abs(value) > 1e-9 * np.abs(value).max()]
        assert (product > 0).any() and (product < 0).any()


def falling_spheres(style, damping, steps):
    positions = [(1.0, 1.0, 0.6), (2.0, 1.1, 0.9), (1.5, 2.2, 1.4), (3.0, 3.0, 0.7)]
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box(style, (4.0, 4.0, 4.0), positions, 0.5))
    for i in range(len(positions)):
        lmp.command(f"set atom {i + 1} vx {0.3 * (i - 1.5)} vy {0.2 * i} vz -0.5")
    if style == "sphere":
        law = ("hertz/material 1e5 0.8 0.3 damping coeff_restitution "
               "tangential linear_nohistory 0 0")
        lmp.commands_string(f"""
            pair_style granular
            pair_coeff * * {law}
            fix floor all wall/gran granular {law} zplane 0 NULL
            fix i all nve/sphere""")
    else:
        lmp.commands_string("""
            pair_style granular/ellipsoid
            pair_coeff * * hertz/material 1e5 0.3 0.8
            fix floor all wall/gran/ellipsoid hertz/material 1e5 0.3 0.8 zplane 0 NULL
            fix i all nve/ellipsoid""")
    lmp.command("fix g all gravity 1.0 vector 0 0 -1")
    if damping:
        lmp.command(f"fix d all damping/cundall{'' if style == 'sphere' else '/ellipsoid'} "
                    "0.5 0.5")
    lmp.command("timestep 1e-4")
    rows = []
    for n in steps:
        lmp.command(f"run {n} post no")
        rows.append(np.array(lmp.numpy.extract_atom("x")[: len(positions)], dtype=float))
    lmp.close()
    return np.array(rows)


def test_spheres_match_lammps_fix_damping_cundall():
    steps = (0,) + (200,) * 10
    ours = falling_spheres("ellipsoid", True, steps)
    ref = falling_spheres("sphere", True, steps)
    np.testing.assert_allclose(ours, ref, rtol=0, atol=1e-10)
    undamped = falling_spheres("sphere", False, steps)
    assert np.abs(undamped - ref).max() > 1e-3


def test_deposit_switches_the_damping_off_before_rest(tmp_path):
    out = tmp_path / "cundall"
    out.mkdir()
    lmp = h.deposit_lammps(out, {"N": "60", "cundall": "0.7", "chunk": "500", "image": "0",
                                 "window": "0", "out": str(out), "width": "5"})
    assert not lmp.has_id("fix", "cundall")
    lmp.close()
    log = (out / "log.lammps").read_text()
    landed = re.search(r"^ELLIPSOID_DEP: landed after (\d+) steps; Cundall damping 0.7 on",
                       log, re.M)
    switched = re.search(r"^ELLIPSOID_DEP: settled under Cundall damping after (\d+) steps; "
                         r"switched off", log, re.M)
    rest = re.search(r"^ELLIPSOID_DEP: at rest after (\d+) steps", log, re.M)
    assert landed and switched and rest
    # on only after the landing: the pour's fall and impacts are undamped
    progress = [(int(a), float(b), float(c)) for a, b, c in re.findall(
        r"^PROGRESS step (\d+) inserted \S+ of \S+ KE/particle (\S+) target \S+ flight (\S+)",
        log, re.M)]
    before = [p for p in progress if p[0] < int(landed.group(1))]
    assert before and all(ke >= 1e-3 or flight >= 1.0 for _, ke, flight in before)
    assert int(rest.group(1)) >= int(switched.group(1)) + 2 * 500


@pytest.mark.parametrize("words, message", [
    ("1.5 0.2", "gamma_l must be in [0, 1], got 1.5"),
    ("0.2 -0.1", "gamma_a must be in [0, 1], got -0.1"),
    ("0.2 0.2 scale", "Unknown Fix damping/cundall/ellipsoid argument: scale"),
])
def test_bad_arguments(words, message):
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box("ellipsoid", (4.0, 4.0, 4.0), [(1, 1, 1)], 0.5))
    with pytest.raises(Exception, match=re.escape(message)):
        lmp.command(f"fix d all damping/cundall/ellipsoid {words}")
    lmp.close()


def test_refuses_atom_style_sphere():
    lmp = new_lammps()
    lmp.commands_string(scenes.spheres_in_box("sphere", (4.0, 4.0, 4.0), [(1, 1, 1)], 0.5))
    with pytest.raises(Exception, match="Fix damping/cundall/ellipsoid"):
        lmp.command("fix d all damping/cundall/ellipsoid 0.2 0.2")
    lmp.close()
