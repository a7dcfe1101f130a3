"""fix wall/gran/ellipsoid: resting states, wall force, a small pour that settles, errors."""

import math

import numpy as np
import pytest

import ed_helpers_pour as h
import geometry
import robust_helpers as rb
import scenes

G = 9.81
RHO = 2500.0


def single_particle(lmp, semi, axis_angle, z0, law, wall="zplane 0 NULL", dt=1e-4):
    for c in [
        "units si",
        "atom_style ellipsoid",
        "boundary p p f",
        "region box block -0.1 0.1 -0.1 0.1 0 0.2",
        "create_box 1 box",
        "comm_modify vel yes",
        f"create_atoms 1 single 0 0 {z0}",
        "set atom 1 shape {} {} {}".format(*(2 * np.asarray(semi))),
        f"set atom 1 density {RHO}",
        "set atom 1 quat {} {} {} {}".format(*axis_angle),
        "pair_style granular/ellipsoid",
        f"pair_coeff * * {law}",
        "fix g all gravity 9.81 vector 0 0 -1",
        "fix i all nve/asphere",
        f"fix w all wall/gran/ellipsoid {law} {wall}",
        "compute er all erotate/asphere",
        "compute ke all ke",
        "thermo_style custom step c_ke c_er f_w[1] f_w[2] f_w[3]",
        "thermo 1000",
        f"timestep {dt}",
    ]:
        lmp.command(c)


def test_sphere_rests_at_hertz_overlap(tmp_path):
    """A sphere at rest on the wall: overlap xi = (m g / kn)^(2/3) (the shared Hertz law),
    wall force = -m g (1e-3 relative)."""
    radius, kn = 0.01, 1.0e4
    lmp = h.new_lammps(tmp_path)
    single_particle(lmp, [radius] * 3, (0, 0, 1, 0), 0.012, f"hertz {kn} 100")
    lmp.command("run 5000")
    snap = h.snapshot(lmp, tmp_path)
    fz = lmp.extract_fix("w", 0, 1, 2)
    lmp.close()
    mass = RHO * 4 / 3 * math.pi * radius ** 3
    xi = (mass * G / kn) ** (2 / 3)
    assert snap["z"][0] == pytest.approx(radius - xi, rel=1e-3)
    assert fz == pytest.approx(-mass * G, rel=1e-3)


def test_ellipsoid_comes_to_rest_on_shortest_axis(tmp_path):
    """Dropped tilted (body axes mixed by a 50 degree turn), a triaxial ellipsoid ends at rest
    with its shortest axis vertical and its centre at height c minus the Hertz overlap."""
    semi = np.array([0.02, 0.012, 0.006])
    kn = 1.0e5
    law = f"hertz {kn} 300 tangential history 1e4 0.5 rolling constant 0.05"
    lmp = h.new_lammps(tmp_path)
    single_particle(lmp, semi, (1, 1, 0.3, 50), 0.04, law)
    lmp.command("run 20000")
    snap = h.snapshot(lmp, tmp_path)
    ke = lmp.get_thermo("c_ke")
    er = lmp.get_thermo("c_er")
    lmp.close()
    r = geometry.rotation(snap["quat"][0])
    assert abs(r[2, 2]) > 0.999, r  # body c axis (shortest) along z
    # resting on the c tip: the Hertz overlap of the shared law, (m g / kn)^(2/3)
    mass = RHO * 4 / 3 * math.pi * np.prod(semi)
    assert snap["z"][0] == pytest.approx(semi[2] - (mass * G / kn) ** (2 / 3), rel=1e-3)
    assert ke + er < 1e-8


