"""The voxel view of a deposit's slab (tools/pores/pores.py): the voxel grid, the image of the
particles, the pore sizes from local thickness, the connectivity from bottom to top, the
geometric tortuosity, and the analysis of one voxel size (analyse_voxels)."""
import math
import os

import numpy as np
from scipy import ndimage

from pore_inscribed import largest_inscribed_ball

BIN_FRACTION = 0.125      # pore-size bins: this fraction of the smallest semi-axis wide
PROGRESS_VOXELS = 2_000_000    # show progress above this many voxels
TORTUOSITY_MAX_VOXELS = 1_500_000    # pore voxels; the path graph needs ~0.6 kB per voxel
# peak memory of the analysis per voxel of the image with its margins (doc/howto_pores.md)
VOXEL_BYTES = 80


def memory_bytes():
    """this machine's physical memory"""
    return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")


def check_memory(grid, voxel, bytes_per_voxel, option):
    """ValueError, before anything is allocated, when the grid's voxels would need more memory
    than the machine has (numpy would fail with a MemoryError, or the machine swap for hours)"""
    voxels = grid.nx * grid.ny * grid.nz
    need, have = voxels * bytes_per_voxel, memory_bytes()
    if need > have:
        raise ValueError("%s %.4g: %d x %d x %d = %.3g voxels would need about %s of memory "
                         "(%d bytes per voxel), more than this machine's %s; give a larger %s"
                         % (option, voxel, grid.nx, grid.ny, grid.nz, voxels, size_text(need),
                            bytes_per_voxel, size_text(have), option))


def size_text(nbytes):
    for unit, scale in (("TiB", 2 ** 40), ("GiB", 2 ** 30), ("MiB", 2 ** 20)):
        if nbytes >= scale:
            return "%.3g %s" % (nbytes / scale, unit)
    return "%d bytes" % nbytes


class Grid:
    """voxel grid over the box in x and y (periodic) and [z0, z0 + nz hz] in z; voxel (i, j, k)
    is centred at ((i + 1/2) hx, (j + 1/2) hy, z0 + (k + 1/2) hz) relative to the box corner"""

    def __init__(self, box, zlo, zhi, voxel, margin):
        lx, ly = box[0, 1] - box[0, 0], box[1, 1] - box[1, 0]
        self.origin = np.array([box[0, 0], box[1, 0]])
        self.nx = max(1, int(round(lx / voxel)))
        self.ny = max(1, int(round(ly / voxel)))
        self.hx, self.hy = lx / self.nx, ly / self.ny
        self.nslab = max(1, int(round((zhi - zlo) / voxel)))
        self.hz = (zhi - zlo) / self.nslab
        self.nbelow = int(math.ceil(margin / self.hz))
        floor_layers = int(math.floor((zlo - box[2, 0]) / self.hz))
        self.floor = self.nbelow > floor_layers    # the grid reaches the box bottom (a wall)
        if self.floor:
            self.nbelow = floor_layers
        self.nabove = int(math.ceil(margin / self.hz))
        self.nz = self.nbelow + self.nslab + self.nabove
        self.z0 = zlo - self.nbelow * self.hz
        self.spacing = (self.hx, self.hy, self.hz)

    @property
    def slab(self):
        return slice(self.nbelow, self.nbelow + self.nslab)

    @property
    def shape(self):
        return (self.nx, self.ny, self.nz)


