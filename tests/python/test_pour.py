"""fix pour/ellipsoid: size distribution, shape, orientation, overlaps, restart, errors.

Statistical tests use fixed seeds; each states its threshold. They are able to fail: the
size test also checks that the same sample is REJECTED against the (wrong) volume
distribution, and the overlap checker is shown to flag a known overlapping pair.
"""

import math
import re

import numpy as np
import pytest
from scipy import integrate, special, stats

import ed_helpers_pour as h
import geometry

RMIN, RMAX, ALPHA, BETA = 0.02, 0.06, 3.0, 3.0
ETA, ZETA = 1.4, 1.8


def base_commands(box=(0, 1, 0, 1, 0, 1), boundary="p p f"):
    return [
        "units si",
        "atom_style ellipsoid",
        f"boundary {boundary}",
        "region box block {} {} {} {} {} {}".format(*box),
        "create_box 1 box",
        "comm_modify vel yes",
    ]


def number_cdf(rmin, rmax, a, b):
    """CDF of the number distribution n(r) ~ (r-rmin)^(a-1) (rmax-r)^(b-1) / r^3."""
    f = lambda r: (r - rmin) ** (a - 1) * (rmax - r) ** (b - 1) / r ** 3
    norm = integrate.quad(f, rmin, rmax, epsabs=0, epsrel=1e-12)[0]
    grid = np.linspace(rmin, rmax, 2001)
    cum = np.concatenate([[0.0], np.cumsum([integrate.quad(f, grid[k], grid[k + 1],
                                                           epsabs=0, epsrel=1e-12)[0]
                                            for k in range(len(grid) - 1)])]) / norm
    return lambda r: np.interp(r, grid, cum)


@pytest.fixture(scope="module")
def big_pour(tmp_path_factory):
    """~3000 ellipsoids inserted in one batch at a low volume fraction (no size bias from
    failed insertions), no dynamics."""
    work = tmp_path_factory.mktemp("bigpour")
    lmp = h.new_lammps(work)
    for c in base_commands(box=(0, 4, 0, 4, 0, 4)):
        lmp.command(c)
    lmp.command("region ins block 0 4 0 4 0.5 3.5")
    lmp.command(f"fix p all pour/ellipsoid 3000 1 12345 region ins size {RMIN} {RMAX} "
                f"alpha {ALPHA} beta {BETA} shape {ETA} {ZETA} density 2500 vol 0.03 50 every 1")
    lmp.command("run 1")
    snap = h.snapshot(lmp, work)
    inserted = lmp.extract_fix("p", 0, 1, 0)
    failed = lmp.extract_fix("p", 0, 1, 1)
    log = h.read_log(lmp)
    lmp.close()
    return snap, inserted, failed, log


def test_all_inserted(big_pour):
    snap, inserted, failed, _ = big_pour
    assert len(snap["id"]) == 3000
    assert inserted == 3000 and failed == 0
    assert sorted(snap["id"]) == list(range(1, 3001))


def test_shape_ratios_exact(big_pour):
    snap = big_pour[0]
    a, b, c = snap["semi"].T
    # full-precision dump: ratios exact to round-off
    assert np.allclose(a / b, ETA, rtol=1e-13, atol=0)
    assert np.allclose(b / c, ZETA, rtol=1e-13, atol=0)
    r = np.cbrt(a * b * c)
    assert r.min() >= RMIN * (1 - 1e-13) and r.max() <= RMAX * (1 + 1e-13)
    # mass = rho 4/3 pi abc
    assert np.allclose(snap["mass"], 2500 * 4 / 3 * math.pi * a * b * c, rtol=1e-13, atol=0)


