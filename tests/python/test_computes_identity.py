"""The computes' references by ID (a slab compute, wall fixes, the pair's contact list) after
the referenced style was deleted or defined again between runs, and their outputs under
`thermo_modify norm yes` (doc/robustness.md, "Computes against the checklist").

A compute evaluated between runs (a library call such as extract_compute) must find what it
reads by its ID at that moment: a clear ERROR when it is gone, never memory freed since the
last run's init().
"""
import numpy as np
import pytest

from conftest import new_lammps
from placed_scenes import array, build_system, oblate_stacks, vector
from scenes import floor_stack

from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_SCALAR

SLAB_USERS = ["contact/histo bins 6", "orient/histo bins 6", "force/histo bins 6"]


def slab_scene():
    box, parts = oblate_stacks(ncol=2, height=6)
    lmp = build_system(box, parts)
    lmp.command("compute pk all packing/ellipsoid auto bottom 0.5 top 0.5")
    for k, style in enumerate(SLAB_USERS):
        lmp.command(f"compute h{k} all {style} slab pk")
    lmp.command("run 0")    # the default thermo invokes none of them
    return lmp


def test_deleted_slab_compute_is_an_error_between_runs():
    lmp = slab_scene()
    try:
        lmp.command("uncompute pk")
        for k in range(len(SLAB_USERS)):
            with pytest.raises(Exception, match="no compute with ID pk"):
                vector(lmp, f"h{k}")
    finally:
        lmp.close()


def test_slab_compute_of_another_style_is_an_error_between_runs():
    lmp = slab_scene()
    try:
        lmp.command("uncompute pk")
        lmp.command("compute pk all reduce sum x")
        with pytest.raises(Exception, match="slab compute pk is not packing/ellipsoid"):
            vector(lmp, "h0")
    finally:
        lmp.close()


def test_slab_compute_defined_again_is_found_by_its_id():
    """before a run the new packing compute is not initialised (its ERROR, not the old slab);
    after run 0 the histograms use the new slab, as with zlo and zhi given as numbers"""
    lmp = slab_scene()
    try:
        lmp.command("uncompute pk")
        lmp.command("compute pk all packing/ellipsoid 0.5 1.5")
        with pytest.raises(Exception, match="before initialisation"):
            vector(lmp, "h0")
        lmp.commands_string("""
            compute z0 all contact/histo bins 6 zlo 0.5 zhi 1.5
            compute z1 all orient/histo bins 6 zlo 0.5 zhi 1.5
            compute z2 all force/histo bins 6 zlo 0.5 zhi 1.5
            run 0
            """)
        for k in range(len(SLAB_USERS)):
            assert array(lmp, f"z{k}")[:, 2].sum() > 0.0    # samples in the slab
            np.testing.assert_array_equal(array(lmp, f"h{k}"), array(lmp, f"z{k}"))
    finally:
        lmp.close()


def test_replaced_pair_style_is_an_error_between_runs():
    box, parts = oblate_stacks(ncol=2, height=6)
    lmp = build_system(box, parts)
    try:
        lmp.commands_string("""
            compute pk all packing/ellipsoid EDGE EDGE
            compute ch all contact/histo
            compute fh all force/histo
            run 0
            pair_style zero 2.0
            pair_coeff * *
            """)
        for cid in ("pk", "ch", "fh"):
            with pytest.raises(Exception, match="pair style changed since the last run"):
                vector(lmp, cid)
    finally:
        lmp.close()


STACK = floor_stack()


def test_deleted_wall_fix_is_an_error_between_runs():
    lmp = new_lammps()
    try:
        lmp.commands_string(STACK + "run 3\nunfix floor\n")
        with pytest.raises(Exception, match="fix ID floor does not exist"):
            vector(lmp, "unb")
    finally:
        lmp.close()


def test_wall_fix_defined_again_is_read_anew():
    """the new fix's contacts array holds no contact until it has run: only the pair's (A, B)
    contact counts, where the old floor's run counted A's too"""
    lmp = new_lammps()
    try:
        lmp.commands_string(STACK + "run 3\n")
        assert vector(lmp, "unb")[3] == 2
        lmp.close()
        lmp = new_lammps()
        floor = [line for line in STACK.splitlines() if line.startswith("fix floor")][0]
        lmp.commands_string(STACK + f"run 3\nunfix floor\n{floor}\n")
        assert vector(lmp, "unb")[3] == 1
    finally:
        lmp.close()


