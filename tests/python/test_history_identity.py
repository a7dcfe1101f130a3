"""A pair's cached history is used only for the pair and periodic image it was made for.

LAMMPS keys each pair's history by the partner's ID. In a periodic box narrower than two
neighbour cutoffs a particle lists two images of one partner, and both get the same row; after
`delete_atoms ... compress yes` the IDs are renumbered and rows reach other pairs. Before the
fix such a row (a normal of another pair) started the contact iteration in the basin of a
spurious minimum about a needle's length deep: lost atoms in a box 4 wide under needles 2.5
long, the temperature of a settled deposit from 0.05 to 8734 in one step after compress. The
pour also inserted overlapping needles there (it tested the nearest image only).

Checks: the narrow box keeps every atom and its contacts are those a
cold evaluation finds (a restart, which carries the rows, against a data file, which does not,
and an independent separating-axis check); no insertion overlaps any image; compress yes gives
the temperature of compress no. Each failed before the fix.
"""
import itertools
import math

import numpy as np
import pytest

import ed_helpers_pour as h
import geometry

HEADER = [
    "units lj",
    "atom_style ellipsoid",
    "boundary p p f",
    "comm_modify vel yes",
    "region box block 0 {L} 0 {L} 0 30",
    "create_box 1 box",
    "pair_style granular/ellipsoid",
    "fix g all gravity 1.0 vector 0 0 -1",
    "fix i all nve/ellipsoid",
]
NEEDLE_BOX = 4.0    # needles 2.5 long (size 0.5 = (abc)^(1/3), a = 4 b = 4 c): two lengths 5


def needle_pour(L, seed=11):
    return [c.format(L=L) for c in HEADER] + [
        "pair_coeff * * hertz/material 2e6 0.3 0.5",
        "fix w all wall/gran/ellipsoid hertz/material 2e6 0.3 0.5 zplane 0 NULL",
        f"region ins block 0 {L} 0 {L} 0.5 25",
        f"fix p all pour/ellipsoid 40 1 {seed} region ins size 0.5 0.5 shape 4 1 vol 0.2 400",
        "timestep 1e-4",
        "thermo_modify lost error",
    ]


def counter(lmp, name):
    return lmp.extract_pair(f"counters/{name}")


def contacts(lmp):
    """(id_i, id_j, overlap) of every pair in contact now (compute pair/local, which evaluates
    each listed pair and image on its own), sorted."""
    lmp.command("compute hi_pl all pair/local p1")
    lmp.command("compute hi_pa all property/local patom1 patom2")
    lmp.command("run 0 post no")
    overlap = np.array(lmp.numpy.extract_compute("hi_pl", 2, 1), dtype=float).reshape(-1)
    ids = np.array(lmp.numpy.extract_compute("hi_pa", 2, 2), dtype=int).reshape(-1, 2)
    lmp.command("uncompute hi_pl")
    lmp.command("uncompute hi_pa")
    keep = overlap > 0.0
    rows = [(min(a, b), max(a, b), o) for (a, b), o in zip(ids[keep], overlap[keep])]
    return sorted(rows)


def image_overlaps(snap, periodic_dims=(0, 1)):
    """The largest min d (overlap > 0, minus the distance when disjoint) over every pair and
    every periodic image within the bounding spheres' reach, by the independent
    separating-axis search of geometry.py; and how many (pair, image) were checked."""
    period, n = snap["box"][:, 1] - snap["box"][:, 0], len(snap["id"])
    worst, checked = -np.inf, 0
    for i in range(n):
        for j in range(i + 1, n):
            reach = snap["semi"][i].max() + snap["semi"][j].max()
            base = snap["x3"][j] - snap["x3"][i]
            ranges = [range(-3, 4) if d in periodic_dims else range(0, 1) for d in range(3)]
            for shift in itertools.product(*ranges):
                dc = base + np.array(shift) * period
                if dc @ dc > reach * reach:
                    continue
                gap, _ = geometry.separating_axis(np.zeros(3), snap["quat"][i], snap["semi"][i],
                                                  dc, snap["quat"][j], snap["semi"][j])
                worst = max(worst, gap)
                checked += 1
    return worst, checked


