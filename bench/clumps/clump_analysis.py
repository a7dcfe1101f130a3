"""Measure a clump deposit as compute packing/ellipsoid and compute contact/histo measure one of
ellipsoids (in.deposit's slab: auto bottom 1 top 2 surface columns, d = 1).

* Slab: z_bot = the lowest sphere bottom, z_top = the mean over the xy columns (n = floor(L/d)
  per side) of the highest sphere top of the clumps whose centre is in the column;
  z_lo = z_bot + 1 d, z_hi = z_top - 2 d.
* phi: the solid volume of the clumps' union (not the sum of the spheres, which counts the
  overlaps twice) between z_lo and z_hi over L^2 (z_hi - z_lo). Clumps wholly inside count
  their union volume (fit_clumps.py's Monte Carlo value); clumps crossing a plane count the
  points of a fixed uniform point set in each sphere that lie in no earlier sphere of the clump.
* Z: distinct pairs of clumps with at least one sphere overlap (wall contacts not counted),
  per clump whose centre is in the slab (the clump's centre: the mean of its spheres, exact
  for the mirror-symmetric clumps of fit_clumps.py).
* Contact normals: one per touching pair of clumps, the mean of its sphere contacts' normals
  weighted by their Hertz force xi^3/2 (normalised), at the same weighted mean of their contact
  points; both sides (n and -n) when that point is in the slab; 18 bins of theta in [0, pi],
  P_k = c_k / (C dOmega_k) (uniform = 1/4pi).
"""
import math

import numpy as np
from scipy.spatial import cKDTree

SLAB_BOTTOM, SLAB_TOP, DIAMETER, BINS = 1.0, 2.0, 1.0, 18


def read_final(path):
    """write_dump custom columns id mol type radius xu yu z, sorted by id."""
    with open(path) as f:
        lines = f.readlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS")) + 1
    data = np.loadtxt(lines[start:], ndmin=2)
    return {"mol": data[:, 1].astype(int), "radius": data[:, 3], "x": data[:, 4:7]}


def slab_bounds(x, radius, mol, centres, box):
    zbot = (x[:, 2] - radius).min()
    top_of = np.full(centres.shape[0], -np.inf)
    np.maximum.at(top_of, mol, x[:, 2] + radius)
    n = max(1, int(box / DIAMETER))
    col = np.floor(np.mod(centres[:, :2], box) / (box / n)).astype(int).clip(0, n - 1)
    key = col[:, 0] * n + col[:, 1]
    column_top = np.full(n * n, -np.inf)
    np.maximum.at(column_top, key, top_of)
    ztop = column_top[np.isfinite(column_top)].mean()
    return zbot + SLAB_BOTTOM * DIAMETER, ztop - SLAB_TOP * DIAMETER


def sphere_points(n=4096, seed=11):
    """Fixed uniform points in the unit ball."""
    rng = np.random.default_rng(seed)
    p = rng.normal(size=(n, 3))
    p /= np.linalg.norm(p, axis=1)[:, None]
    return p * rng.uniform(0, 1, n)[:, None] ** (1.0 / 3.0)


def union_volume_in_slab(x, radius, mol, union_volume, zlo, zhi):
    unit = sphere_points()
    lo_body = np.full(mol.max() + 1, np.inf)
    hi_body = np.full(mol.max() + 1, -np.inf)
    np.minimum.at(lo_body, mol, x[:, 2] - radius)
    np.maximum.at(hi_body, mol, x[:, 2] + radius)
    present = np.isfinite(lo_body)
    inside = present & (lo_body >= zlo) & (hi_body <= zhi)
    solid = union_volume * np.count_nonzero(inside)
    for body in np.nonzero(present & ~inside & (hi_body > zlo) & (lo_body < zhi))[0]:
        members = np.nonzero(mol == body)[0]
        for m, i in enumerate(members):
            pts = x[i] + radius[i] * unit
            keep = np.ones(len(pts), bool)
            for j in members[:m]:    # a point of an earlier sphere is counted there
                keep &= ((pts - x[j]) ** 2).sum(axis=1) > radius[j] ** 2
            in_slab = keep & (pts[:, 2] >= zlo) & (pts[:, 2] < zhi)
            solid += 4.0 / 3.0 * math.pi * radius[i] ** 3 * np.count_nonzero(in_slab) / len(pts)
    return solid


