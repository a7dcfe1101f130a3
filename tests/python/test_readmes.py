"""The examples' READMEs say what runs today: their numbers are generated or checked here.

* examples/smoke: the styles `plugin list` (in.smoke) prints are the README's list.
* examples/silo: the README's table is plot_silo.py's table of the committed results/ (the
  runs' wall tables).
* examples/discharge: the README's tables are plot_discharge.py's of the committed results/
  (the rates, Beverloo's C and k, the stiffness check).
* examples/repose: the README's tables are repose_angle.py's of the committed results/*.json.
* examples/deposit: the depth numbers (mean particle volume, number-mean diameter, the depth
  at the quoted phi, the smallest N of the default shape) are tools/deposit/deposit_depth.py's.
* Every example input that includes in.deposit, and every `./ellipsoid-dep run` command in a
  README, is deep enough for its measuring slab (tools/deposit/deposit_run.py refuses it otherwise).
"""
import glob
import os
import re
import shlex
import sys

import pytest
from lammps import lammps

from conftest import root_dir

ROOT = root_dir()
sys.path.insert(0, os.path.join(ROOT, "examples", "silo"))
import deposit_depth  # noqa: E402
import deposit_run  # noqa: E402


def readme(name):
    return open(os.path.join(ROOT, "examples", name, "README.md")).read()


def generated(name, what):
    """the README's text between its markers <!-- BEGIN generated: what --> and <!-- END ... -->"""
    text = readme(name)
    begin = "<!-- BEGIN generated: %s -->\n" % what
    return text[text.index(begin) + len(begin):text.index("<!-- END generated: %s -->" % what)].strip()


def test_smoke_lists_the_loaded_styles(tmp_path):
    log = tmp_path / "log.lammps"
    lmp = lammps(cmdargs=["-log", str(log), "-screen", "none", "-nocite"])
    lmp.file(os.path.join(ROOT, "examples", "smoke", "in.smoke"))
    lmp.close()
    printed = [line.rstrip() for line in open(log)
               if re.match(r"(Currently loaded plugins|\s+\d+: )", line)]
    block = readme("smoke").split("```")[3].strip().splitlines()
    listed = [line.rstrip() for line in block if re.match(r"(Currently loaded|\s+\d+: )", line)]
    assert listed == printed
    count = int(printed[0].split(":")[1])
    words = {9: "nine", 10: "ten", 11: "eleven", 12: "twelve", 13: "thirteen"}
    assert "the package's %s styles" % words[count] in readme("smoke")


def test_silo_table_is_the_committed_data():
    import plot_silo
    text = readme("silo")
    start = text.index("| R / d | shape")
    committed = text[start:text.index("\n\n", start)]
    assert committed == plot_silo.table(plot_silo.runs()), \
        "examples/silo/README.md's table differs from its data: print it with plot_silo.py --table"


def test_discharge_tables_are_the_committed_data():
    sys.path.insert(0, os.path.join(ROOT, "examples", "discharge"))
    import plot_discharge
    committed = generated("discharge", "discharge tables")
    assert committed == plot_discharge.table(plot_discharge.runs()), \
        "examples/discharge/README.md's tables differ from the data: plot_discharge.py --table"


def test_repose_table_is_the_committed_data():
    sys.path.insert(0, os.path.join(ROOT, "examples", "repose"))
    import repose_angle
    committed = generated("repose", "repose table")
    runs = sorted(glob.glob(os.path.join(ROOT, "examples", "repose", "results", "*.json")))
    assert committed == repose_angle.table(repose_angle.read_runs(runs)), \
        "examples/repose/README.md's table differs from its data: print it with repose_angle.py --table"


def number(pattern, text):
    m = re.search(pattern, text)
    assert m, pattern
    return float(m.group(1))


def test_deposit_depth_numbers():
    text = " ".join(readme("deposit").split())
    volume, diameter = deposit_depth.size_moments(0.6)
    assert number(r"<v> = ([0-9.]+) d\^3", text) == round(volume, 3)
    assert number(r"d_mean = ([0-9.]+)", text) == round(diameter, 3)
    phi = number(r"<v> = [0-9.]+ d\^3 of the pour's size distribution, phi ([0-9.]+)", text)
    assert number(r"\(0\.09 phi\), ([0-9.]+) d for the default shape", text) == \
        round(volume / (0.09 * phi), 1)
    smallest = int(number(r"at the default shape, N = (\d+)", text))
    default = {"N": smallest, "eta": 1.4, "zeta": 1.8, "dr": 0.6, "vars": {}}
    assert deposit_depth.too_shallow(default) is None
    assert "give --N %d or more" % smallest in deposit_depth.too_shallow(
        dict(default, N=smallest - 1))


def example_settings(path):
    """N, eta, zeta, dr of an example input that includes in.deposit (its index variables
    over in.deposit's defaults)"""
    values = {"N": 1000, "eta": 1.4, "zeta": 1.8, "dr": 0.6, "width": 0, "slabmin": 1}
    for line in open(path):
        words = line.split()
        if words[:1] == ["variable"] and len(words) > 3 and words[2] == "index" \
                and words[1] in values:
            values[words[1]] = float(words[3])
    return {"N": int(values["N"]), "eta": values["eta"], "zeta": values["zeta"],
            "dr": values["dr"], "vars": {"width": values["width"], "slabmin": values["slabmin"]}}


@pytest.mark.parametrize("path", sorted(
    p for p in glob.glob(os.path.join(ROOT, "examples", "*", "in.*"))
    if "examples/deposit/in.deposit" in open(p).read()))
def test_examples_are_deep_enough(path):
    assert deposit_depth.too_shallow(example_settings(path)) is None


def test_readme_run_commands_are_deep_enough():
    """every `./ellipsoid-dep run --OPTION ...` line of a README or a howto: the runner's
    options and its depth check"""
    commands = []
    for path in glob.glob(os.path.join(ROOT, "examples", "*", "README.md")) + \
            glob.glob(os.path.join(ROOT, "doc", "howto_*.md")) + [os.path.join(ROOT, "README.md")]:
        for line in open(path):
            line = line.split("#")[0]
            m = re.match(r"(NP=\d+ )?\./ellipsoid-dep run( --.*)$", line.strip())
            if m and "--resume" not in m.group(2) and "--help" not in m.group(2):
                commands.append(shlex.split(m.group(2)))
    assert ["--N", "200"] in commands    # examples/deposit's one-rank command
    for args in commands:
        settings, _ = deposit_run.requested_settings(deposit_run.parse_args(args))
        assert deposit_depth.too_shallow(settings) is None, args