def voxelize(particles, grid, progress, periodic=True):
    """solid[i, j, k]: the voxel centre lies inside some ellipsoid; x and y wrap around when
    periodic (the grid spans the periodic box), else the grid is cut out of the particles
    given (which must then include the periodic images that reach into it)"""
    solid = np.zeros(grid.shape, dtype=bool)
    lo = np.array([grid.origin[0], grid.origin[1], grid.z0])
    h = np.array(grid.spacing)
    if periodic and np.any(2 * particles.half_extent[:, :2]
                           >= [grid.nx * grid.hx, grid.ny * grid.hy]):
        raise ValueError("a particle is wider than the periodic box")
    if not periodic:
        last_index = np.array(grid.shape) - 1
    first = np.ceil((particles.centres - particles.half_extent - lo) / h - 0.5).astype(int)
    last = np.floor((particles.centres + particles.half_extent - lo) / h - 0.5).astype(int)
    n = len(particles)
    report = max(1, n // 10) if solid.size > PROGRESS_VOXELS else n + 1
    for p in range(n):
        kz = np.arange(max(first[p, 2], 0), min(last[p, 2], grid.nz - 1) + 1)
        if periodic:
            ix = np.arange(first[p, 0], last[p, 0] + 1)
            iy = np.arange(first[p, 1], last[p, 1] + 1)
        else:
            ix, iy = (np.arange(max(first[p, a], 0), min(last[p, a], last_index[a]) + 1)
                      for a in (0, 1))
        if kz.size == 0 or ix.size == 0 or iy.size == 0:
            continue
        d = [(idx + 0.5) * h[a] + lo[a] - particles.centres[p, a]
             for a, idx in enumerate((ix, iy, kz))]
        Q = particles.form[p]
        q = (Q[0, 0] * d[0][:, None, None] ** 2 + Q[1, 1] * d[1][None, :, None] ** 2
             + Q[2, 2] * d[2][None, None, :] ** 2
             + 2 * Q[0, 1] * d[0][:, None, None] * d[1][None, :, None]
             + 2 * Q[0, 2] * d[0][:, None, None] * d[2][None, None, :]
             + 2 * Q[1, 2] * d[1][None, :, None] * d[2][None, None, :])
        solid[np.ix_(ix % grid.nx, iy % grid.ny, kz)] |= q <= 1.0
        if (p + 1) % report == 0:
            progress("voxelised %d of %d particles" % (p + 1, n))
    return solid


def periodic_distance(mask, spacing, reach):
    """Euclidean distance from every True voxel to the nearest False voxel, periodic in x and
    y; exact wherever it is at most reach (the image is wrapped by that much on each side)"""
    px = min(int(math.ceil(reach / spacing[0])) + 1, 4 * mask.shape[0])
    py = min(int(math.ceil(reach / spacing[1])) + 1, 4 * mask.shape[1])
    padded = np.pad(mask, ((px, px), (py, py), (0, 0)), mode="wrap")
    d = ndimage.distance_transform_edt(padded, sampling=spacing)
    return d[px:px + mask.shape[0], py:py + mask.shape[1], :]


def local_thickness(pore, spacing, radii, window, progress):
    """local thickness level of the pore voxels in window (a z slice of the grid): the number
    of the given increasing ball radii (voxel distances) for which a ball inside the pore space
    contains the voxel. A ball of radius r is centred on a voxel whose distance to the solid is
    >= r; it covers the voxels within r of its centre. Returns (levels of the window's voxels,
    distance map of the grid: exact up to the largest radius, larger than it where the true
    distance is)."""
    distance = periodic_distance(pore, spacing, radii[-1])
    level = np.zeros(pore[:, :, window].shape, dtype=int)
    inside = pore[:, :, window]
    for n, r in enumerate(radii):
        # a ball of radius r reaches the window only from centres within r of it
        lo = max(0, window.start - int(math.ceil(r / spacing[2])))
        hi = min(pore.shape[2], window.stop + int(math.ceil(r / spacing[2])))
        centres = distance[:, :, lo:hi] >= r
        if not centres.any():
            break
        reach = periodic_distance(~centres, spacing, r)[:, :, window.start - lo:window.stop - lo]
        level[(reach <= r) & inside] = n + 1
        if pore.size > PROGRESS_VOXELS and (n + 1) % 5 == 0:
            progress("local thickness: radius %.4g (at most %.4g)" % (r, radii[-1]))
    return level, distance


def periodic_labels(pore, periodic=(True, True)):
    """face-connected components of the pore voxels, merged across the faces of the periodic
    axes among x and y; returns (labels, number of labels) with label 0 = solid"""
    labels, n = ndimage.label(pore)
    parent = np.arange(n + 1)

    def root(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    faces = ((labels[0], labels[-1]), (labels[:, 0], labels[:, -1]))
    for a, b in (pair for pair, p in zip(faces, periodic) if p):
        joined = (a > 0) & (b > 0)
        for u, v in set(zip(a[joined].tolist(), b[joined].tolist())):
            ru, rv = root(u), root(v)
            if ru != rv:
                parent[max(ru, rv)] = min(ru, rv)
    roots = np.array([root(k) for k in range(n + 1)])
    return roots[labels], n


def geometric_tortuosity(pore, spacing):
    """mean over the pore voxels of the top layer reached from the bottom layer of (shortest
    path through the pore voxels from any bottom pore voxel) / (height between the layer
    centres); paths step between 26-neighbours (x and y periodic). None if not connected or
    if the image has more than TORTUOSITY_MAX_VOXELS pore voxels (the graph's memory)."""
    nx, ny, nz = pore.shape
    n = int(pore.sum())
    if nz < 2 or n > TORTUOSITY_MAX_VOXELS:
        return None
    if nx < 3 or ny < 3:    # the periodic neighbours would repeat
        raise ValueError("geometric tortuosity needs at least 3 voxels in x and y")
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import dijkstra
    index = -np.ones(pore.shape, dtype=np.int32)
    index[pore] = np.arange(n, dtype=np.int32)
    rows, cols, weights = [], [], []
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            for dz in (0, 1):
                if (dz, dy, dx) <= (0, 0, 0):    # each neighbour pair once
                    continue
                a = index[:, :, :nz - dz]
                b = np.roll(index, (-dx, -dy), axis=(0, 1))[:, :, dz:]
                both = (a >= 0) & (b >= 0)
                rows.append(a[both])
                cols.append(b[both])
                weights.append(np.full(int(both.sum()), math.sqrt(
                    (dx * spacing[0]) ** 2 + (dy * spacing[1]) ** 2 + (dz * spacing[2]) ** 2)))
    graph = coo_matrix((np.concatenate(weights), (np.concatenate(rows), np.concatenate(cols))),
                       shape=(n, n)).tocsr()
    bottom = index[:, :, 0][pore[:, :, 0]]
    top = index[:, :, -1][pore[:, :, -1]]
    if bottom.size == 0 or top.size == 0:
        return None
    length = dijkstra(graph, directed=False, indices=bottom, min_only=True)[top]
    length = length[np.isfinite(length)]
    if length.size == 0:
        return None
    return float(length.mean() / ((nz - 1) * spacing[2]))


def analyse_voxels(particles, box, zlo, zhi, voxel, progress, check=True):
    """voxel porosity, pore sizes and connectivity of the slab at one voxel size; with check,
    a ValueError if the widest pore is narrower than 2 voxels"""
    width = BIN_FRACTION * float(particles.semi.min())    # pore-size bins, whatever the voxel
    margin = float(particles.semi.max())    # doubled below while a pore is wider than half
    for _ in range(4):
        grid = Grid(box, zlo, zhi, voxel, margin)
        check_memory(grid, voxel, VOXEL_BYTES, "--voxel")
        progress("voxel grid %d x %d x %d (slab %d layers), voxel %.4g"
                 % (grid.nx, grid.ny, grid.nz, grid.nslab, voxel))
        solid = voxelize(particles, grid, progress)
        if grid.floor:    # the box bottom is the ground: solid below the grid
            solid = np.concatenate([np.ones(grid.shape[:2] + (1,), bool), solid], axis=2)
            grid.nbelow += 1
            grid.nz += 1
            grid.z0 -= grid.hz
        pore = ~solid
        # the radii that matter: balls centred within margin / 2 of the slab; the bin edges
        # k w are the ball radii, so bin k holds the voxels of local thickness in
        # [k w, (k + 1) w) whatever the voxel
        radius_max = margin / 2.0
        h = min(grid.spacing)
        radii = width * np.arange(1, int(math.floor(radius_max / width)) + 1)
        level, distance = local_thickness(pore, grid.spacing, radii, grid.slab, progress)
        lo = max(0, grid.slab.start - int(math.ceil(radius_max / grid.hz)))
        hi = min(grid.nz, grid.slab.stop + int(math.ceil(radius_max / grid.hz)))
        if distance[:, :, lo:hi].max() <= radius_max:
            break
        margin *= 2.0    # a pore wider than the margin: enlarge it and redo
    else:
        raise RuntimeError("pores wider than the margin around the slab; is it inside the deposit?")

    slab_pore = pore[:, :, grid.slab]
    npore = int(slab_pore.sum())
    labels, _ = periodic_labels(slab_pore)
    spanning = np.intersect1d(labels[:, :, 0][labels[:, :, 0] > 0],
                              labels[:, :, -1][labels[:, :, -1] > 0])
    levels = level[slab_pore]
    counts = np.bincount(levels) if npore else np.zeros(0)
    thickness = np.where(pore[:, :, grid.slab], (level + 0.5) * width, 0.0)
    slab_distance = np.where(slab_pore, distance[:, :, grid.slab], 0.0)

    def centre(index):
        i, j, k = index
        return np.array([grid.origin[0] + (i + 0.5) * grid.hx,
                         grid.origin[1] + (j + 0.5) * grid.hy, zlo + (k + 0.5) * grid.hz])

    inscribed, inscribed_centre = largest_inscribed_ball(
        particles, box, zlo, zhi, slab_distance, centre, float(slab_distance.max()))
    if check and inscribed < h:
        raise ValueError("voxel %.4g too large for the pores: the widest pore (radius %.4g) is "
                         "under 2 voxels across; give a smaller --voxel" % (voxel, inscribed))
    return {
        "voxel_size": h,
        "voxel_spacing": list(grid.spacing),
        "grid": [grid.nx, grid.ny, grid.nslab],
        "porosity_voxel": npore / slab_pore.size,
        "largest_inscribed_radius": inscribed,
        "largest_inscribed_centre": None if inscribed_centre is None
        else inscribed_centre.tolist(),
        "largest_inscribed_radius_voxel": float(slab_distance.max()),
        "mean_pore_radius": float(thickness[slab_pore].mean()) if npore else 0.0,
        "connected_z": bool(spanning.size > 0),
        "connected_pore_fraction": float(np.isin(labels, spanning).sum() / max(npore, 1)),
        "geometric_tortuosity": geometric_tortuosity(slab_pore, grid.spacing),
        "pore_size_distribution": {"radius": ((np.arange(len(counts)) + 0.5) * width).tolist(),
                                   "volume_fraction": (counts / max(npore, 1)).tolist(),
                                   "bin_width": width},
        "margin": margin,
        "_solid_slab": solid[:, :, grid.slab],
        "_thickness": thickness,
        "_grid": grid,
    }
