"""The candidates' history rows in the pair's own array (granular_contact_rows.h).

Specification: during a run the pair reads and writes the rows of the pairs it evaluates in
its own array and stores them back into fix NEIGH_HISTORY before that fix reads them (its
pre_exchange at every neighbour list build, the end of a run, write_restart). A row not stored
back would be handed on stale at the next build: the tangential springs would restart from
it. Oracle: the same gas with a list build at every step (neigh_modify check no: every row
passes through the fix at every step) and with builds only when an atom has moved half the
skin (check yes: the rows live in the pair's array between builds). Each contact's spring
is the same in both, so are the trajectories, to round-off.
"""
import numpy as np
import pytest

import scenes
from conftest import new_lammps

BOX = 5.0
# a/c = 2 ellipsoids; the tangential spring and Coulomb cap keep history in every contact
SHAPE = (0.6, 0.45, 0.3)
COEFF = "hertz 1.0e4 5.0 tangential history 5.0e3 0.5"


def gas_input(style_neigh):
    """The gas's input up to its first run: 36 ellipsoids on a loose lattice in a periodic
    box, random orientations and velocities."""
    lines = [scenes.particle_box("ellipsoid", 0, BOX)]
    for i in range(3):
        for j in range(3):
            for k in range(4):
                p = (np.array([i, j, k]) + 0.5) * BOX / np.array([3, 3, 4])
                lines.append(f"create_atoms 1 single {p[0]} {p[1]} {p[2]}")
    lines.append(f"""
        set type 1 shape {SHAPE[0]} {SHAPE[1]} {SHAPE[2]}
        set type 1 density 1.0
        set type 1 quat/random 11
        velocity all create 2.0 11 loop geom
        pair_style granular/ellipsoid
        pair_coeff * * {COEFF}
        fix integrate all nve/ellipsoid
        neighbor 0.1 bin
        neigh_modify {style_neigh}
        timestep 5e-4
        """)
    return "\n".join(lines)


def gas(style_neigh, steps):
    """The gas (T = 2: an atom moves half the skin in about 60 steps, so check yes builds
    every few dozen steps); positions and velocities by atom ID after `steps` steps, the
    pair's counts of contacts and of continued contacts."""
    lmp = new_lammps()
    lmp.commands_string(gas_input(style_neigh))
    lmp.command(f"run {steps}")
    nlocal = lmp.extract_global("nlocal")
    order = np.argsort(lmp.numpy.extract_atom("id")[:nlocal])
    x = lmp.numpy.extract_atom("x")[:nlocal][order].copy()
    v = lmp.numpy.extract_atom("v")[:nlocal][order].copy()
    contacts = lmp.extract_pair("counters/contacts")
    continued = lmp.extract_pair("counters/continued")
    lmp.close()
    return x, v, contacts, continued


def test_rows_between_builds_equal_rows_through_the_fix_at_every_step():
    steps = 2000
    x_every, v_every, contacts, continued = gas("every 1 delay 0 check no", steps)
    x, v, contacts_kept, continued_kept = gas("every 1 delay 0 check yes", steps)
    # contacts that lasted several steps (their springs carry history), the same in both
    assert continued > 200
    assert (contacts_kept, continued_kept) == (contacts, continued)
    dx = x - x_every
    dx -= BOX * np.round(dx / BOX)
    np.testing.assert_allclose(dx, 0.0, rtol=0, atol=1e-9)
    np.testing.assert_allclose(v, v_every, rtol=0, atol=1e-8)


def test_the_internal_fix_unfixed_is_an_error_not_a_crash():
    lmp = new_lammps()
    lmp.commands_string(gas_input("every 1 delay 0 check yes"))
    lmp.command("run 0")
    lmp.command("unfix STORE_CONTACT_ROWS_GRANULAR_ELLIPSOID")
    with pytest.raises(Exception, match="STORE_CONTACT_ROWS_GRANULAR_ELLIPSOID unfixed"):
        lmp.command("run 500")
    lmp.close()