def test_size_follows_volume_distribution(big_pour):
    """KS test of r against the NUMBER distribution n(r) ~ V(r)/r^3 (p > 0.01 required),
    and against V(r) itself, which must be rejected (p < 1e-6): the test has power."""
    snap = big_pour[0]
    r = np.cbrt(np.prod(snap["semi"], axis=1))
    cdf = number_cdf(RMIN, RMAX, ALPHA, BETA)
    p_number = stats.kstest(r, cdf).pvalue
    assert p_number > 0.01, p_number
    beta_cdf = lambda x: special.betainc(ALPHA, BETA, (x - RMIN) / (RMAX - RMIN))
    p_volume = stats.kstest(r, beta_cdf).pvalue
    assert p_volume < 1e-6, p_volume
    # volume-weighted sample vs the V(r) CDF: weighted KS distance with n_eff, 1% level
    order = np.argsort(r)
    w = r[order] ** 3
    ecdf = np.cumsum(w) / w.sum()
    dist = np.max(np.abs(ecdf - beta_cdf(r[order])))
    n_eff = w.sum() ** 2 / (w ** 2).sum()
    assert dist * math.sqrt(n_eff) < 1.63, (dist, n_eff)


def test_orientation_uniform(big_pour):
    """Each body axis is uniform on the sphere: cos(theta) with z uniform on [-1, 1] and the
    azimuth uniform on [0, 2 pi) (KS, p > 0.001 for each of the 6 tests)."""
    snap = big_pour[0]
    rots = np.array([geometry.rotation(q) for q in snap["quat"]])
    for axis in range(3):
        u = rots[:, :, axis]
        p_cos = stats.kstest(u[:, 2], stats.uniform(loc=-1, scale=2).cdf).pvalue
        phi = np.mod(np.arctan2(u[:, 1], u[:, 0]), 2 * np.pi)
        p_phi = stats.kstest(phi, stats.uniform(loc=0, scale=2 * np.pi).cdf).pvalue
        assert p_cos > 1e-3 and p_phi > 1e-3, (axis, p_cos, p_phi)


def cutoff_with_inserting_fixes(tmp_path, fixes, atom_style="ellipsoid"):
    """The master neighbour cutoff at run 0 of a two-type box with the given inserting
    fixes and no atoms yet (skin 0.01)."""
    lmp = h.new_lammps(tmp_path)
    for c in base_commands():
        lmp.command(c.replace("atom_style ellipsoid", f"atom_style {atom_style}")
                    .replace("create_box 1 box", "create_box 2 box"))
    lmp.command("region ins block 0 1 0 1 0.5 1")
    lmp.command("fix g all gravity 9.81 vector 0 0 -1")
    for f in fixes:
        lmp.command(f)
    lmp.command("pair_style granular/ellipsoid")
    lmp.command("pair_coeff * * hertz 1e5 10")
    lmp.command("neighbor 0.01 bin")
    lmp.command("run 0")
    log = h.read_log(lmp)
    lmp.close()
    return float(re.search(r"master list distance cutoff = ([0-9.eE+-]+)", log).group(1))


def test_extract_radius_sets_pair_cutoff(tmp_path):
    """extract("radius") = largest semi-axis = rmax eta^(2/3) zeta^(1/3); the pair sizes its
    cutoff from it before any particle exists."""
    cut = cutoff_with_inserting_fixes(tmp_path, [
        f"fix p all pour/ellipsoid 10 1 5 region ins size {RMIN} {RMAX} "
        f"shape {ETA} {ZETA} dshape 0.1 0.2 every 100"])
    a_max = RMAX * (ETA * 1.1) ** (2 / 3) * (ZETA * 1.2) ** (1 / 3)
    assert cut == pytest.approx(2 * a_max + 0.01, rel=1e-6)


