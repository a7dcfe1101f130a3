"""The deposit's particles for tools/pores/pores.py: centres, rotations and semi-axes, read from the
runner's dump (deposit.dump: id type x y z quatw quati quatj quatk semi_a_x semi_a_y semi_a_z)
with the slab of its packing.dat; bad input is a ValueError that says what is wrong."""
import math
import os

import numpy as np

from deposit_run import read_packing


class Particles:
    """centres (N, 3), rotations (N, 3, 3) body -> box (columns = body axes), semi-axes (N, 3)"""

    def __init__(self, centres, quats, semi):
        self.centres = np.asarray(centres, dtype=float).reshape(-1, 3)
        self.semi = np.asarray(semi, dtype=float).reshape(-1, 3)
        quats = np.asarray(quats, dtype=float).reshape(-1, 4)
        if not len(self.centres):
            raise ValueError("no particles")
        if not (np.all(np.isfinite(self.centres)) and np.all(self.semi > 0)):
            raise ValueError("particles need finite centres and positive semi-axes")
        norms = np.linalg.norm(quats, axis=1)
        bad = np.flatnonzero(~(np.isfinite(norms) & (norms > 0)))
        if bad.size:
            raise ValueError("%d particles have no orientation (zero quaternion), the first "
                             "in row %d: %s" % (bad.size, bad[0] + 1,
                                                " ".join("%g" % q for q in quats[bad[0]])))
        self.rotations = rotation_matrices(quats)
        # M = R diag(s^2) R^T and Q = M^-1
        self.inverse_form = np.einsum("nij,nj,nkj->nik", self.rotations, self.semi ** 2,
                                      self.rotations)
        self.form = np.einsum("nij,nj,nkj->nik", self.rotations, self.semi ** -2, self.rotations)
        self.half_extent = np.sqrt(np.einsum("nii->ni", self.inverse_form))    # along x, y, z

    def __len__(self):
        return len(self.centres)

    @property
    def volumes(self):
        return 4.0 / 3.0 * math.pi * np.prod(self.semi, axis=1)


def rotation_matrices(quats):
    """unit quaternions (w, x, y, z) -> rotation matrices (normalised first)"""
    q = quats / np.linalg.norm(quats, axis=1)[:, None]
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)], 1)


def read_dump(path):
    """last frame of a LAMMPS custom dump with the runner's columns -> (Particles, box (3, 2))"""
    with open(path) as f:
        lines = f.read().splitlines()
    starts = [k for k, line in enumerate(lines) if line.startswith("ITEM: TIMESTEP")]
    if not starts:
        raise ValueError("%s: not a LAMMPS dump" % path)
    frame = lines[starts[-1]:]
    header = frame[8].split() if len(frame) > 8 else []
    if header[:2] != ["ITEM:", "ATOMS"] or not frame[2].startswith("ITEM: NUMBER OF ATOMS") \
            or not frame[4].startswith("ITEM: BOX BOUNDS"):
        raise ValueError("%s: unexpected dump layout or a truncated last frame (line %d)"
                         % (path, starts[-1] + 1))
    try:
        n = int(frame[3])
        box = np.array([[float(v) for v in frame[5 + k].split()[:2]] for k in range(3)])
    except ValueError:
        raise ValueError("%s: unreadable atom count or box in the last frame" % path) from None
    if n <= 0:
        raise ValueError("%s: no atoms in the last frame" % path)
    columns = header[2:]
    rows = [row.split() for row in frame[9:9 + n]]
    short = [k for k, row in enumerate(rows) if len(row) != len(columns)]
    if len(rows) < n or short:
        raise ValueError("%s: truncated dump: the last frame holds %d complete atom rows of %d"
                         % (path, short[0] if short else len(rows), n))
    try:
        data = np.array(rows, dtype=float)
    except ValueError:
        raise ValueError("%s: a non-numeric value in the atom rows" % path) from None

    def cols(names):
        missing = [c for c in names if c not in columns]
        if missing:
            raise ValueError("%s: missing dump columns %s" % (path, " ".join(missing)))
        return data[:, [columns.index(c) for c in names]]

    return (Particles(cols(["x", "y", "z"]), cols(["quatw", "quati", "quatj", "quatk"]),
                      cols(["semi_a_x", "semi_a_y", "semi_a_z"])), box)


def read_slab(run_dir):
    """packing.dat of a finished deposit's run folder, with its slab zlo < zhi"""
    path = os.path.join(run_dir, "packing.dat")
    pk = read_packing(path)
    missing = [k for k in ("zlo", "zhi") if not isinstance(pk.get(k), float)]
    if missing:
        raise ValueError("%s: no %s (not the packing.dat of a finished deposit)"
                         % (path, " or ".join(missing)))
    if not pk["zhi"] > pk["zlo"] or pk.get("slab_ok", 1) == 0:
        raise ValueError("%s: %s slab (zlo %g, zhi %g): the deposit is too shallow for its "
                         "measuring slab" % (path, "empty" if not pk["zhi"] > pk["zlo"]
                                             else "too thin a", pk["zlo"], pk["zhi"]))
    return pk