@pytest.fixture(scope="module")
def settled_needles(tmp_path_factory):
    """The issue's needle pour in a box 4 wide, 30 000 steps (lost 11 of 40 atoms before the
    fix); its restart and data files."""
    work = tmp_path_factory.mktemp("needles")
    lmp = h.new_lammps(work)
    for c in needle_pour(NEEDLE_BOX):
        lmp.command(c)
    lmp.command("run 30000")
    natoms = lmp.get_natoms()
    spurious, foreign = counter(lmp, "spurious_minima"), counter(lmp, "foreign_histories")
    lmp.command(f"write_restart {work}/needles.restart")
    lmp.command(f"write_data {work}/needles.data")
    lmp.close()
    return {"work": work, "natoms": natoms, "spurious": spurious, "foreign": foreign}


def test_narrow_box_keeps_every_atom(settled_needles):
    assert settled_needles["natoms"] == 40
    # the rows of other images reached the pair, and were not used
    assert settled_needles["spurious"] + settled_needles["foreign"] > 0


def continued(work, how, name):
    lmp = h.new_lammps(work, name)
    lmp.command("units lj")
    lmp.command("atom_style ellipsoid")
    if how == "restart":
        lmp.command(f"read_restart {work}/needles.restart")
    else:
        lmp.command("boundary p p f")
        lmp.command(f"read_data {work}/needles.data")
        lmp.command("pair_style granular/ellipsoid")
        lmp.command("pair_coeff * * hertz/material 2e6 0.3 0.5")
    lmp.command("comm_modify vel yes")
    lmp.command("fix i all nve/ellipsoid")
    lmp.command("fix w all wall/gran/ellipsoid hertz/material 2e6 0.3 0.5 zplane 0 NULL")
    return lmp


def test_restart_rows_give_the_contacts_of_a_cold_start(settled_needles):
    """A restart carries every pair's row (each image of a partner gets the first one): its
    contacts equal those of a data file (no rows), and an independent check of every pair and
    image finds no overlap deeper than the deepest contact. Before the fix: 42 contacts up to
    7.2 deep from the restart, 0 from the data file."""
    work = settled_needles["work"]
    found = {}
    for how in ("restart", "data"):
        lmp = continued(work, how, how)
        found[how] = contacts(lmp)
        if how == "data":
            snap = h.snapshot(lmp, work)
        lmp.close()
    assert [c[:2] for c in found["restart"]] == [c[:2] for c in found["data"]]
    for a, b in zip(found["restart"], found["data"]):
        assert a[2] == pytest.approx(b[2], rel=1e-6, abs=1e-12)
    worst, checked = image_overlaps(snap)
    assert checked > 40
    deepest = max([c[2] for c in found["data"]], default=0.0)
    assert worst <= deepest + 1e-9, (worst, deepest)
    cmin = 0.5 / 4 ** (1 / 3)
    assert deepest < 0.05 * cmin


@pytest.mark.parametrize("seed, n, top", [(13, 40, 25), (12, 80, 12)])
def test_pour_checks_every_image(tmp_path, seed, n, top):
    """A batch of needles 2.5 long in a box 4 wide, inserted at once (no dynamics): no
    (pair, image) overlaps, although more than the nearest image is within reach. Before the
    fix (nearest image only) these seeds inserted needles overlapping by 0.126 and 0.0125."""
    lmp = h.new_lammps(tmp_path)
    for c in needle_pour(NEEDLE_BOX, seed=seed)[:-2]:
        lmp.command(c.replace("pour/ellipsoid 40", f"pour/ellipsoid {n}")
                    .replace("0.5 25", f"0.5 {top}"))
    lmp.command("run 1")
    snap = h.snapshot(lmp, tmp_path)
    lmp.close()
    assert len(snap["id"]) >= 40
    worst, checked = image_overlaps(snap)
    assert checked > 100
    assert worst < 0.0, worst