def test_cutoff_covers_the_larger_of_two_pours(tmp_path):
    """Two pours of different sizes (types 1 and 2): the cutoff covers two of the larger
    particles, whichever fix is defined first."""
    small = "fix small all pour/ellipsoid 10 1 5 region ins size 0.01 0.02 shape 1.2 1.1 every 100"
    large = f"fix large all pour/ellipsoid 10 2 6 region ins size {RMIN} {RMAX} shape {ETA} {ZETA} every 100"
    a_large = RMAX * ETA ** (2 / 3) * ZETA ** (1 / 3)
    for fixes in ([small, large], [large, small]):
        cut = cutoff_with_inserting_fixes(tmp_path, fixes)
        assert cut == pytest.approx(2 * a_large + 0.01, rel=1e-6), fixes


@pytest.mark.parametrize("other,radius", [
    # LAMMPS's fix pour (spheres of diameter 0.3) and fix deposit (radius 0.5 for atoms
    # without a molecule template), whose style name holds no "pour"
    ("fix other all pour 10 2 7 region ins diam one 0.3", 0.15),
    ("fix other all deposit 10 2 100 7 region ins", 0.5),
])
def test_cutoff_asks_every_inserting_fix(tmp_path, other, radius):
    """Any fix answering extract("radius", type) is heard, not only pour/ellipsoid."""
    ours = "fix p all pour/ellipsoid 10 1 5 region ins size 0.01 0.01 every 100"
    cut = cutoff_with_inserting_fixes(tmp_path, [ours, other], "hybrid sphere ellipsoid")
    assert cut == pytest.approx(2 * radius + 0.01, rel=1e-6)


@pytest.mark.parametrize("boundary", ["p p f", "f p p"])
def test_no_insertion_overlaps(tmp_path, boundary):
    """A dense batch (volume fraction 0.3): every pair whose bounding spheres meet is proven
    disjoint by an independent separating-axis search. The box is 4 of the pour's search
    cells wide (twice the largest bounding radius, 0.145), so a periodic side's overlaps are
    found only through the cells' wrap-around; a side that is not periodic has edge cells."""
    periodic = tuple(flag == "p" for flag in boundary.split())
    lmp = h.new_lammps(tmp_path)
    for c in base_commands(box=(0, 0.6, 0, 0.6, 0, 1), boundary=boundary):
        lmp.command(c)
    lmp.command("region ins block 0 0.6 0 0.6 0.6 1.0")
    lmp.command("fix p all pour/ellipsoid 1000 1 777 region ins size 0.02 0.04 "
                "shape 2.0 1.5 vol 0.3 200 every 1000")
    lmp.command("run 1")
    snap = h.snapshot(lmp, tmp_path)
    rejected = lmp.extract_fix("p", 0, 1, 2)
    lmp.close()
    n = len(snap["id"])
    assert n > 300
    assert rejected > 0  # the test exercised the overlap rejection
    box = snap["box"]
    checked = 0
    for i in range(n):
        # the pairs (i, j > i) whose bounding spheres meet
        d = geometry.minimum_image(snap["x3"][i + 1:] - snap["x3"][i], box, periodic)
        reach = snap["semi"][i].max() + snap["semi"][i + 1:].max(axis=1)
        for k in np.flatnonzero((d * d).sum(axis=1) <= reach * reach):
            j = i + 1 + k
            gap, _ = geometry.separating_axis(np.zeros(3), snap["quat"][i], snap["semi"][i],
                                              d[k], snap["quat"][j], snap["semi"][j])
            assert gap < 0.0, (snap["id"][i], snap["id"][j], gap)
            checked += 1
    assert checked > 80  # close pairs existed


def test_overlap_checker_detects_overlap():
    """The independent checker reports no separating axis for overlapping ellipsoids."""
    q = [1, 0, 0, 0]
    gap, _ = geometry.separating_axis(np.zeros(3), q, [0.3, 0.1, 0.1], [0.35, 0.05, 0.0], q,
                               [0.3, 0.1, 0.1])
    assert gap > 0.0
    gap, _ = geometry.separating_axis(np.zeros(3), q, [0.3, 0.1, 0.1], [0.0, 0.25, 0.0], q,
                               [0.3, 0.1, 0.1])
    assert gap < 0.0


