"""hertz/material between unlike materials, LAMMPS's spelling of the law, and named materials.

Specification:
- unlike types mix to Hertz's reduced modulus 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2 and the
  geometric mean of the restitution coefficients: for spheres the forces equal LAMMPS's
  `pair granular hertz/material E e nu damping coeff_restitution` to round-off;
- LAMMPS's order `hertz/material E e nu damping coeff_restitution` is accepted and is the
  same law as this package's `hertz/material E nu e`; other LAMMPS damping models are refused
  with a message saying what to write;
- a wall is of the particles' material unless `wall_material E nu | NAME | rigid` says
  otherwise;
- named materials hold SI values: converted under units cgs (same physics as si), refused
  under units lj; the file is read once per command, and not at all for numbers.
"""
import math
import re

import numpy as np
import pytest

import ed_helpers_pour as h
import scenes
from conftest import new_lammps

E1, NU1, REST1, R1 = 1.0e7, 0.2, 0.7, 0.5
E2, NU2, REST2, R2 = 4.0e7, 0.4, 0.9, 0.4
DENSITY = 1.0


def unlike_cluster(seed=11, n=14):
    """Spheres of two types (radii R1, R2) in a small periodic box, many overlapping by up
    to ~5 % of the radius, with random velocities (so the damping acts) and spins."""
    rng = np.random.default_rng(seed)
    pos, types = [], []
    while len(pos) < n:
        p = rng.uniform(0.6, 2.9, 3)
        t = 1 + len(pos) % 2
        r = R1 if t == 1 else R2
        if all(np.linalg.norm(p - q) > 0.95 * (r + (R1 if s == 1 else R2))
               for q, s in zip(pos, types)):
            pos.append(p)
            types.append(t)
    return np.array(pos), types, rng.normal(0.0, 0.3, (n, 3)), rng.normal(0.0, 0.5, (n, 3))


def cluster_forces(style, coeffs, seed=11):
    """Forces on the unlike cluster: style 'sphere' runs LAMMPS's pair granular, 'ellipsoid'
    this package; coeffs are the pair_coeff lines."""
    pos, types, vel, omega = unlike_cluster(seed)
    lmp = new_lammps()
    lmp.commands_string(scenes.particle_box(style, 0, 3.5, ntypes=2))
    for p, t in zip(pos, types):
        lmp.command(f"create_atoms {t} single {p[0]} {p[1]} {p[2]}")
    for t, r in ((1, R1), (2, R2)):
        size = f"diameter {2 * r}" if style == "sphere" else f"shape {2 * r} {2 * r} {2 * r}"
        lmp.command(f"set type {t} {size}")
    lmp.command(f"set type * density {DENSITY}")
    nlocal = lmp.extract_global("nlocal")
    ids = lmp.numpy.extract_atom("id")[:nlocal]
    v = lmp.numpy.extract_atom("v")
    spin = lmp.numpy.extract_atom("omega" if style == "sphere" else "angmom")
    for k, tag in enumerate(ids):
        v[k][:] = vel[tag - 1]
        r = R1 if types[tag - 1] == 1 else R2
        inertia = 0.4 * DENSITY * 4.0 / 3.0 * math.pi * r**3 * r**2
        spin[k][:] = omega[tag - 1] * (1.0 if style == "sphere" else inertia)
    lmp.command("pair_style granular" if style == "sphere" else "pair_style granular/ellipsoid")
    for line in coeffs:
        lmp.command(f"pair_coeff {line}")
    lmp.command("run 0")
    order = np.argsort(lmp.numpy.extract_atom("id")[:nlocal])
    f = lmp.numpy.extract_atom("f")[:nlocal][order].copy()
    lmp.close()
    return f


LAMMPS_COEFFS = [f"1 1 hertz/material {E1} {REST1} {NU1} damping coeff_restitution "
                 "tangential linear_nohistory 0 0",
                 f"2 2 hertz/material {E2} {REST2} {NU2} damping coeff_restitution "
                 "tangential linear_nohistory 0 0"]


def assert_same_forces(f, f_ref):
    scale = np.abs(f_ref).max()
    assert scale > 0.0
    np.testing.assert_allclose(f, f_ref, rtol=1e-10, atol=1e-10 * scale)


