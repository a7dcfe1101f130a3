"""Exact volumes and areas of ellipsoids cut by a slab (tools/pores/pores.py): the solid fraction
of each particle inside the slab (closed form), the area of an ellipsoid (Carlson's R_G) and
of the zone a slab cuts from it (a converged quadrature); and both inside an axis-aligned box
(the flow solve's cut box: the slab's along one axis, a quadrature over the directions from
the centre at its edges and corners)."""
import math

import numpy as np
from scipy import special

QUADRATURE_NODES = (24, 32)    # zone quadrature: Gauss-Legendre in t, trapezoid in phi
KOZENY_CONSTANT = 5.0     # k = eps^3 / (K S_v^2), Carman's K = 5 (180 for spheres in d^2)


def kozeny_carman(porosity, specific_surface):
    """Kozeny-Carman's k = eps^3 / (K S_v^2) (inf without surface)"""
    if specific_surface <= 0:
        return math.inf
    return porosity ** 3 / (KOZENY_CONSTANT * specific_surface ** 2)


def slab_fraction(particles, zlo, zhi, axis=2):
    """fraction of each ellipsoid's volume between the planes normal to axis (z by default):
    the section area at t = (z - z_c)/h is (3 V / 4 h)(1 - t^2), h = sqrt(M_zz)"""
    t1, t2 = slab_heights(particles, zlo, zhi, axis)
    return np.maximum(0.75 * ((t2 - t1) - (t2 ** 3 - t1 ** 3) / 3.0), 0.0)


def slab_heights(particles, lo, hi, axis):
    """the planes' heights about each centre in units of its half-extent, clipped to [-1, 1]"""
    h = particles.half_extent[:, axis]
    c = particles.centres[:, axis]
    return np.clip((lo - c) / h, -1.0, 1.0), np.clip((hi - c) / h, -1.0, 1.0)


def ellipsoid_area(semi):
    """exact surface area 4 pi abc R_G(1/a^2, 1/b^2, 1/c^2) (Carlson's symmetric integral)"""
    s = np.asarray(semi, dtype=float)
    a, b, c = s[..., 0], s[..., 1], s[..., 2]
    return 4.0 * math.pi * a * b * c * special.elliprg(a ** -2, b ** -2, c ** -2)