def pour_commands(seed=4242):
    return base_commands(box=(0, 0.3, 0, 0.3, 0, 0.6)) + [
        "region ins block 0 0.3 0 0.3 0.3 0.6",
        "pair_style granular/ellipsoid",
        "pair_coeff * * hertz 2e5 300 tangential history 5e4 0.5",
        f"fix p all pour/ellipsoid 90 1 {seed} region ins size mean 0.025 delta_r 0.4 "
        "shape 1.3 1.3 density 2500 vol 0.05 50 every 500",
        "fix g all gravity 9.81 vector 0 0 -1",
        "fix i all nve/asphere",
        "fix w all wall/gran/ellipsoid hertz 2e5 300 tangential history 5e4 0.5 zplane 0 NULL",
        "timestep 1e-4",
    ]


def test_restart_continues_pour(tmp_path):
    """A pour written to a restart file mid-way and continued from it inserts the same
    particles (same ids, shapes and insertion order) as the uninterrupted pour."""
    steps, half = 2500, 700

    lmp = h.new_lammps(tmp_path, "full")
    for c in pour_commands():
        lmp.command(c)
    lmp.command(f"run {steps}")
    full = h.snapshot(lmp, tmp_path, "full")
    full_count = lmp.extract_fix("p", 0, 0)
    lmp.close()

    restart = tmp_path / "pour.restart"
    lmp = h.new_lammps(tmp_path, "first")
    for c in pour_commands():
        lmp.command(c)
    lmp.command(f"run {half}")
    mid_count = lmp.extract_fix("p", 0, 0)
    lmp.command(f"write_restart {restart}")
    lmp.close()

    lmp = h.new_lammps(tmp_path, "second")
    lmp.command(f"read_restart {restart}")
    lmp.command("comm_modify vel yes")
    lmp.command("region ins block 0 0.3 0 0.3 0.3 0.6")
    lmp.command("pair_coeff * * hertz 2e5 300 tangential history 5e4 0.5")
    lmp.command("fix p all pour/ellipsoid 90 1 4242 region ins size mean 0.025 delta_r 0.4 "
                "shape 1.3 1.3 density 2500 vol 0.05 50 every 500")
    lmp.command("fix g all gravity 9.81 vector 0 0 -1")
    lmp.command("fix i all nve/asphere")
    lmp.command("fix w all wall/gran/ellipsoid hertz 2e5 300 tangential history 5e4 0.5 "
                "zplane 0 NULL")
    lmp.command("timestep 1e-4")
    lmp.command(f"run {steps - half}")
    cont = h.snapshot(lmp, tmp_path, "cont")
    cont_count = lmp.extract_fix("p", 0, 0)
    log = h.read_log(lmp)
    lmp.close()

    assert "Resetting global fix info from restart file" in log
    assert 0 < mid_count < 90  # the restart really was in the middle of the pour
    assert full_count == cont_count == 90
    assert len(full["id"]) == len(cont["id"]) == 90
    assert np.array_equal(full["id"], cont["id"])
    # same random stream after the restart: identical shapes per id (dump precision)
    assert np.allclose(full["semi"], cont["semi"], rtol=1e-14, atol=0)


# ---- the time step against the particles to come ---------------------------------------------
# The pair's run-start check sees the atoms present; into an empty box the pour checks its own
# particles: the lightest (size rmin) with the flattest surface, against each other and the
# wall, at the speed of a fall from the region's top to the box's bottom plus vel.

POUR_KN = 2.0e4
POUR_LINE = re.compile(r"^Fix pour/ellipsoid: Hertz contact time (\S+) \(types 1 1, impact "
                       r"speed (\S+)\)", re.M)
POUR_WARNING = re.compile(r"^WARNING: Fix pour/ellipsoid: timestep (\S+) exceeds 0.1 of the "
                          r"Hertz contact time (\S+) \(types 1 1, impact speed (\S+)\)", re.M)


