"""Ellipsoid geometry for the tests, independent of the plugin's kernel (numpy/scipy only).

Conventions:
- a quaternion is (w, x, y, z); functions that take one normalise it first;
- a rotation matrix has the body axes as its columns (body to box);
- `semi` are the semi-axes (a, b, c) along the body axes x, y, z;
- the shape matrix M = R diag(a^2, b^2, c^2) R^T gives the support function of an ellipsoid
  of centre c: h(n) = n.c + sqrt(n^T M n) for a unit vector n.

The gap function of two ellipsoids A and B (separating-axis theorem) is, for unit n,
    d(n) = sqrt(n^T M_A n) + sqrt(n^T M_B n) - n.(c_B - c_A).
A negative value proves the bodies disjoint (n is a separating axis); when they overlap,
min_n d(n) > 0 is the penetration depth along the common normal n (from A to B).
"""
import math

import numpy as np
from scipy import optimize


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


# ------------------------------------------------------------------------------------------
# quaternions


def rotation(q):
    """Body-to-box rotation matrix (columns = body axes) of a quaternion (w, x, y, z)."""
    w, x, y, z = unit(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def quat_from_matrix(r):
    """Unit quaternion (w, x, y, z) of a rotation matrix."""
    from scipy.spatial.transform import Rotation
    x, y, z, w = Rotation.from_matrix(r).as_quat()
    return np.array([w, x, y, z])


def quat_axis_angle(axis, degrees):
    """Unit quaternion of a turn by `degrees` about `axis` (any length)."""
    half = math.radians(degrees) / 2
    return np.concatenate([[math.cos(half)], math.sin(half) * unit(axis)])


def axis_angle(q):
    """The words of `set atom ID quat a b c theta` for quaternion q: unit axis and angle in
    degrees (the identity as a zero turn about z)."""
    w, x, y, z = unit(q)
    angle = 2 * math.degrees(math.acos(max(-1.0, min(1.0, w))))
    axis = np.array([x, y, z])
    if np.linalg.norm(axis) < 1e-300:
        return (0.0, 0.0, 1.0, 0.0)
    return (*unit(axis), angle)


def random_quats(rng, n):
    """n quaternions uniform over the rotations (normalised 4-d Gaussians), shape (n, 4)."""
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1)[:, None]


# ------------------------------------------------------------------------------------------
# one ellipsoid


def volume(semi):
    return 4.0 / 3.0 * math.pi * float(np.prod(semi))


def shape_matrix(q, semi):
    """M = R diag(a^2, b^2, c^2) R^T."""
    r = rotation(q)
    return r @ np.diag(np.asarray(semi, dtype=float) ** 2) @ r.T


def half_height(q, semi):
    """Half the ellipsoid's extent in z: sqrt(M_zz)."""
    return math.sqrt(shape_matrix(q, semi)[2, 2])


def lowest_z(q, semi, z):
    """Height of the lowest point of an ellipsoid of centre height z."""
    return z - half_height(q, semi)


def half_width(q, semi, axis):
    """Half the ellipsoid's extent along coordinate axis (0 x, 1 y, 2 z): sqrt(M_kk)."""
    return math.sqrt(shape_matrix(q, semi)[axis, axis])


def farthest_from_z_axis(q, semi, centre, axis_xy):
    """The largest distance of the ellipsoid's points from the vertical line through axis_xy:
    its shadow on the xy plane is the ellipse of the shape matrix's xy block, whose farthest
    point from p lies at max over unit u of sqrt(u^T M_xy u) + u.(c - p) (support function);
    the angle sampled densely, then refined."""
    m = shape_matrix(q, semi)[:2, :2]
    d = np.asarray(centre, dtype=float)[:2] - np.asarray(axis_xy, dtype=float)

    def reach(angle):
        u = np.array([math.cos(angle), math.sin(angle)])
        return math.sqrt(u @ m @ u) + u @ d

    angles = np.linspace(0.0, 2.0 * math.pi, 3601)
    best = angles[int(np.argmax([reach(a) for a in angles]))]
    step = angles[1] - angles[0]
    found = optimize.minimize_scalar(lambda a: -reach(a), bounds=(best - step, best + step),
                                     method="bounded", options={"xatol": 1e-13})
    return max(reach(best), -found.fun)


# ------------------------------------------------------------------------------------------
# two ellipsoids


def gap(n, ma, mb, dc):
    """d(n) for the direction of n (normalised here); dc = c_B - c_A."""
    n = np.asarray(n, dtype=float)
    n = n / math.sqrt(n @ n)
    return math.sqrt(n @ ma @ n) + math.sqrt(n @ mb @ n) - n @ dc