def test_wall_force_vector_upper_and_lower(tmp_path):
    """Two walls in the order given: zplane lo then hi; x walls NULL-free; the force of a
    resting particle appears on the lower wall only."""
    lmp = h.new_lammps(tmp_path)
    single_particle(lmp, [0.01, 0.01, 0.01], (0, 0, 1, 0), 0.012, "hertz 1e4 100",
                    wall="zplane 0 0.2")
    lmp.command("run 3000")
    vec = [lmp.extract_fix("w", 0, 1, k) for k in range(6)]
    lmp.close()
    mass = RHO * 4 / 3 * math.pi * 1e-6
    assert vec[2] == pytest.approx(-mass * G, rel=1e-3)
    assert vec[5] == 0.0 and vec[0] == 0.0 and vec[1] == 0.0


def test_small_pour_settles(tmp_path):
    """~120 ellipsoids poured onto the wall in a box periodic in x and y: none lost, none
    below the wall (lowest point above -5% of the smallest semi-axis: the elastic overlap
    under the pile's weight is ~2%), kinetic energy down
    by 1e4 from its peak, all at rest."""
    lmp = h.new_lammps(tmp_path)
    for c in [
        "units si",
        "atom_style ellipsoid",
        "boundary p p f",
        "region box block 0 0.2 0 0.2 0 0.5",
        "create_box 1 box",
        "comm_modify vel yes",
        "region ins block 0 0.2 0 0.2 0.2 0.5",
        "pair_style granular/ellipsoid",
        "pair_coeff * * hertz 1e6 2000 tangential history 2e5 0.5 rolling constant 0.02",
        "fix p all pour/ellipsoid 120 1 2024 region ins size mean 0.015 delta_r 0.3 "
        "shape 1.4 1.8 density 2500 vol 0.15 100",
        "fix g all gravity 9.81 vector 0 0 -1",
        "fix i all nve/asphere",
        "fix w all wall/gran/ellipsoid hertz 1e6 2000 tangential history 2e5 0.5 "
        "rolling constant 0.02 zplane 0 NULL",
        "compute er all erotate/asphere",
        "compute ke all ke",
        "variable e equal c_ke+c_er",
        "fix ave all ave/time 1 1 200 v_e file " + str(tmp_path / "energy.txt"),
        "thermo_style custom step atoms f_p[1] f_p[2] c_ke c_er f_w[3]",
        "thermo 2000",
        "timestep 5e-5",
    ]:
        lmp.command(c)
    lmp.command("run 24000")
    snap = h.snapshot(lmp, tmp_path)
    inserted = lmp.extract_fix("p", 0, 1, 0)
    natoms = lmp.get_natoms()
    fz = lmp.extract_fix("w", 0, 1, 2)
    lmp.close()
    energy = np.loadtxt(tmp_path / "energy.txt")[:, 1]
    assert inserted == 120 and natoms == 120 and len(snap["id"]) == 120
    c_min = snap["semi"].min()
    low = np.array([geometry.lowest_z(q, s, z) for q, s, z in zip(snap["quat"], snap["semi"],
                                                            snap["z"])])
    assert low.min() > -0.05 * c_min, low.min()
    assert (snap["z"] > 0.0).all()
    assert snap["z"].max() < 0.2  # everything came down
    assert energy[-1] < 1e-4 * energy.max(), (energy[-1], energy.max())
    # at rest the wall carries the whole weight
    assert fz == pytest.approx(-snap["mass"].sum() * G, rel=0.02)