def sphere_contacts(x, radius, mol, box):
    """Sphere pairs of different clumps that overlap: (i, j, normal i->j, overlap, point)."""
    shifted = x.copy()
    shifted[:, :2] = np.mod(shifted[:, :2], box)
    shifted[:, 2] -= shifted[:, 2].min()
    zspan = shifted[:, 2].max() + 4 * radius.max() + 1.0
    tree = cKDTree(shifted, boxsize=[box, box, zspan])
    pairs = tree.query_pairs(2 * radius.max(), output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    keep = mol[i] != mol[j]
    i, j = i[keep], j[keep]
    delta = shifted[j] - shifted[i]
    delta[:, :2] -= box * np.round(delta[:, :2] / box)
    dist = np.linalg.norm(delta, axis=1)
    overlap = radius[i] + radius[j] - dist
    touch = overlap > 0
    i, j, delta, dist, overlap = i[touch], j[touch], delta[touch], dist[touch], overlap[touch]
    normal = delta / dist[:, None]
    point = x[i] + normal * (radius[i] - overlap / 2)[:, None]
    return i, j, normal, overlap, point


def measure(final_path, box, union_volume):
    d = read_final(final_path)
    x, radius = d["x"], d["radius"]
    _, mol = np.unique(d["mol"], return_inverse=True)
    nbody = mol.max() + 1
    counts = np.bincount(mol, minlength=nbody)
    centres = np.zeros((nbody, 3))
    np.add.at(centres, mol, x)
    centres /= counts[:, None]
    zlo, zhi = slab_bounds(x, radius, mol, centres, box)
    zhi = max(zhi, zlo)    # as compute packing/ellipsoid: an empty slab when the deposit is low
    solid = union_volume_in_slab(x, radius, mol, union_volume, zlo, zhi)
    phi = solid / (box * box * (zhi - zlo)) if zhi > zlo else 0.0

    i, j, normal, overlap, point = sphere_contacts(x, radius, mol, box)
    a, b = mol[i], mol[j]
    flip = a > b    # orient every sphere contact from the lower to the higher clump index
    normal[flip] *= -1
    a, b = np.where(flip, b, a), np.where(flip, a, b)
    pair_key = a * nbody + b
    keys, inverse = np.unique(pair_key, return_inverse=True)
    w = overlap ** 1.5
    n_sum = np.zeros((len(keys), 3))
    p_sum = np.zeros((len(keys), 3))
    w_sum = np.zeros(len(keys))
    np.add.at(n_sum, inverse, normal * w[:, None])
    np.add.at(p_sum, inverse, point * w[:, None])
    np.add.at(w_sum, inverse, w)
    n_pair = n_sum / np.linalg.norm(n_sum, axis=1)[:, None]
    z_pair = p_sum[:, 2] / w_sum
    body_a, body_b = keys // nbody, keys % nbody
    z_body = np.bincount(body_a, minlength=nbody) + np.bincount(body_b, minlength=nbody)
    in_slab = (centres[:, 2] >= zlo) & (centres[:, 2] < zhi)
    Z = z_body[in_slab].mean() if in_slab.any() else 0.0

    sel = (z_pair >= zlo) & (z_pair < zhi)
    cos_t = np.concatenate([n_pair[sel, 2], -n_pair[sel, 2]])
    theta = np.arccos(np.clip(cos_t, -1, 1))
    width = math.pi / BINS
    counts_k = np.bincount(np.minimum((theta / width).astype(int), BINS - 1), minlength=BINS)
    edges = np.arange(BINS + 1) * width
    d_omega = 2 * math.pi * (np.cos(edges[:-1]) - np.cos(edges[1:]))
    P = counts_k / max(counts_k.sum(), 1) / d_omega
    return {"phi": phi, "Z": Z, "zlo": zlo, "zhi": zhi, "Nslab": int(in_slab.sum()),
            "nbody": int(nbody), "sphere_contacts": int(len(i)), "body_contacts": int(len(keys)),
            "theta": (edges[:-1] + width / 2).tolist(), "P": P.tolist()}