def test_delete_atoms_compress_keeps_the_deposit(tmp_path):
    """A settled deposit (150 particles) after delete_atoms with compress yes, which
    renumbers the IDs and so hands rows to other pairs, has the temperature of compress no
    (to 1e-4: the renumbered contacts only restart their tangential displacement). The deposit
    is settled once; compress no continues from its restart. Before the fix the temperature
    went from 0.0509 to 8734 in one step."""
    temps = {}
    lmp = h.new_lammps(tmp_path, "compress_yes")
    for c in [c.format(L=8) for c in HEADER] + [
            "pair_coeff * * hertz/material 1.2e7 0.3 0.5",
            "fix w all wall/gran/ellipsoid hertz/material 1.2e7 0.3 0.5 zplane 0 NULL",
            "region ins block 0 8 0 8 0.5 12",
            "fix p all pour/ellipsoid 150 1 4767 region ins size 0.5 0.5 shape 2 2 vol 0.3 400",
            "timestep 1e-4",
            "run 40000",
            f"write_restart {tmp_path}/settled.restart"]:
        lmp.command(c)
    for compress in ("yes", "no"):
        if compress == "no":
            lmp = h.new_lammps(tmp_path, "compress_no")
            for c in ["units lj", "atom_style ellipsoid",
                      f"read_restart {tmp_path}/settled.restart", "comm_modify vel yes",
                      "fix g all gravity 1.0 vector 0 0 -1", "fix i all nve/ellipsoid",
                      "fix w all wall/gran/ellipsoid hertz/material 1.2e7 0.3 0.5 zplane 0 "
                      "NULL",
                      "region ins block 0 8 0 8 0.5 12",
                      "fix p all pour/ellipsoid 150 1 4767 region ins size 0.5 0.5 shape 2 2 "
                      "vol 0.3 400",
                      "timestep 1e-4"]:
                lmp.command(c)
        lmp.command(f"delete_atoms random count 5 yes all NULL 7 compress {compress}")
        lmp.command("run 3")
        temps[compress] = (lmp.get_thermo("temp"), counter(lmp, "contacts"))
        assert lmp.get_natoms() == 145
        lmp.close()
    assert temps["yes"][1] > 100    # a deposit with contacts
    assert math.isfinite(temps["yes"][0])
    assert temps["yes"][0] == pytest.approx(temps["no"][0], rel=1e-4)
    assert temps["yes"][0] < 0.1    # settled: 0.0509


@pytest.mark.parametrize("eta, zeta, dr", [(3.0, 3.0, 0.0), (1.4, 1.8, 0.6), (1.0, 1.0, 0.0)])
def test_deposit_box_holds_one_image_per_partner(tmp_path, eta, zeta, dr):
    """examples/deposit/in.deposit makes its box at least 5 d and wider than two neighbour
    cutoffs of its longest particles (4 a_max + 2 skin, skin 0.2), so that no list holds two
    images of one partner: 6.4 for N = 150 needles of a/c 9 (was 5, where `./ellipsoid-dep run
    --N 150 --eta 3 --zeta 3 --dr 0` lost every atom), 5.27 for the default shape at N = 150,
    5 for spheres. One step of the pour only."""
    lmp = h.deposit_lammps(tmp_path, {"N": 150, "eta": eta, "zeta": zeta, "dr": dr,
                                      "chunk": 1, "maxchunks": 1, "image": 0,
                                      "out": str(tmp_path)})
    lo, hi = lmp.extract_box()[:2]
    lmp.close()
    a_max = 0.5 * (1 + dr) * (eta ** 2 * zeta) ** (1 / 3)
    width = hi[0] - lo[0]
    assert hi[1] - lo[1] == width
    assert width == pytest.approx(max(5.0, 0.3 * math.sqrt(150), 4 * a_max + 2 * 0.2))