def test_after_restart_defined_again_and_initialised_by_a_run(tmp_path):
    """the computes keep no state: read_restart, the same definitions, and after run 0 the
    same values as run 0 in the run that wrote the file; before that run, an ERROR"""
    path = str(tmp_path / "stack.restart")
    lines = STACK.splitlines()
    fixes = "\n".join(line for line in lines if line.startswith(("fix ", "compute ")))
    lmp = new_lammps()
    try:
        lmp.commands_string(STACK + OUTPUTS + f"run 3\nwrite_restart {path}\nrun 0\n")
        written = np.array(list(lmp.last_thermo().values())[1:], dtype=float)
        lmp.close()
        lmp = new_lammps()
        lmp.commands_string(f"read_restart {path}\ncomm_modify vel yes\n{fixes}\n" + OUTPUTS)
        with pytest.raises(Exception, match="before initialisation"):
            vector(lmp, "unb")
        lmp.command("run 0")
        np.testing.assert_allclose(np.array(list(lmp.last_thermo().values())[1:], dtype=float),
                                   written, rtol=1e-12, atol=1e-14)
    finally:
        lmp.close()


# every global output of the six computes; under lj units thermo's default norm yes divides
# extensive outputs by the atom count (3 here), so equal columns under norm yes and no prove
# each output flagged intensive
OUTPUTS = """
compute pk all packing/ellipsoid EDGE EDGE rattler 1
compute pp all packing/profile 0.5
compute ch all contact/histo bins 4
compute fh all force/histo bins 4
compute or all orient/histo bins 4
thermo_style custom step c_pk[*] c_ch[*] c_fh[*] c_or[*] c_unb c_unb[*] &
  c_pp[1][1] c_pp[1][2] c_pp[1][3] c_pp[1][4] c_ch[1][1] c_ch[1][2] c_ch[1][3] c_ch[1][4] &
  c_fh[1][1] c_fh[1][2] c_fh[1][3] c_or[1][1] c_or[1][2] c_or[1][3]
"""


def test_outputs_are_intensive():
    columns = {}
    for norm in ("yes", "no"):
        lmp = new_lammps()
        try:
            lmp.commands_string(STACK + OUTPUTS +
                                f"thermo_modify norm {norm}\nrun 3\n")
            assert lmp.extract_compute("unb", LMP_STYLE_GLOBAL, LMP_TYPE_SCALAR) > 0.0
            columns[norm] = np.array(list(lmp.last_thermo().values())[1:], dtype=float)
        finally:
            lmp.close()
    assert len(columns["no"]) == 9 + 9 + 5 + 7 + 1 + 4 + 14
    assert np.count_nonzero(columns["no"]) > 30
    np.testing.assert_array_equal(columns["yes"], columns["no"])


def test_periodic_images_count_each_volume_once():
    """an ellipsoid across the periodic x and z boundaries: packing/ellipsoid counts its whole
    volume once over the box and the part below z = 0 in a slab at the top (its image), as
    packing/profile does (test_packing_profile.py)"""
    semi = np.array([0.5, 0.3, 0.45])
    parts = [(np.array([0.1, 1.0, 0.2]), semi, np.array([1.0, 0.0, 0.0, 0.0]))]
    lmp = build_system([(0.0, 2.0), (0.0, 2.0), (0.0, 3.0)], parts, periodic="p p p")
    try:
        lmp.commands_string("""
            compute all all packing/ellipsoid EDGE EDGE
            compute top all packing/ellipsoid 2.25 3.0
            compute prof all packing/profile 0.75
            run 0
            """)
        volume = 4.0 / 3.0 * np.pi * semi.prod()
        assert vector(lmp, "all")[8] == pytest.approx(volume, rel=1e-12)
        assert vector(lmp, "top")[8] == pytest.approx(array(lmp, "prof")[-1, 2], rel=1e-12)
        assert 0.0 < vector(lmp, "top")[8] < 0.5 * volume
    finally:
        lmp.close()
