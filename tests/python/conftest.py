"""Shared pytest fixtures: a LAMMPS instance with the ELLIPSOID_DEP plugin loaded.

The entry script and ctest set LAMMPS_PLUGIN_PATH, PYTHONPATH and LD_LIBRARY_PATH; LAMMPS
loads every *plugin.so on LAMMPS_PLUGIN_PATH at start-up.
"""
import os

import pytest
from lammps import lammps


def new_lammps(screen=False, comm=None):
    args = ["-log", "none", "-nocite"]
    if not screen:
        args += ["-screen", "none"]
    lmp = lammps(cmdargs=args, comm=comm) if comm is not None else lammps(cmdargs=args)
    if not lmp.has_style("pair", "granular/ellipsoid"):
        lmp.close()
        raise RuntimeError(
            "plugin not loaded: LAMMPS_PLUGIN_PATH=%s" % os.environ.get("LAMMPS_PLUGIN_PATH"))
    return lmp


@pytest.fixture
def lmp():
    instance = new_lammps()
    yield instance
    instance.close()


def root_dir():
    return os.environ.get("ELLIPSOID_DEP_ROOT",
                          os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))


def subprocess_env():
    """The environment for an mpirun/lmp child process: Python's snapshot of the start-up
    environment. MPI_Init in this process (the lammps module) adds variables to the C-level
    environment that make a child mpirun fail silently; passing this dict leaves them out."""
    return dict(os.environ)