def fast_pour_log(tmp_path, name, dt, region="0 8 0 8 20 29", pour="", steps=1):
    """The issue's input (header H, hertz 2e4 200 for pair and floor, a pour at vz -60 into the
    empty box) at time step dt: its log."""
    lmp = h.new_lammps(tmp_path, name)
    lmp.commands_list([
        "units lj", "atom_style ellipsoid", "boundary p p f", "comm_modify vel yes",
        "region box block 0 8 0 8 0 100", "create_box 1 box", "pair_style granular/ellipsoid",
        "fix g all gravity 1.0 vector 0 0 -1", "fix i all nve/ellipsoid",
        f"pair_coeff * * hertz {POUR_KN} 200",
        f"fix w all wall/gran/ellipsoid hertz {POUR_KN} 200 zplane 0 NULL",
        f"region ins block {region}",
        pour or "fix p all pour/ellipsoid 100 1 4767 region ins size mean 0.5 delta_r 0.2 "
        "shape 1.4 1.4 vol 0.15 200 vel 0 0 0 0 -60",
        f"timestep {dt}", "thermo_modify lost ignore", f"run {steps}"])
    log = h.read_log(lmp)
    lmp.close()
    return log


def test_pour_into_an_empty_box_checks_the_time_step(tmp_path):
    log = fast_pour_log(tmp_path, "fast", 2.0e-3)
    assert "Pair granular/ellipsoid: Hertz contact time" not in log    # no atom at run start
    warned = POUR_WARNING.search(log)
    assert warned, log
    tc, speed = float(warned.group(2)), float(warned.group(3))
    # from the region's top, 29, to the floor at 60 down: sqrt(60^2 + 2 g 29)
    assert speed == pytest.approx(math.sqrt(60.0**2 + 2 * 29.0), rel=1e-5)
    m_eff = 4.0 / 3.0 * math.pi * 0.4**3 / 2.0    # two of the lightest, rmin = 0.4, density 1
    closed_form = 2 * 0.4 * special.beta(0.4, 0.5) * (5 * m_eff * speed**2 / (4 * POUR_KN))**0.4 / speed
    assert tc == pytest.approx(closed_form, rel=1e-5)
    assert 0.1 * tc < 2.0e-3 < 0.2 * tc    # the t_c / 6
    assert "WARNING: Fix pour/ellipsoid: damping number" in log
    # a time step of 1/24 of the contact time passes without a warning, and is reported
    safe = fast_pour_log(tmp_path, "safe", 5.0e-4)
    assert POUR_LINE.search(safe) and "WARNING" not in safe, safe


def test_pour_checks_again_when_its_region_rises(tmp_path):
    """A region rising at 43 per time unit drops later batches from higher up: the check at
    run start passes (top 4: impact speed 2.83, 11.1 steps per contact) and one at a later
    batch warns (top 12.6: speed 5.02, 9.9 steps)."""
    log = fast_pour_log(tmp_path, "rising", 2.0e-3, region="0 8 0 8 2 4",
                        pour="fix p all pour/ellipsoid 20 1 4767 region ins size mean 0.5 "
                        "delta_r 0.2 shape 1.4 1.4 vol 0.01 50 rate 43 every 100", steps=1000)
    first = POUR_LINE.search(log)
    assert first and float(first.group(2)) == pytest.approx(math.sqrt(2 * 4.0), rel=1e-5)
    assert log.index("Fix pour/ellipsoid: Hertz contact time") < log.index("Step")
    warned = POUR_WARNING.search(log)
    assert warned and float(warned.group(3)) > 1.5 * float(first.group(2)), log
    assert log.index("Step") < warned.start()    # at a batch, not at the run start