def zone_area(semi, rotations, t1, t2, nodes=QUADRATURE_NODES, axis=2):
    """area of the part of each ellipsoid surface between z_c + h t1 and z_c + h t2 (z: the
    axis, 2 by default).

    The surface is the image of the unit sphere under x = z_c + R S u (S = diag(semi)), with
    area element abc |S^-1 u| dOmega. The height z = z_c + w.u, w = S R^T e_z, |w| = h, so the
    part between the planes is the spherical zone t1 <= u.w/h <= t2 about w: integrate in
    (t, phi) around that axis. The phi-integral is even in sqrt(1 - t^2), hence analytic in t,
    and Gauss-Legendre in t with the trapezoid rule in phi converge exponentially."""
    semi = np.asarray(semi, dtype=float).reshape(-1, 3)
    nt, nphi = nodes
    w = semi * rotations[:, axis, :]
    axis = w / np.linalg.norm(w, axis=1)[:, None]
    # an orthonormal pair perpendicular to the axis
    helper = np.where(np.abs(axis[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    e1 = np.cross(axis, helper)
    e1 /= np.linalg.norm(e1, axis=1)[:, None]
    e2 = np.cross(axis, e1)
    x, wt = np.polynomial.legendre.leggauss(nt)
    t = 0.5 * (t2 - t1)[:, None] * x[None, :] + 0.5 * (t2 + t1)[:, None]      # (n, nt)
    phi = 2.0 * math.pi * np.arange(nphi) / nphi
    rho = np.sqrt(np.clip(1.0 - t * t, 0.0, None))
    u = (t[:, :, None, None] * axis[:, None, None, :]
         + rho[:, :, None, None] * (np.cos(phi)[None, None, :, None] * e1[:, None, None, :]
                                    + np.sin(phi)[None, None, :, None] * e2[:, None, None, :]))
    integrand = np.sqrt(np.sum((u / semi[:, None, None, :]) ** 2, axis=-1))   # (n, nt, nphi)
    inner = integrand.mean(axis=2) * 2.0 * math.pi
    return np.prod(semi, axis=1) * 0.5 * (t2 - t1) * (inner @ wt)


def converged_zone_area(semi, rotations, t1, t2, rtol=1e-12, max_nodes=(1024, 2048), axis=2):
    """zone_area with the nodes doubled per particle until two successive results agree to
    rtol; returns (areas, largest relative change of the last doubling)"""
    semi = np.asarray(semi, dtype=float).reshape(-1, 3)
    areas = zone_area(semi, rotations, t1, t2, axis=axis)
    change = np.full(len(semi), np.inf)
    nodes = QUADRATURE_NODES
    todo = np.arange(len(semi))
    while todo.size:
        nodes = tuple(2 * n for n in nodes)
        if nodes[0] > max_nodes[0]:
            raise RuntimeError("zone quadrature did not converge to %g" % rtol)
        # chunks keep the (particles, t, phi, 3) array below about 50 MB
        chunk = max(1, 2_000_000 // (nodes[0] * nodes[1]))
        for k in range(0, todo.size, chunk):
            sel = todo[k:k + chunk]
            new = zone_area(semi[sel], rotations[sel], t1[sel], t2[sel], nodes, axis)
            change[sel] = np.abs(new - areas[sel]) / np.maximum(np.abs(new), 1e-300)
            areas[sel] = new
        todo = todo[change[todo] > rtol]
    return areas, float(change.max()) if len(semi) else 0.0


def slab_surface(particles, zlo, zhi):
    """solid surface area between the planes: exact for whole particles, the converged zone
    quadrature for those a plane cuts; returns (area, relative change of the last doubling of
    the quadrature nodes, number of cut particles)"""
    h = particles.half_extent[:, 2]
    z = particles.centres[:, 2]
    whole = (z - h >= zlo) & (z + h <= zhi)
    cut = ~whole & (z + h > zlo) & (z - h < zhi)
    area = float(ellipsoid_area(particles.semi[whole]).sum())
    change = 0.0
    if cut.any():
        t1 = np.clip((zlo - z[cut]) / h[cut], -1.0, 1.0)
        t2 = np.clip((zhi - z[cut]) / h[cut], -1.0, 1.0)
        zones, change = converged_zone_area(particles.semi[cut], particles.rotations[cut], t1, t2)
        area += float(zones.sum())
    return area, change, int(cut.sum())


def box_part(particles, ranges, rtol=1e-4, max_nodes=(1024, 2048)):
    """(volume fraction, surface area) of each ellipsoid inside the box ranges ((x0, x1),
    (y0, y1), (z0, z1)): exact for the particles wholly inside or outside and for those that
    only the faces of one axis cut (the slab along that axis: slab_fraction and the converged
    zone area); a quadrature over the directions from the centre for those at the box's edges
    and corners, its nodes doubled until the box's solid volume and area change by less than
    rtol of their totals. Returns (fractions, areas, that change)."""
    lo = np.array([r[0] for r in ranges], float)
    hi = np.array([r[1] for r in ranges], float)
    c, h = particles.centres, particles.half_extent
    outside = np.any((c + h <= lo) | (c - h >= hi), axis=1)
    crossed = ~outside[:, None] & ((c - h < lo) | (c + h > hi))    # by a face of that axis
    fractions = (~outside).astype(float)
    areas = np.where(outside, 0.0, ellipsoid_area(particles.semi))
    for axis in range(3):
        one = crossed[:, axis] & (crossed.sum(axis=1) == 1)
        if one.any():
            fractions[one] = slab_fraction(particles, lo[axis], hi[axis], axis)[one]
            t1, t2 = slab_heights(particles, lo[axis], hi[axis], axis)
            areas[one] = converged_zone_area(particles.semi[one], particles.rotations[one],
                                             t1[one], t2[one], axis=axis)[0]
    edges = crossed.sum(axis=1) > 1
    if not edges.any():
        return fractions, areas, 0.0
    volumes = particles.volumes
    nodes, previous = (64, 128), None
    while True:
        f, a = box_quadrature(particles.semi[edges], particles.rotations[edges], c[edges], lo, hi,
                              nodes)
        fractions[edges], areas[edges] = f, a
        if previous is not None:
            change = max(abs((f - previous[0]) @ volumes[edges]) / (fractions @ volumes),
                         abs((a - previous[1]).sum()) / areas.sum())
            if change <= rtol:
                return fractions, areas, change
        previous, nodes = (f, a), tuple(2 * n for n in nodes)
        if nodes[0] > max_nodes[0]:
            raise RuntimeError("box quadrature did not converge to %g" % rtol)


def box_quadrature(semi, rotations, centres, lo, hi, nodes):
    """the ray from the centre along R S u, r in [0, 1], lies in the box for r0 <= r <= r1
    (the slabs' intervals crossed with [0, 1]): the fraction of the volume inside is the mean
    over the directions of r1^3 - r0^3, the area the integral of abc |S^-1 u| over the
    directions whose surface point (r = 1) lies inside. Gauss-Legendre in cos(theta), the
    trapezoid in phi; chunks of particles keep each array below about 50 MB (six of them
    at once)."""
    nt, nphi = nodes
    x, wt = np.polynomial.legendre.leggauss(nt)
    phi = 2.0 * math.pi * np.arange(nphi) / nphi
    rho = np.sqrt(1.0 - x * x)
    u = np.stack([np.outer(rho, np.cos(phi)), np.outer(rho, np.sin(phi)),
                  np.repeat(x[:, None], nphi, axis=1)], axis=-1).reshape(-1, 3)
    weights = np.repeat(wt, nphi) * (2.0 * math.pi / nphi)    # sum 4 pi
    fractions, areas = np.empty(len(semi)), np.empty(len(semi))
    chunk = max(1, 2_000_000 // len(u))
    for k in range(0, len(semi), chunk):
        sl = slice(k, k + chunk)
        v = np.einsum("nij,nj,dj->ndi", rotations[sl], semi[sl], u)    # (n, directions, 3)
        with np.errstate(divide="ignore", invalid="ignore"):
            t_lo = (lo - centres[sl, None, :]) / v
            t_hi = (hi - centres[sl, None, :]) / v
        # a coordinate that does not move along the ray: inside for every r or for none (the
        # box half-open, so that the parts two boxes side by side cut add up to the whole)
        still = v == 0.0
        between = (centres[sl, None, :] >= lo) & (centres[sl, None, :] < hi)
        enter = np.where(still, np.where(between, -np.inf, np.inf), np.minimum(t_lo, t_hi))
        leave = np.where(still, np.where(between, np.inf, -np.inf), np.maximum(t_lo, t_hi))
        r0 = np.clip(enter.max(axis=2), 0.0, 1.0)
        r1 = np.clip(leave.min(axis=2), 0.0, 1.0)
        r1 = np.maximum(r1, r0)
        fractions[sl] = ((r1 ** 3 - r0 ** 3) @ weights) / (4.0 * math.pi)
        on_surface = (r1 >= 1.0) & (r0 < 1.0)
        element = np.sqrt(np.sum((u[None, :, :] / semi[sl, None, :]) ** 2, axis=-1))
        areas[sl] = np.prod(semi[sl], axis=1) * ((element * on_surface) @ weights)
    return fractions, areas
