"""compute unbalanced/force: the mean |net force| of the group's particles over the mean
|contact force| of the pair's and the given walls' contacts (YADE's unbalancedForce()).

The oracle is a stack on the ground: A on the floor, B on A, C falling freely. The net forces
are LAMMPS's per-atom forces; the floor's contact is its contacts array; the pair's one contact
(A, B) is B's force less its weight, since B touches nothing else. Held still (no integrator)
the stack is out of balance and the ratio is that of these numbers.
"""
import math

import numpy as np
import pytest

from conftest import new_lammps
from scenes import floor_stack



def stack(lmp, contacts="contacts", walls="wall floor"):
    lmp.commands_string(floor_stack(contacts, walls) +
                        "thermo_style custom step c_unb c_unb[*]\nrun 3\n")


def test_ratio_of_the_stack_equals_the_oracle():
    lmp = new_lammps()
    stack(lmp)
    mass = lmp.numpy.extract_atom("rmass")[:3].copy()
    f = lmp.numpy.extract_atom("f")[:3].copy()
    floor = lmp.numpy.extract_fix("floor", 1, 2)[:3].copy()    # per-atom array
    values = [lmp.extract_compute("unb", 0, 1)[k] for k in range(4)]
    ratio = lmp.extract_compute("unb", 0, 0)
    lmp.close()
    assert floor[0, 0] == 1 and floor[1, 0] == 0 and floor[2, 0] == 0    # only A on the floor
    weight_b = np.array([0.0, 0.0, -mass[1]])
    pair_ab = f[1] - weight_b    # B touches only A
    assert np.linalg.norm(pair_ab) > 0.1 * mass[1]
    net = np.mean(np.linalg.norm(f, axis=1))
    contact = np.mean([np.linalg.norm(floor[0, 1:4]), np.linalg.norm(pair_ab)])
    assert values[1] == pytest.approx(net, rel=1e-12)
    assert values[2] == pytest.approx(contact, rel=1e-12)
    assert values[3] == 2
    assert ratio == values[0] == pytest.approx(net / contact, rel=1e-12)


def test_without_the_wall_only_the_pair_contact_counts():
    lmp = new_lammps()
    stack(lmp, walls="")
    assert lmp.extract_compute("unb", 0, 1)[3] == 1
    lmp.close()


def test_no_contact_is_infinite_and_no_particle_zero():
    lmp = new_lammps()
    lmp.commands_string((floor_stack() + "thermo_style custom step c_unb c_unb[*]\nrun 3\n")
                        .replace("create_atoms 1 single 2.0 2.0 0.24\n", "")
                        .replace("create_atoms 1 single 2.1 2.05 0.70\n", "")
                        .replace("set atom 2 quat 1 1 0 30\n", ""))
    assert math.isinf(lmp.extract_compute("unb", 0, 0))    # C falls: nothing holds it
    lmp.command("group none empty")
    lmp.command("compute nobody none unbalanced/force")
    lmp.command("run 0")
    assert lmp.extract_compute("nobody", 0, 0) == 0.0
    lmp.close()


@pytest.mark.parametrize("walls,message", [
    ("wall grav", "fix grav is gravity, not a granular ellipsoid wall"),
    ("wall nowall", "fix ID nowall does not exist"),
    ("wall", "Illegal compute unbalanced/force wall command: missing argument"),
    ("walls floor", "Unknown compute unbalanced/force keyword: walls"),
])
def test_bad_walls_are_refused(walls, message):
    lmp = new_lammps()
    try:
        with pytest.raises(Exception, match=message):
            stack(lmp, walls=walls)
    finally:
        lmp.close()


def test_a_wall_without_its_contacts_array_is_refused():
    lmp = new_lammps()
    try:
        with pytest.raises(Exception, match="fix floor has no contacts array: add its contacts "
                                            "keyword"):
            stack(lmp, contacts="")
    finally:
        lmp.close()
