#!/usr/bin/env python3
"""Compare the run 0 outputs of two builds on one state (bench/scenes/in.force_run0):
compare_run0.py OLD NEW [--tol 1e-12] [--gravity 1.0], OLD and NEW the two `out` prefixes.

An atom's force is a sum of contact forces, gravity and the wall's force, which nearly cancel
for a particle at rest, so each difference is measured against the size of the terms summed:
  |F_new - F_old| <= tol * (|F_old| + m g + sum over its contacts of |f_c|)
  |T_new - T_old| <= tol * (|T_old| + r (m g + sum over its contacts of |f_c|))
(r: the largest semi-axis, which bounds the lever arm of every force on the atom; m g stands
for the wall's force on a particle resting on it). Both builds must see the same contacts.
Exit 1 on any violation."""
import argparse
import sys

import numpy as np


def entries(path, item):
    text = open(path).read().split(f"ITEM: {item}")[1].strip().splitlines()
    return np.array([[float(v) for v in line.split()] for line in text[1:]])


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("--tol", type=float, default=1e-12)
    p.add_argument("--gravity", type=float, default=1.0)
    a = p.parse_args()

    atoms_old, atoms_new = (entries(f"{x}.atoms", "ATOMS") for x in (a.old, a.new))
    if not np.array_equal(atoms_old[:, 0], atoms_new[:, 0]):
        sys.exit("compare_run0: the outputs hold different atoms")
    pairs_old, pairs_new = (entries(f"{x}.contacts", "ENTRIES") for x in (a.old, a.new))
    touching_old = pairs_old[pairs_old[:, 2] > 0.0]
    touching_new = pairs_new[pairs_new[:, 2] > 0.0]
    key = lambda rows: {(int(r[0]), int(r[1])) for r in rows}
    if key(touching_old) != key(touching_new):
        print(f"contact sets differ: {len(key(touching_old) ^ key(touching_new))} pairs")
        sys.exit(1)

    index = {int(i): k for k, i in enumerate(atoms_old[:, 0])}
    contact_sum = np.zeros(len(atoms_old))
    for row in touching_old:
        magnitude = np.linalg.norm(row[3:6])
        contact_sum[index[int(row[0])]] += magnitude
        contact_sum[index[int(row[1])]] += magnitude
    mass, radius = atoms_old[:, 1], atoms_old[:, 2:5].max(axis=1) / 2.0    # shape: diameters
    f_old, f_new = atoms_old[:, 5:8], atoms_new[:, 5:8]
    t_old, t_new = atoms_old[:, 8:11], atoms_new[:, 8:11]
    terms = mass * a.gravity + contact_sum
    f_scale = np.linalg.norm(f_old, axis=1) + terms
    t_scale = np.linalg.norm(t_old, axis=1) + radius * terms
    f_rel = np.linalg.norm(f_new - f_old, axis=1) / f_scale
    t_rel = np.linalg.norm(t_new - t_old, axis=1) / t_scale
    c_rel = np.linalg.norm(touching_new[:, 3:6] - touching_old[:, 3:6], axis=1) / np.maximum(
        np.linalg.norm(touching_old[:, 3:6], axis=1), np.finfo(float).tiny)
    print(f"{len(atoms_old)} atoms, {len(touching_old)} contacts: force rel. diff max "
          f"{f_rel.max():.3g}, torque {t_rel.max():.3g} (tolerance {a.tol:g}); contact "
          f"forces against their own size max {c_rel.max():.3g}, median {np.median(c_rel):.3g}")
    sys.exit(1 if f_rel.max() > a.tol or t_rel.max() > a.tol else 0)


if __name__ == "__main__":
    main()