def test_unlike_spheres_equal_pair_granular():
    f_ref = cluster_forces("sphere", LAMMPS_COEFFS)
    assert np.count_nonzero(np.linalg.norm(f_ref, axis=1)) >= 6, "too few contacts"
    f = cluster_forces("ellipsoid", [f"1 1 hertz/material {E1} {NU1} {REST1}",
                                     f"2 2 hertz/material {E2} {NU2} {REST2}"])
    assert_same_forces(f, f_ref)


def test_lammps_order_is_the_same_law():
    ours = cluster_forces("ellipsoid", [f"1 1 hertz/material {E1} {NU1} {REST1}",
                                        f"2 2 hertz/material {E2} {NU2} {REST2}"])
    lammps_order = cluster_forces("ellipsoid", [
        f"1 1 hertz/material {E1} {REST1} {NU1} damping coeff_restitution",
        f"2 2 hertz/material {E2} {REST2} {NU2} damping coeff_restitution tangential none"])
    np.testing.assert_array_equal(lammps_order, ours)




@pytest.mark.parametrize("coeff,message", [
    ("hertz/material 1e7 0.5 0.3 damping viscoelastic",
     "damping viscoelastic is not available: hertz/material damps by the restitution "
     "coefficient e; write 'hertz/material E nu e' or, in LAMMPS's order, "
     "'hertz/material E e nu damping coeff_restitution'"),
    ("hertz/material 1e7 0.5 0.3 damping tsuji", "damping tsuji is not available"),
    ("hertz 1e4 10 damping coeff_restitution", "applies only to hertz/material"),
    ("hertz/material 1e7 0.5 0.3 damping", "missing argument(s) for damping"),
    # a LAMMPS line without a damping word still stops at LAMMPS's tangential model
    ("hertz/material 1e7 0.5 0.3 tangential linear_history 1e3 0.5 0.3",
     "unknown tangential model 'linear_history' (expected none, viscous or history); "
     "'linear_history' is LAMMPS pair granular's syntax, whose hertz/material numbers are in "
     "another order (E damping nu)"),
])
def test_other_lammps_damping_is_refused(coeff, message):
    lmp = new_lammps()
    try:
        with pytest.raises(Exception, match=re.escape(message)):
            lmp.commands_string(scenes.empty_pair_box() + f"pair_coeff * * {coeff}\n")
    finally:
        lmp.close()


# ---- the wall's material --------------------------------------------------------------------

RADIUS, OVERLAP = 0.5, 2.0e-3


def wall_force(wall_words, law=f"hertz/material {E1} {NU1} {REST1}"):
    """Vertical force on a resting sphere pressed OVERLAP into a zplane wall (no damping:
    the particle is at rest)."""
    lmp = new_lammps()
    lmp.commands_string(scenes.sphere_over_wall(RADIUS, RADIUS - OVERLAP,
                                                f"{law} zplane 0 NULL {wall_words}") +
                        "run 0\n")
    fz = lmp.extract_fix("w", 0, 1, 2)
    lmp.close()
    return -fz


def hertz_force(e_star):
    return 4.0 / 3.0 * e_star * math.sqrt(RADIUS) * OVERLAP**1.5


def test_wall_of_the_particle_material_by_default():
    assert wall_force("") == pytest.approx(hertz_force(E1 / (2 * (1 - NU1**2))), rel=1e-12)


def test_wall_of_its_own_material():
    e_star = 1.0 / ((1 - NU1**2) / E1 + (1 - NU2**2) / E2)
    assert wall_force(f"wall_material {E2} {NU2}") == pytest.approx(hertz_force(e_star), rel=1e-12)


def test_rigid_wall():
    assert wall_force("wall_material rigid") == pytest.approx(hertz_force(E1 / (1 - NU1**2)),
                                                             rel=1e-12)


def test_wall_material_errors():
    for words, message in [("wall_material 1e7 0.7", "wall_material: hertz/material nu must be"),
                           ("wall_material", "Illegal fix wall/gran/ellipsoid wall_material"),
                           ("wall_material nosuch", "unknown material 'nosuch'")]:
        with pytest.raises(Exception, match=re.escape(message)):
            wall_force(words)
    with pytest.raises(Exception, match="wall_material needs hertz/material"):
        wall_force("wall_material rigid", law="hertz 1e4 10")


