"""Hand-placed particle configurations for the computes' tests, with values known by
construction, and the means to load them (a data file read by LAMMPS, no dynamics).

A configuration is (box, particles): box = [(xlo, xhi), (ylo, yhi), (zlo, zhi)], particles =
a list of (centre(3), semi-axes(3), quaternion (w, x, y, z)); density 1, one atom type.
"""
import math
import os
import tempfile

import numpy as np
import pytest

import geometry
from conftest import new_lammps

from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY, LMP_TYPE_VECTOR


def write_data(path, box, particles):
    """particles: list of (x(3), semi_axes(3), quat(4)); density 1; one atom type"""
    with open(path, "w") as f:
        f.write("ELLIPSOID_DEP compute test\n\n")
        f.write(f"{len(particles)} atoms\n1 atom types\n{len(particles)} ellipsoids\n\n")
        for d, (lo, hi) in zip("xyz", box):
            f.write(f"{lo:.17g} {hi:.17g} {d}lo {d}hi\n")
        f.write("\nAtoms # ellipsoid\n\n")
        for k, (x, _, _) in enumerate(particles, 1):
            f.write(f"{k} 1 1 1.0 {x[0]:.17g} {x[1]:.17g} {x[2]:.17g}\n")
        f.write("\nEllipsoids\n\n")
        for k, (_, s, q) in enumerate(particles, 1):
            f.write(f"{k} {2 * s[0]:.17g} {2 * s[1]:.17g} {2 * s[2]:.17g} "
                    f"{q[0]:.17g} {q[1]:.17g} {q[2]:.17g} {q[3]:.17g}\n")


def build_system(box, particles, newton="off", periodic="p p f", lmp=None, extra=""):
    """a LAMMPS instance holding the particles, pair granular/ellipsoid, not yet run"""
    lmp = lmp or new_lammps()
    fd, path = tempfile.mkstemp(suffix=".data", prefix="computes_")
    os.close(fd)
    try:
        write_data(path, box, particles)
        lmp.commands_string(f"""
            units lj
            atom_style ellipsoid
            atom_modify map array
            newton {newton}
            comm_modify vel yes
            boundary {periodic}
            {extra}
            read_data {path}
            pair_style granular/ellipsoid
            pair_coeff * * hertz 1e5 0 tangential none
            neighbor 0.2 bin
            """)
    finally:
        os.remove(path)
    return lmp


def vector(lmp, cid):
    values = lmp.numpy.extract_compute(cid, LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR)
    return np.array(values, dtype=float)


def array(lmp, cid):
    return np.array(lmp.numpy.extract_compute(cid, LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY), dtype=float)


# ----------------------------------------------------------------------------------------------
# configurations


SEMI = np.array([0.45, 0.3, 0.2])    # triaxial, bounding radius 0.45
SPACING = 1.0                         # lattice constant > 2 * 0.45: nothing touches


def lattice(n=(4, 4, 5), seed=1):
    """simple cubic lattice of randomly oriented triaxial ellipsoids in a periodic xy box"""
    rng = np.random.default_rng(seed)
    nx, ny, nz = n
    quats = geometry.random_quats(rng, nx * ny * nz)
    parts = []
    k = 0
    for iz in range(nz):
        for iy in range(ny):
            for ix in range(nx):
                x = np.array([(ix + 0.5) * SPACING, (iy + 0.5) * SPACING, (iz + 0.5) * SPACING])
                parts.append((x, SEMI, quats[k]))
                k += 1
    box = [(0.0, nx * SPACING), (0.0, ny * SPACING), (-0.5, nz * SPACING + 1.0)]
    return box, parts


def network():
    """designed contact network; returns box, particles and the expected contacts per atom"""
    r = 0.5
    edge = 2 * r * 0.99
    base = np.array([3.0, 3.0, 1.0])
    tet = [base + np.array(v) * edge for v in
           [(0, 0, 0), (1, 0, 0), (0.5, math.sqrt(3) / 2, 0),
            (0.5, math.sqrt(3) / 6, math.sqrt(2.0 / 3.0))]]
    unit = np.array([1.0, 0.0, 0.0, 0.0])
    sph = np.array([r, r, r])
    parts = [(p, sph, unit) for p in tet]                                # atoms 1-4
    # dangling prolate ellipsoid on the top sphere, long axis (body x) along z
    R = np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])  # columns: body axes
    prolate = np.array([1.0, 0.35, 0.35])
    top = tet[3] + np.array([0.0, 0.0, r + prolate[0] - 0.02])
    parts.append((top, prolate, geometry.quat_from_matrix(R)))       # atom 5
    # near miss: parallel prolate ellipsoids along x, 0.72 apart in y (> 2 * 0.35): bounding
    # spheres (radius 1) overlap, the ellipsoids do not
    parts.append((np.array([3.0, 7.0, 1.0]), prolate, unit))            # atom 6
    parts.append((np.array([3.0, 7.72, 1.0]), prolate, unit))           # atom 7
    # two oblate ellipsoids side by side across the periodic x boundary (x = 0 = 10)
    oblate = np.array([0.6, 0.6, 0.2])
    parts.append((np.array([0.55, 5.0, 1.5]), oblate, unit))            # atom 8
    parts.append((np.array([9.7, 5.0, 1.5]), oblate, unit))             # atom 9  (gap 0.85 < 1.2)
    box = [(0.0, 10.0), (0.0, 10.0), (0.0, 6.0)]
    expected = np.array([3, 3, 3, 4, 1, 0, 0, 1, 1])
    return box, parts, expected


