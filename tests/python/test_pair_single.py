"""single() (compute pair/local) evaluates a pair as the atoms are now.

Two unit spheres overlap by 0.02 at the end of a `run 0`; atom 2 is then moved 0.02 closer
with `set` (same time step, no force evaluation in between). compute pair/local, invoked
only then, must see the new overlap 0.04 and the new contact point, not the positions the
last force evaluation used.
"""
import pytest

from conftest import new_lammps


def test_single_sees_atoms_moved_since_the_last_force_evaluation():
    lmp = new_lammps()
    try:
        lmp.commands_string("""
            units lj
            atom_style ellipsoid
            atom_modify map array
            comm_modify vel yes
            region box block -3 3 -3 3 -3 3
            create_box 1 box
            create_atoms 1 single 0.0 0 0
            create_atoms 1 single 0.98 0 0
            set type 1 shape 1 1 1
            set type 1 density 1
            pair_style granular/ellipsoid
            pair_coeff * * hertz 1e4 10
            neighbor 0.5 bin
            compute pl all pair/local p1 p5
            run 0
            set atom 2 x 0.96
            """)
        overlap = lmp.numpy.extract_compute("pl", 2, 2)
        assert overlap.shape[0] == 1
        assert overlap[0, 0] == pytest.approx(0.04, abs=1e-12)
        assert overlap[0, 1] == pytest.approx(0.48, abs=1e-12)    # contact point x
    finally:
        lmp.close()