def test_history_restart(tmp_path):
    """The per-atom tangential history of the wall survives write_restart/read_restart."""
    law = "hertz 1e4 100 tangential history 1e3 0.5"
    lmp = h.new_lammps(tmp_path, "a")
    single_particle(lmp, [0.02, 0.012, 0.006], (1, 1, 0.3, 50), 0.03, law)
    lmp.command("velocity all set 0.05 0 0")
    lmp.command("run 800")
    restart = tmp_path / "wall.restart"
    lmp.command(f"write_restart {restart}")
    lmp.command("run 200")
    ref = h.snapshot(lmp, tmp_path, "ref")
    lmp.close()

    lmp = h.new_lammps(tmp_path, "b")
    lmp.command(f"read_restart {restart}")
    lmp.command("comm_modify vel yes")
    lmp.command(f"pair_coeff * * {law}")
    lmp.command("fix g all gravity 9.81 vector 0 0 -1")
    lmp.command("fix i all nve/asphere")
    lmp.command(f"fix w all wall/gran/ellipsoid {law} zplane 0 NULL")
    lmp.command("timestep 1e-4")
    lmp.command("run 200")
    cont = h.snapshot(lmp, tmp_path, "cont")
    log = h.read_log(lmp)
    lmp.close()
    assert "Resetting peratom fix info from restart file" in log
    assert np.allclose(ref["x3"], cont["x3"], rtol=0, atol=1e-12)
    assert np.allclose(ref["v3"], cont["v3"], rtol=0, atol=1e-10)


@pytest.mark.parametrize("args,pattern", [
    ("hertz 1e4 10", r"needs at least one wall"),
    ("hertz 1e4 10 zplane 0", r"Illegal fix wall/gran/ellipsoid zplane command: missing"),
    ("hertz 1e4 10 zplane abc NULL", r"zplane lo: expected a number or NULL, got 'abc'"),
    ("hertz 1e4 10 zplane 1 0", r"lo 1 must be below hi 0"),
    ("hertz 1e4 10 xplane 0 1", r"periodic dimension"),
    ("hertz 1e4 10 zplane NULL NULL", r"every wall is NULL"),
    ("hertz 1e4 10 zplane 0 NULL bogus 1", r"Unknown fix wall/gran/ellipsoid keyword 'bogus'"),
    ("hertz abc 10 zplane 0 NULL", r"expected a number for hertz kn, got 'abc'"),
    ("hooke 1 2 zplane 0 NULL", r"unknown normal model 'hooke'"),
    ("hertz 1e4 10 tangential spring 1 zplane 0 NULL", r"unknown tangential model 'spring'"),
    ("hertz/material nosuch zplane 0 NULL", r"unknown material 'nosuch'"),
])
def test_errors(tmp_path, args, pattern):
    h.assert_refused(tmp_path, ["units si", "atom_style ellipsoid", "boundary p p f",
                                "region box block 0 1 0 1 0 1", "create_box 1 box"],
                     [f"fix w all wall/gran/ellipsoid {args}"], pattern)


def test_error_centre_behind_wall(tmp_path):
    lmp = h.new_lammps(tmp_path)
    single_particle(lmp, [0.01] * 3, (0, 0, 1, 0), 0.05, "hertz 1e4 10", wall="zplane 0.06 NULL")
    with pytest.raises(Exception, match="solid side of a wall"):
        lmp.command("run 1")
    lmp.close()


def test_shapeless_atom_added_during_a_run(lmp):
    """The wall alone (no pair style) and fix deposit adding atoms without a shape: an ERROR
    naming the first at the step it appears (1), instead of letting it fall through the wall"""
    rb.assert_shapeless_atom_refused(
        lmp, scenes.shapeless_deposit(pair=False),
        "Fix wall/gran/ellipsoid requires every atom of its group to be an ellipsoid: atom 2 has "
        "no shape")


def test_centre_driven_through_during_a_run_warns(tmp_path):
    """a centre on the solid side is bad input before the first run, but after a run the
    impacts drove it there: the next run warns and the plane pushes the particle back up"""
    lmp = h.new_lammps(tmp_path)
    single_particle(lmp, [0.01] * 3, (0, 0, 1, 0), 0.05, "hertz 1e4 10", wall="zplane 0.02 NULL")
    lmp.command("run 1")
    lmp.command("set atom 1 z 0.015")    # 0.005 below the plane: overlap 0.015 of radius 0.01
    lmp.command("run 1")
    assert lmp.extract_fix("w", 0, 1, 2) < 0.0    # on the wall: down; the particle is pushed up
    lmp.close()
    assert "were driven through a flat wall during the last run" in open(lmp._test_log).read()
