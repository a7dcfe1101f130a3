#!/usr/bin/python3
"""Packing fraction and coordination number of a LIGGGHTS deposit (tools/liggghts/examples).

usage: deposit_stats.py DIR [BOX_EDGE_X BOX_EDGE_Y]
Reads DIR/final.dump (dump custom: id type x y z quat1..4 shapex shapey shapez ...) and
DIR/contacts.dump (dump local of pair/gran/local id force: id_i id_j periodic fx fy fz).
Prints "key value" lines: n, height, phi (bulk, central slab), z_mean (contacts per particle,
particle-particle only), z_wall-free.

phi: exact volume of the ellipsoids inside the slab d_max <= z <= H - d_max (d_max = the longest
axis, 2 a; H = the mean of the 10 % highest centres), divided by the slab volume (closed-form ellipsoid slab volume,
as EllipsoidDep::ellipsoid_slab_volume). The box edges default to the box bounds of the dump.
"""
import sys

import numpy as np


def read_dump(path):
    """last snapshot of a LAMMPS/LIGGGHTS text dump: (box bounds, column names, rows)"""
    with open(path) as f:
        lines = f.read().splitlines()
    starts = [i for i, line in enumerate(lines) if line.startswith("ITEM: TIMESTEP")]
    lines = lines[starts[-1]:]
    box, cols, rows = [], [], []
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("ITEM: BOX BOUNDS"):
            box = [list(map(float, lines[i + k].split()[:2])) for k in (1, 2, 3)]
            i += 4
            continue
        if line.startswith("ITEM: ATOMS") or line.startswith("ITEM: ENTRIES"):
            cols = line.split()[2:]
            rows = [list(map(float, x.split())) for x in lines[i + 1:] if x.strip()]
            break
        i += 1
    return np.array(box), cols, np.array(rows).reshape(-1, len(cols)) if cols else np.zeros((0, 0))


def rotation(q):
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[w*w + x*x - y*y - z*z, 2*(x*y - w*z), 2*(x*z + w*y)],
                     [2*(x*y + w*z), w*w - x*x + y*y - z*z, 2*(y*z - w*x)],
                     [2*(x*z - w*y), 2*(y*z + w*x), w*w - x*x - y*y + z*z]])


def slab_volume(center_z, R, axes, zlo, zhi):
    """volume of the ellipsoid between z = zlo and z = zhi (closed form)"""
    h = np.sqrt(np.sum((R[2, :] * axes) ** 2))  # z half-extent sqrt(M_zz)
    vol = 4.0 / 3.0 * np.pi * np.prod(axes)
    t1 = np.clip((zlo - center_z) / h, -1.0, 1.0)
    t2 = np.clip((zhi - center_z) / h, -1.0, 1.0)
    return 0.75 * vol * ((t2 - t1) - (t2 ** 3 - t1 ** 3) / 3.0)


def stats(folder, lx=None, ly=None):
    box, cols, rows = read_dump(f"{folder}/final.dump")
    col = {name: k for k, name in enumerate(cols)}
    n = len(rows)
    if lx is None:
        lx, ly = box[0][1] - box[0][0], box[1][1] - box[1][0]
    z = rows[:, col["z"]]
    axes = rows[:, [col["shapex"], col["shapey"], col["shapez"]]]
    quat = rows[:, [col["quat1"], col["quat2"], col["quat3"], col["quat4"]]]
    dmax = 2.0 * axes.max()
    top = np.sort(z)[-max(1, n // 10):].mean()
    zlo, zhi = dmax, top - dmax
    out = {"n": n, "height": top}
    if zhi > zlo:
        solid = sum(slab_volume(z[i], rotation(quat[i]), axes[i], zlo, zhi) for i in range(n))
        out["phi"] = solid / (lx * ly * (zhi - zlo))
        out["slab_lo"], out["slab_hi"] = zlo, zhi
    try:
        _, ccols, crows = read_dump(f"{folder}/contacts.dump")
        pairs = {tuple(sorted((int(r[0]), int(r[1])))) for r in crows} if len(crows) else set()
        out["contacts"] = len(pairs)
        out["z_mean"] = 2.0 * len(pairs) / n if n else 0.0
    except (OSError, IndexError):
        pass
    return out


if __name__ == "__main__":
    args = sys.argv[1:]
    if not args:
        sys.exit(__doc__)
    extra = [float(a) for a in args[1:3]] if len(args) >= 3 else [None, None]
    for key, value in stats(args[0], *extra).items():
        print(key, value)
