"""What each command of ./ellipsoid-dep sets up before it runs: `./ellipsoid-dep plan COMMAND
[ARGS]` prints the list that the script's own set-up step follows. A LAMMPS user's commands
(run, lmp, python, study) build LAMMPS and the plugin, never LIGGGHTS nor OpenFOAM; test builds
LIGGGHTS (so the adapter is always tested) and installs OpenFOAM (the flow solve's tests);
bench builds LIGGGHTS only when its peers table, the one with LIGGGHTS rows, runs; pores needs
neither LAMMPS nor LIGGGHTS, and OpenFOAM only with --flow. Every command of the help text has a
plan, and an unknown one is refused. Cost: a few seconds (about 30 calls of the script)."""
import os
import re
import subprocess
import sys

import pytest

from conftest import root_dir

ROOT = root_dir()
SCRIPT = os.path.join(ROOT, "ellipsoid-dep")
sys.path.insert(0, os.path.join(ROOT, "bench"))
import run_bench    # noqa: E402

LAMMPS = ["packages", "lammps", "plugin"]
PLANS = [
    ("run", LAMMPS), ("run --N 4000 --np 1", LAMMPS), ("run my.in", LAMMPS),
    ("lmp -in in.x", LAMMPS), ("python x.py", LAMMPS), ("study -n", LAMMPS),
    ("setup-lammps", ["packages", "lammps"]),
    ("setup", LAMMPS + ["liggghts"]),
    ("test", LAMMPS + ["liggghts", "openfoam"]),
    ("test -R py.test_pores", LAMMPS + ["liggghts", "openfoam"]),
    ("test --sanitize", LAMMPS),
    ("bench", LAMMPS + ["liggghts"]), ("bench --full", LAMMPS + ["liggghts"]),
    ("bench --only peers", LAMMPS + ["liggghts"]), ("bench --only=peers", LAMMPS + ["liggghts"]),
    ("bench --only knobs --only peers", LAMMPS + ["liggghts"]),
    ("bench --only knobs", LAMMPS), ("bench --full --only scaling --only=spheres", LAMMPS),
    ("pores runs/x", ["packages"]), ("pores runs/x --flow", ["packages", "openfoam"]),
    ("fuzz 10", ["packages"]),
    ("liggghts setup", ["packages", "liggghts"]), ("liggghts -in in.x", ["packages", "liggghts"]),
    ("help", []),
]


def plan(args):
    r = subprocess.run(["bash", SCRIPT, "plan"] + args.split(), stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, timeout=30)
    return r.returncode, r.stdout.split(), r.stderr


@pytest.mark.parametrize("args,steps", PLANS, ids=[a for a, _ in PLANS])
def test_plan(args, steps):
    code, out, err = plan(args)
    assert code == 0, err
    assert out == steps


def test_every_command_of_the_help_has_a_plan():
    text = subprocess.run(["bash", SCRIPT, "help"], stdout=subprocess.PIPE, text=True,
                          check=True).stdout
    commands = sorted(set(re.findall(r"^  ([a-z][a-z-]*)", text, re.M)))
    assert {"run", "test", "bench", "pores", "liggghts", "plan"} <= set(commands)
    for c in commands:
        code, _, err = plan(c)
        assert code == 0, f"{c}: {err}"


def test_an_unknown_command_is_refused():
    code, out, err = plan("deposit")
    assert code != 0 and out == []
    assert "unknown command 'deposit'" in err


def test_bench_builds_liggghts_only_for_the_peers_table():
    # the shell decides from bench's arguments: it must know every subcommand and table
    for sub in run_bench.SUBCOMMANDS:
        assert "liggghts" not in plan(f"bench {sub}")[1], sub
    for part in run_bench.PARTS:
        assert ("liggghts" in plan(f"bench --only {part}")[1]) == (part == "peers"), part
