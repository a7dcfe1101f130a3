"""Bad input to pair_style granular/ellipsoid: a LAMMPS ERROR naming the problem, no crash."""
import re

import pytest

from conftest import new_lammps
import robust_helpers as rb
import scenes

SETUP = """
units lj
atom_style ellipsoid
comm_modify vel yes
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 single 1 1 1
create_atoms 1 single 2 1 1
set type 1 mass 1.0
set type 1 shape 1.2 1.0 0.8
"""


def expect_error(commands, message, setup=SETUP):
    lmp = new_lammps()
    try:
        with pytest.raises(Exception, match=re.escape(message)):
            lmp.commands_string(setup + commands)
    finally:
        lmp.close()


@pytest.mark.parametrize("style,message", [
    ("granular/ellipsoid tolerance", "Illegal pair_style granular/ellipsoid tolerance"),
    ("granular/ellipsoid tolerance abc", "Expected floating point parameter"),
    ("granular/ellipsoid tolerance 2", "tolerance must be in (0, 1)"),
    ("granular/ellipsoid iterations 0", "iterations must be >= 1"),
    ("granular/ellipsoid correction -5", "correction angle must be in [0, 180]"),
    ("granular/ellipsoid planes maybe", "Expected boolean parameter"),
    ("granular/ellipsoid preset quick", "Unknown pair_style granular/ellipsoid preset 'quick'"),
    ("granular/ellipsoid speed 3", "Unknown pair_style granular/ellipsoid keyword 'speed'"),
])
def test_bad_pair_style(style, message):
    expect_error(f"pair_style {style}\n", message)


@pytest.mark.parametrize("coeff,message", [
    ("hertz 1e4", "missing argument(s) for hertz kn K"),
    ("hertz x 1", "expected a number for hertz kn, got 'x'"),
    ("hertz -1 1", "hertz kn must be > 0"),
    ("hertz 1e4 -2", "hertz K must be >= 0"),
    ("spring 1e4 1", "unknown normal model 'spring'"),
    ("hertz/material unobtainium", "unknown material 'unobtainium'"),
    ("hertz/material 1e7 0.7 0.5", "hertz/material nu must be in (-1, 0.5)"),
    ("hertz/material 1e7 0.3 1.5", "hertz/material e must be in (0, 1]"),
    ("hertz 1e4 1 tangential sticky 1", "unknown tangential model 'sticky'"),
    ("hertz 1e4 1 tangential history 0 0.5", "tangential history kt must be > 0"),
    ("hertz 1e4 1 rolling spring 1", "unknown rolling model 'spring'"),
    ("hertz 1e4 1 colour red", "Unknown pair_coeff granular/ellipsoid keyword 'colour'"),
])
def test_bad_pair_coeff(coeff, message):
    expect_error(f"pair_style granular/ellipsoid\npair_coeff * * {coeff}\n", message)


def test_named_material_is_found():
    """(materials hold SI values: units lj refuses them, see test_unlike_materials.py)"""
    lmp = new_lammps()
    lmp.commands_string(SETUP.replace("units lj", "units si") + "pair_style granular/ellipsoid\n"
                        "pair_coeff * * hertz/material glass tangential history 1e4 0.3\nrun 0\n")
    lmp.close()


def test_needs_ghost_velocities():
    expect_error("comm_modify vel no\npair_style granular/ellipsoid\npair_coeff * * hertz 1e4 1\n"
                 "run 0\n", "comm_modify vel yes")


def test_needs_ellipsoid_atom_style():
    setup = SETUP.replace("atom_style ellipsoid", "atom_style sphere").replace(
        "set type 1 shape 1.2 1.0 0.8", "")
    expect_error("pair_style granular/ellipsoid\npair_coeff * * hertz 1e4 1\nrun 0\n",
                 "requires atom_style ellipsoid", setup)


def test_needs_a_shape_on_every_atom():
    setup = SETUP.replace("set type 1 shape 1.2 1.0 0.8", "set atom 1 shape 1.2 1.0 0.8")
    expect_error("pair_style granular/ellipsoid\npair_coeff * * hertz 1e4 1\nrun 0\n",
                 "requires every atom to be an ellipsoid", setup)


def test_unlike_models_cannot_mix():
    setup = SETUP.replace("create_box 1 box", "create_box 2 box").replace(
        "create_atoms 1 single 2 1 1", "create_atoms 2 single 2 1 1").replace(
        "set type 1 shape 1.2 1.0 0.8", "set type * shape 1.2 1.0 0.8").replace(
        "set type 1 mass 1.0", "set type * mass 1.0")
    expect_error("pair_style granular/ellipsoid\npair_coeff 1 1 hertz 1e4 1\n"
                 "pair_coeff 2 2 hertz 1e4 1 tangential viscous 0.1\nrun 0\n",
                 "use different models", setup)


def test_shapeless_atom_added_during_a_run():
    """fix deposit adds atoms without a shape: an ERROR naming the first at the neighbour list
    build that brings it (step 1), instead of reads outside the pair's arrays and lost atoms"""
    lmp = new_lammps()
    try:
        rb.assert_shapeless_atom_refused(
            lmp, scenes.shapeless_deposit(pair=True),
            "Pair granular/ellipsoid requires every atom to be an ellipsoid: atom 2 has no shape")
    finally:
        lmp.close()


def test_only_one_instance_under_hybrid():
    """a second instance replaced the first one's history fix: 'could not be found' at run 0,
    then an abort when LAMMPS was closed"""
    expect_error("pair_style hybrid granular/ellipsoid granular/ellipsoid\n",
                 "Pair granular/ellipsoid can be used only once")