def _tangent_pair(u):
    """Unit vectors e1, e2 completing unit u to a right-handed basis (x, y for u = z)."""
    k = 0 if abs(u[0]) < 0.9 else 1
    e1 = unit(np.eye(3)[k] - u[k] * u)
    return e1, np.cross(u, e1)


def sphere_minimum(f, starts, xatol=1e-12, fatol=1e-14, maxiter=None, stop_below=-np.inf):
    """Minimum of f(n) over unit vectors n: Nelder-Mead from each start direction u over the
    angles (s, t) of n = cos t (cos s u + sin s e1) + sin t e2, a chart of the whole sphere
    that is regular around u (its poles +-e2 are 90 degrees away), first simplex 0.05 rad.
    Returns (f, n) of the best start; stops at the first start whose minimum is below
    stop_below."""
    best = (np.inf, None)
    options = {"xatol": xatol, "fatol": fatol,
               "initial_simplex": [[0.0, 0.0], [0.05, 0.0], [0.0, 0.05]]}
    if maxiter is not None:
        options["maxiter"] = maxiter
    for start in starts:
        u = unit(start)
        e1, e2 = _tangent_pair(u)

        def direction(st):
            return math.cos(st[1]) * (math.cos(st[0]) * u + math.sin(st[0]) * e1) + \
                math.sin(st[1]) * e2

        res = optimize.minimize(lambda st: f(direction(st)), [0.0, 0.0], method="Nelder-Mead",
                                options=options)
        if res.fun < best[0]:
            best = (res.fun, unit(direction(res.x)))
        if best[0] < stop_below:
            break
    return best


def min_gap(ma, mb, dc, starts, **options):
    """Minimum of d(n) (sphere_minimum from the given start directions): (d, n)."""
    return sphere_minimum(lambda n: gap(n, ma, mb, dc), starts, **options)


def _fibonacci_sphere(n):
    """n nearly uniform unit vectors (Fibonacci lattice), shape (n, 3)."""
    k = np.arange(n) + 0.5
    z = 1 - 2 * k / n
    phi = math.pi * (1 + 5 ** 0.5) * k
    r = np.sqrt(1 - z * z)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def distance_for_depth(ma, mb, dc, u, depth=0.0, starts=None):
    """How far B must move along unit u from c_B - c_A = dc for min d to equal `depth`.
    Moved by t, d_t(n) = d(n) - t n.u: it falls with t where n.u > 0, so (when the bodies
    stay apart in the directions n.u <= 0, as for B above, beside or behind A along u) the
    answer is t = min over n.u > 0 of (d(n) - depth) / n.u. Without start directions, the
    best four of 20000 spread over the sphere."""
    u = unit(u)

    def ratio(n):
        nu = unit(n) @ u
        return (gap(n, ma, mb, dc) - depth) / nu if nu > 1e-12 else 1e300

    if starts is None:
        dirs = _fibonacci_sphere(20000)
        dirs = dirs[dirs @ u > 1e-6]
        vals = (np.sqrt(np.einsum("ij,jk,ik->i", dirs, ma, dirs)) +
                np.sqrt(np.einsum("ij,jk,ik->i", dirs, mb, dirs)) - dirs @ dc - depth) / (dirs @ u)
        starts = dirs[np.argsort(vals)[:4]]
    return sphere_minimum(ratio, starts)[0]


def touch_distance(qa, sa, qb, sb, u):
    """Centre distance along unit u at which the bodies (fixed orientations) first touch:
    the radius of the Minkowski sum A + (-B) along u."""
    return distance_for_depth(shape_matrix(qa, sa), shape_matrix(qb, sb), np.zeros(3), u)


def separating_axis(ca, qa, sa, cb, qb, sb, starts=12, seed=0):
    """Disjointness certificate: min d(n) searched from the centre line and `starts` random
    directions, stopping at the first negative value. Returns (d, n); d < 0 PROVES the
    bodies disjoint (n separates them)."""
    dc = np.asarray(cb, float) - np.asarray(ca, float)
    ma, mb = shape_matrix(qa, sa), shape_matrix(qb, sb)
    rng = np.random.default_rng(seed)
    directions = [dc] + list(rng.normal(size=(starts, 3)))
    for n in directions:    # a start that already separates needs no search
        if gap(n, ma, mb, dc) < 0.0:
            return gap(n, ma, mb, dc), unit(n)
    return min_gap(ma, mb, dc, directions, maxiter=4000, stop_below=0.0)


def minimum_image(d, box, periodic):
    """Separation vectors d (shape (..., 3)) wrapped into the nearest periodic image (box:
    rows lo, hi)."""
    d = np.array(d, dtype=float)
    for k in range(3):
        if periodic[k]:
            length = box[k, 1] - box[k, 0]
            d[..., k] -= length * np.round(d[..., k] / length)
    return d