def test_pour_checks_the_time_step_against_the_walls(tmp_path):
    """The particles to come are checked against each wall acting on them, as the doc says
    (before: the walls were looked up by a style pattern that LAMMPS's matcher cannot read,
    and none was found): a floor 100 times stiffer than the pair law has the shortest contact
    time, and the report names it."""
    lmp = h.new_lammps(tmp_path, "walls")
    lmp.commands_list([
        "units lj", "atom_style ellipsoid", "boundary p p f", "comm_modify vel yes",
        "region box block 0 8 0 8 0 30", "create_box 1 box", "pair_style granular/ellipsoid",
        "fix g all gravity 1.0 vector 0 0 -1", f"pair_coeff * * hertz {POUR_KN} 200",
        f"fix w all wall/gran/ellipsoid hertz {100 * POUR_KN} 200 zplane 0 NULL",
        "region ins block 0 8 0 8 20 29",
        "fix p all pour/ellipsoid 100 1 4767 region ins size mean 0.5 delta_r 0.2 shape 1.4 1.4",
        "timestep 1e-4", "run 0"])
    log = h.read_log(lmp)
    lmp.close()
    assert re.search(r"^Fix pour/ellipsoid: Hertz contact time \S+ \(type 1 on fix w, impact "
                     r"speed \S+\)", log, re.M), log


@pytest.mark.parametrize("args,pattern", [
    ("10 1 5 region nope", r"region nope does not exist"),
    ("10 1 5", r"requires the keyword 'region ID'"),
    ("10 1 0 region ins", r"seed must be > 0"),
    ("ten 1 5 region ins", r"N: expected an integer, got 'ten'"),
    ("10 7 5 region ins", r"atom type 7 is not in 1..1"),
    ("10 1 5 region ins size 0.1 abc", r"size rmax: expected a number, got 'abc'"),
    ("10 1 5 region ins size 0 0.1", r"rmin must be > 0"),
    ("10 1 5 region ins size 0.2 0.1", r"rmin 0.2 exceeds rmax 0.1"),
    ("10 1 5 region ins size mean 0.1 delta_r 1.0", r"delta_r must be in \[0, 1\)"),
    ("10 1 5 region ins size mean 0.1 dr 0.5", r"expected 'delta_r', got 'dr'"),
    ("10 1 5 region ins alpha 0", r"alpha must be > 0"),
    ("10 1 5 region ins beta -1", r"beta must be > 0"),
    ("10 1 5 region ins shape 0.9 1", r"eta = a/b must be >= 1"),
    ("10 1 5 region ins shape 1 0.5", r"zeta = b/c must be >= 1"),
    ("10 1 5 region ins shape 1.1 1 dshape 0.5 0", r"eta \(1 - delta_eta\)"),
    ("10 1 5 region ins bogus 3", r"Unknown fix pour/ellipsoid keyword 'bogus'"),
    ("10 1 5 region ins size 0.2 0.2 vol 0.01 10", r"region ins is too small"),
    ("10 1 5 region ins size 1 1", r"region ins is 0.5 high: too low for particles"),
    ("10 1 5 region xcyl", r"must be a z-axis cylinder"),
])
def test_errors(tmp_path, args, pattern):
    h.assert_refused(tmp_path, base_commands() + ["region ins block 0 1 0 1 0.5 1",
                                                  "region xcyl cylinder x 0.5 0.5 0.3 0.1 0.9"],
                     [f"fix p all pour/ellipsoid {args}"], pattern)


def test_error_atom_style(tmp_path):
    h.assert_refused(tmp_path, ["atom_style sphere", "region box block 0 1 0 1 0 1",
                                "create_box 1 box"],
                     ["fix p all pour/ellipsoid 10 1 5 region box"],
                     "requires atom_style ellipsoid")


