"""The largest ball in the pore space, refined from the voxel image to the exact particles.

The voxel distance transform measures distances to solid voxel centres, which misplaces the
surface by up to half a voxel; here the ball's centre moves off the voxel grid to maximise its
exact distance to the nearest ellipsoid surface (doc/howto_pores.md, "Largest inscribed ball").
"""
import numpy as np
from scipy import optimize

CANDIDATES = 12    # local maxima of the voxel distance map that are refined


def distance_to_ellipsoids(point, centres, rotations, semi):
    """distance from point to each ellipsoid's surface (0 inside). In the body frame the
    nearest surface point is x_i = a_i^2 y_i / (a_i^2 + t) with t > 0 the root of
    sum a_i^2 y_i^2 / (a_i^2 + t)^2 = 1, decreasing and convex in t: Newton from t = 0 rises
    monotonically to it."""
    y = np.einsum("nji,nj->ni", rotations, point - centres)    # R^T (p - c)
    a2 = semi ** 2
    outside = np.sum(y * y / a2, axis=1) > 1.0
    t = np.zeros(len(y))
    for _ in range(100):
        w = a2 * y * y / (a2 + t[:, None]) ** 2
        f = w.sum(axis=1) - 1.0
        df = -2.0 * (w / (a2 + t[:, None])).sum(axis=1)
        step = np.where(outside, -f / df, 0.0)
        t += step
        if np.all(np.abs(step) <= 1e-14 * (1.0 + t)):
            break
    nearest = a2 * y / (a2 + t[:, None])
    return np.where(outside, np.linalg.norm(y - nearest, axis=1), 0.0)


def largest_inscribed_ball(particles, box, zlo, zhi, distance, grid_points, start_radius):
    """(radius, centre) of the largest ball in the pore space centred in the slab, refined
    from the CANDIDATES largest local maxima of the voxel distance map (distance: the map on
    the slab's voxels, grid_points(index) -> voxel centre)"""
    peaks = (distance == _local_max(distance)) & (distance > 0)
    order = np.argsort(distance[peaks])[::-1][:CANDIDATES]
    starts = np.argwhere(peaks)[order]
    length = np.array([box[0, 1] - box[0, 0], box[1, 1] - box[1, 0]])
    reach = 2.0 * start_radius + 2.0 * float(particles.half_extent.max())
    best = (0.0, None)
    for index in starts:
        p0 = grid_points(index)
        # the particles (their periodic images in x and y) that can be nearest near p0
        d = particles.centres - p0
        d[:, :2] -= length * np.round(d[:, :2] / length)
        near = np.all(np.abs(d) <= reach, axis=1)
        centres = p0 + d[near]
        rot, semi = particles.rotations[near], particles.semi[near]

        def negative_clearance(p):
            q = np.array([p[0], p[1], min(max(p[2], zlo), zhi)])
            return -distance_to_ellipsoids(q, centres, rot, semi).min()

        res = optimize.minimize(negative_clearance, p0, method="Nelder-Mead",
                                options={"xatol": 1e-9, "fatol": 1e-12, "maxiter": 4000})
        if -res.fun > best[0]:
            c = res.x.copy()
            c[2] = min(max(c[2], zlo), zhi)
            best = (float(-res.fun), c)
    return best


def _local_max(a):
    from scipy import ndimage
    return ndimage.maximum_filter(a, size=3, mode=("wrap", "wrap", "nearest"))