# ---- named materials: SI values, converted by unit style ------------------------------------

GLASS_E, GLASS_NU = 6.3e10, 0.23    # potentials/ellipsoid_dep.materials


def glass_pair_force(units):
    """Force on the first of two 1 mm glass spheres overlapping by 1 um and approaching at
    0.1 m/s (so the restitution damping acts), in SI newtons, from a run in `units`."""
    length, mass, time = {"si": (1.0, 1.0, 1.0), "cgs": (100.0, 1000.0, 1.0)}[units]
    force_unit = mass * length / time**2    # one newton in the unit style's force unit
    r, xi, speed = 1.0e-3 * length, 1.0e-6 * length, 0.1 * length / time
    density = 2500.0 * mass / length**3
    lmp = new_lammps()
    lmp.commands_string(f"""
        units {units}
        atom_style ellipsoid
        atom_modify map array
        comm_modify vel yes
        region box block {-4 * r} {4 * r} {-4 * r} {4 * r} {-4 * r} {4 * r}
        create_box 1 box
        create_atoms 1 single {-r + xi / 2} 0 0
        create_atoms 1 single {r - xi / 2} 0 0
        set type 1 shape {2 * r} {2 * r} {2 * r}
        set type 1 density {density}
        set atom 1 vx {speed / 2}
        set atom 2 vx {-speed / 2}
        pair_style granular/ellipsoid
        pair_coeff * * hertz/material glass
        run 0
        """)
    f = lmp.numpy.extract_atom("f")[lmp.map_atom(1)][0] / force_unit
    lmp.close()
    return f


def test_named_material_in_cgs_gives_the_si_physics():
    f_si = glass_pair_force("si")
    # the elastic part alone, to see that the SI run is the handbook glass
    r_eff, xi = 0.5e-3, 1.0e-6
    elastic = 4.0 / 3.0 * GLASS_E / (2 * (1 - GLASS_NU**2)) * math.sqrt(r_eff) * xi**1.5
    assert -f_si > elastic    # pushed back (-x) and damped while approaching
    assert -f_si < 1.5 * elastic
    assert glass_pair_force("cgs") == pytest.approx(f_si, rel=1e-9)


def test_named_material_refused_in_lj():
    lmp = new_lammps()
    try:
        with pytest.raises(Exception, match=r"units lj has no SI equivalent; give E nu e as "
                                            r"numbers"):
            lmp.commands_string(scenes.empty_pair_box() + "pair_coeff * * hertz/material glass\n")
    finally:
        lmp.close()


def test_materials_file_read_once_per_command(tmp_path):
    """Two names in one command: one read; numbers only: no read."""
    def reads(lmp):
        found = h.read_log(lmp).count("Reading potential file ellipsoid_dep.materials")
        lmp.command(f"log {lmp._test_log} append")
        return found

    lmp = h.new_lammps(tmp_path)
    lmp.commands_string(scenes.sphere_over_wall(
        0.01, 0.02, "hertz/material glass zplane 0 NULL wall_material steel", units="si"))
    after_wall = reads(lmp)
    lmp.commands_string("pair_style granular/ellipsoid\npair_coeff * * hertz/material 1e7 0.3 0.5\n")
    after_pair = reads(lmp)
    lmp.close()
    assert (after_wall, after_pair) == (1, 1)


def test_material_beyond_double_range_is_an_error(tmp_path, monkeypatch):
    """A materials-file entry beyond double range (E 1e999) is a LAMMPS ERROR naming E, not an
    uncaught exception (the file in the working folder is found before LAMMPS_POTENTIALS)."""
    (tmp_path / "ellipsoid_dep.materials").write_text(
        "# DATE: 2026-12-01 test materials\nhuge 1e999 0.3 0.5\n")
    monkeypatch.chdir(tmp_path)
    lmp = new_lammps()
    try:
        with pytest.raises(Exception, match=r"\bE\b.*must be"):
            lmp.commands_string(scenes.empty_pair_box(units="si")
                                + "pair_coeff * * hertz/material huge\n")
    finally:
        lmp.close()