def test_superellipsoid_variant(tmp_path):
    """atom_style ellipsoid superellipsoid: block 2 2, stored inertia and radius consistent."""
    lmp = h.new_lammps(tmp_path)
    lmp.command("units si")
    lmp.command("atom_style ellipsoid superellipsoid")
    lmp.command("boundary p p f")
    lmp.command("region box block 0 1 0 1 0 1")
    lmp.command("create_box 1 box")
    lmp.command("region ins block 0 1 0 1 0.5 1")
    lmp.command(f"fix p all pour/ellipsoid 50 1 9 region ins size {RMIN} {RMAX} "
                f"shape {ETA} {ZETA} density 1000 every 10")
    lmp.command("run 1")
    lmp.command("compute r all property/atom radius")
    lmp.command("compute b all property/atom block1 block2")
    lmp.command("run 0")
    snap = h.snapshot(lmp, tmp_path)
    radius = np.array(lmp.numpy.extract_compute("r", 1, 1))
    blocks = np.array(lmp.numpy.extract_compute("b", 1, 2))
    ids = np.array(lmp.numpy.extract_atom("id"))
    lmp.close()
    order = np.argsort(ids)
    assert len(snap["id"]) == 50
    assert np.allclose(blocks[order], 2.0)
    assert np.allclose(radius[order], snap["semi"].max(axis=1), rtol=1e-13)
    assert np.allclose(snap["mass"], 1000 * 4 / 3 * math.pi * np.prod(snap["semi"], axis=1),
                       rtol=1e-13)


# one pour in SI and in units metal and real: metres per length unit, seconds per time unit,
# m/s^2 per force/mass unit (LAMMPS's doc/src/units.rst)
UNIT_STYLES = {"si": (1.0, 1.0, 1.0),
               "metal": (1e-10, 1e-12, 1.602176634e-19 / 1e-10 / (1e-3 / 6.02214076e23)),
               "real": (1e-10, 1e-15, 4184.0 / 1e-10 / 1e-3)}


@pytest.mark.parametrize("style", ["metal", "real"])
def test_pour_schedule_and_velocities_in_every_unit_style(tmp_path, style):
    """The same physical pour (a 5 cm high region at 5-10 cm, g 9.81 m/s^2, dt 10 us) in SI
    and in another unit style: the same batch interval in steps and the same particles with the
    same velocities (gravity converted to velocity/time with force->ftm2v, as fix pour does)."""
    def pour(units):
        length, time, accel = UNIT_STYLES[units]
        box = " ".join(f"{v / length:.17g}" for v in (0, 0.1, 0, 0.1, 0, 0.1))
        lmp = h.new_lammps(tmp_path, units)
        lmp.commands_list([
            f"units {units}", "atom_style ellipsoid", "boundary p p f", "comm_modify vel yes",
            f"region box block {box}", "create_box 1 box",
            f"region ins block 0 {0.1 / length:.17g} 0 {0.1 / length:.17g} {0.05 / length:.17g} "
            f"{0.1 / length:.17g}",
            f"fix p all pour/ellipsoid 20 1 17 region ins size {0.004 / length:.17g} "
            f"{0.006 / length:.17g} shape 1.4 1.2 vol 0.05 50 vel 0 0 0 0 {-0.5 * time / length:.17g}",
            f"fix g all gravity {9.81 / accel:.17g} vector 0 0 -1", f"timestep {1e-5 / time:.17g}",
            "run 1"])
        snap = h.snapshot(lmp, tmp_path, units)
        log = h.read_log(lmp)
        lmp.close()
        every = re.search(r"fix pour/ellipsoid: \d+ particles every (\d+) steps", log)
        return int(every.group(1)), snap["x3"] * length, snap["v3"] * length / time

    every_si, x_si, v_si = pour("si")
    every, x, v = pour(style)
    assert every == every_si
    assert len(x) == len(x_si) == 20
    # to 1e-7: LAMMPS's force->ftm2v of metal has 8 digits (1 / 1.0364269e-4), and the
    # stream's heights depend on g
    assert np.abs(x - x_si).max() < 1e-7 * 0.1
    assert np.allclose(v, v_si, rtol=1e-7, atol=0)
    assert v[:, 2].max() < -0.5    # at least the entry speed downwards, in m/s