def random_pairs(npairs=3000, seed=7, spacing=2.6, r=0.5):
    """sphere pairs with isotropic random contact normals on a lattice; returns box, particles,
    normals"""
    rng = np.random.default_rng(seed)
    normals = rng.normal(size=(npairs, 3))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    side = int(math.ceil(npairs ** (1.0 / 3.0)))
    parts = []
    sph = np.array([r, r, r])
    unit = np.array([1.0, 0.0, 0.0, 0.0])
    for k in range(npairs):
        ix, iy, iz = k % side, (k // side) % side, k // (side * side)
        c = (np.array([ix, iy, iz]) + 0.5) * spacing
        d = normals[k] * r * 0.98
        parts.append((c - d, sph, unit))
        parts.append((c + d, sph, unit))
    L = side * spacing
    return [(0.0, L), (0.0, L), (0.0, L)], parts, normals


def min_penetration(xa, sa, qa, xb, sb, qb):
    """min of the gap function d(n) over directions n near +z (the stacked contacts): the
    penetration depth when > 0"""
    return geometry.min_gap(geometry.shape_matrix(qa, sa), geometry.shape_matrix(qb, sb),
                            np.asarray(xb) - np.asarray(xa), [(0.0, 0.0, 1.0)])[0]


def oblate_stacks(ncol=4, height=6, seed=3, tilt_deg=8.0):
    """columns of flat oblate ellipsoids (semi-axes 1, 1, 0.25) stacked with small random
    tilts and offsets, each overlapping the one below by 0.01 (checked with
    min_penetration); columns 2.6 apart, so no side contacts"""
    rng = np.random.default_rng(seed)
    semi = np.array([1.0, 1.0, 0.25])
    up = np.array([0.0, 0.0, 1.0])
    parts = []
    for cx in range(ncol):
        for cy in range(ncol):
            below = None
            for k in range(height):
                axis = rng.normal(size=3)
                axis[2] = 0.0
                q = geometry.quat_axis_angle(axis, rng.uniform(0, tilt_deg))
                off = rng.uniform(-0.1, 0.1, 2)
                x = np.array([(cx + 0.5) * 2.6 + off[0], (cy + 0.5) * 2.6 + off[1], 0.3])
                if below is not None:
                    # raised from the height of the one below until they overlap by 0.01
                    xb, _, qb = below
                    x[2] = xb[2] + geometry.distance_for_depth(
                        geometry.shape_matrix(qb, semi), geometry.shape_matrix(q, semi),
                        np.array([x[0], x[1], xb[2]]) - xb, up, depth=0.01, starts=[up])
                    depth = min_penetration(xb, semi, qb, x, semi, q)
                    assert abs(depth - 0.01) < 1e-10, depth
                parts.append((x, semi, q))
                below = parts[-1]
    box = [(0.0, ncol * 2.6), (0.0, ncol * 2.6), (0.0, height * 0.6 + 2.0)]
    return box, parts


def mc_slab_volume(x, semi, q, zlo, zhi, rng, n=400000):
    """Monte Carlo volume of an ellipsoid between two planes: uniform points in the unit ball
    mapped onto the ellipsoid; returns (estimate, standard error)"""
    p = rng.normal(size=(n, 3))
    p /= np.linalg.norm(p, axis=1)[:, None]
    p *= rng.uniform(size=(n, 1)) ** (1.0 / 3.0)
    pts = x + (p * semi) @ geometry.rotation(q).T
    inside = (pts[:, 2] >= zlo) & (pts[:, 2] <= zhi)
    frac = inside.mean()
    v = geometry.volume(semi)
    return v * frac, v * math.sqrt(frac * (1 - frac) / n)


def section_area(x, semi, q, z):
    """Area of the ellipsoid's cross-section by the plane at height z: the ellipse
    {p : (p - x)^T Q (p - x) <= 1, p_z = z} from the 2x2 block of the quadratic form Q."""
    r = geometry.rotation(q)
    Q = r @ np.diag(1 / np.asarray(semi) ** 2) @ r.T
    A = Q[:2, :2]
    b = Q[:2, 2] * (z - x[2])
    rhs = 1 - Q[2, 2] * (z - x[2]) ** 2 + b @ np.linalg.solve(A, b)
    return math.pi * max(rhs, 0.0) / math.sqrt(np.linalg.det(A))


def assert_needs_ellipsoids(command):
    """`command` refused in a box of atom_style sphere, with a message naming the style."""
    lmp = new_lammps()
    lmp.commands_string("""
        atom_style sphere
        region b block 0 1 0 1 0 1
        create_box 1 b
        """)
    with pytest.raises(Exception, match="atom style ellipsoid"):
        lmp.command(command)
    lmp.close()
