"""Pair granular/ellipsoid puts the owned atoms' bonus entries (shape, quaternion) in the atoms'
order at each neighbour-list build. LAMMPS's atom sort moves atoms, not their bonus entries,
so after a pour the entries stay in insertion order and every read of a shape or quaternion
goes to a random place (doc/benchmarks.md, "Cost against N"). Every atom keeps its own shape
and orientation, under both ellipsoid atom styles."""
import numpy as np
import pytest
from lammps import LMP_STYLE_ATOM, LMP_TYPE_ARRAY

from conftest import new_lammps

N = 300


def random_gas(atom_style):
    """N ellipsoids at random places (created in an order the atom sort permutes), each with
    its own semi-axes (from its ID) and a random orientation; atoms sorted every 10 steps"""
    lmp = new_lammps()
    lmp.commands_string(f"""
units lj
atom_style {atom_style}
atom_modify map array sort 10 1.0
comm_modify vel yes
boundary p p f
region box block 0 14 0 14 0 14
create_box 1 box
create_atoms 1 random {N} 4829 NULL overlap 1.6 maxtry 500
variable sx atom 1.2+0.2*(id%7)/7
variable sy atom 1.0+0.1*(id%5)/5
variable sz atom 0.7+0.1*(id%3)/3
set atom * shape v_sx v_sy v_sz
set type * mass 1.0
{"set type * block 2.0 2.0" if "superellipsoid" in atom_style else ""}
set type * quat/random 4830
compute shp all property/atom shapex shapey shapez quatw quati quatj quatk
""")
    return lmp


def by_id(lmp):
    """{ID: (3 diameters, quaternion)} of the owned atoms, read through their bonus entries"""
    nlocal = lmp.extract_global("nlocal")
    ids = lmp.numpy.extract_atom("id")[:nlocal]
    values = lmp.numpy.extract_compute("shp", LMP_STYLE_ATOM, LMP_TYPE_ARRAY)[:nlocal]
    return {int(t): tuple(v) for t, v in zip(ids, values)}


def bonus_in_atom_order(lmp):
    nlocal = lmp.extract_global("nlocal")
    return bool(np.array_equal(lmp.numpy.extract_atom("ellipsoid")[:nlocal], np.arange(nlocal)))


@pytest.mark.parametrize("atom_style", ["ellipsoid", "ellipsoid superellipsoid"])
def test_bonus_follows_the_atoms(atom_style):
    lmp = random_gas(atom_style)
    lmp.command("run 0 post no")    # no pair yet: the sort leaves the entries where they were
    assert not bonus_in_atom_order(lmp)
    before = by_id(lmp)
    assert len(before) == N
    lmp.commands_string("""
pair_style granular/ellipsoid
pair_coeff * * hertz 1.0e4 0.0 tangential none
run 0 post no
""")
    assert bonus_in_atom_order(lmp)
    assert by_id(lmp) == before    # bit for bit: only where the values are stored changed
    # moving atoms, sorted every 10 steps: the entries keep following them, and each atom its
    # own semi-axes
    lmp.commands_string("""
velocity all create 1.0 4831 loop geom
fix integrate all nve/ellipsoid
timestep 1e-3
run 55 post no
""")
    assert bonus_in_atom_order(lmp)
    after = by_id(lmp)
    assert {t: v[:3] for t, v in after.items()} == {t: v[:3] for t, v in before.items()}
    lmp.close()
