"""tools/pores/pores.py (doc/howto_pores.md) against analytic results and independent oracles.

- simple cubic lattice of touching spheres (diameter d = 1): porosity 1 - pi/6, specific
  surface pi/d (also for slab planes that cut the spheres: Archimedes' zones), largest
  inscribed pore radius (sqrt(3) - 1) d / 2, pore space connected from bottom to top;
- surface areas: prolate and oblate spheroids against their closed forms, a triaxial ellipsoid
  against a scipy double quadrature in the usual (theta, phi) parametrisation, cut spheroids
  against the surface-of-revolution integral;
- local thickness against a brute-force search over all ball centres on a small periodic grid;
  periodic connectivity on hand-made images;
- voxel porosity converging to the exact porosity as the voxel shrinks;
- a real (small) deposit of examples/deposit/in.deposit: porosity from the dump against
  1 - phi of compute packing/ellipsoid, and the whole tool on its run folder.
"""
import copy
import csv
import json
import math
import os
import warnings

import numpy as np
import pytest
from scipy import integrate

import geometry
import pore_voxels
import pore_surface
import pores
from conftest import new_lammps, root_dir

D = 1.0
SPHERE_R = 0.5 * D


def cubic_lattice(n=2, layers=8):
    """touching spheres of diameter 1 at the centres of unit cells; box n x n x layers"""
    c = np.array([[i + 0.5, j + 0.5, k + 0.5]
                  for i in range(n) for j in range(n) for k in range(layers)])
    p = pores.Particles(c, np.tile([1.0, 0, 0, 0], (len(c), 1)), np.full((len(c), 3), SPHERE_R))
    return p, np.array([[0, n], [0, n], [0, layers]], dtype=float)


# ---------------------------------------------------------------------------------------------
# simple cubic lattice


@pytest.mark.parametrize("zlo,zhi", [(2.0, 6.0), (2.25, 6.25), (1.7, 4.7)])
def test_cubic_lattice_exact_porosity_and_surface(zlo, zhi):
    """whole periods of the lattice in z: porosity 1 - pi/6; any slab: S_v = pi / d, since a
    sphere's zone area is 2 pi R x height (the cut spheres go through the quadrature)"""
    p, box = cubic_lattice()
    v_slab = 4.0 * (zhi - zlo)
    porosity = 1 - (pore_surface.slab_fraction(p, zlo, zhi) * p.volumes).sum() / v_slab
    assert porosity == pytest.approx(1 - math.pi / 6, rel=1e-13)
    area, change, ncut = pore_surface.slab_surface(p, zlo, zhi)
    assert area / v_slab == pytest.approx(math.pi / D, rel=1e-12)
    assert ncut == (0 if zlo == 2.0 else 8)
    assert change < 1e-12


def test_cubic_lattice_voxels():
    """voxel 2/33: a voxel centre sits on the cell centre, where the largest inscribed ball is
    (radius R = (sqrt(3) - 1) d / 2); voxel distances are to solid voxel centres, so the voxel
    radius lies in [R, R + sqrt(3) h / 2]; refined to the spheres it is R"""
    p, box = cubic_lattice()
    h = 2.0 / 33.0
    r = pores.analyse(p, box, 2.0, 6.0, voxel=h)
    R = (math.sqrt(3) - 1) * D / 2
    assert r["voxel_size"] == pytest.approx(h, rel=1e-12)
    assert r["porosity"] == pytest.approx(1 - math.pi / 6, rel=1e-13)
    assert r["specific_surface"] == pytest.approx(math.pi / D, rel=1e-12)
    assert R <= r["largest_inscribed_radius_voxel"] <= R + math.sqrt(3) / 2 * h
    assert r["largest_inscribed_radius"] == pytest.approx(R, abs=1e-9)
    centre = np.array(r["largest_inscribed_centre"])    # a cell centre: integer coordinates
    assert np.abs(centre - np.round(centre)).max() < 1e-6
    assert r["connected_z"] and r["connected_pore_fraction"] == 1.0
    # straight vertical channels along the cell edges; other paths detour a little
    assert 1.0 < r["geometric_tortuosity"] < 1.2
    psd = r["pore_size_distribution"]
    assert sum(psd["volume_fraction"]) == pytest.approx(1.0, rel=1e-12)
    # the largest local thickness is the largest ball, to one bin
    largest = psd["radius"][int(np.nonzero(psd["volume_fraction"])[0].max())]
    assert abs(largest - R) <= 1.5 * psd["bin_width"]
    assert abs(r["porosity_voxel"] - r["porosity"]) < 0.01
    assert r["kozeny_carman_permeability"] == pytest.approx(
        (1 - math.pi / 6) ** 3 / (5 * math.pi ** 2), rel=1e-12)
    assert r["convergence"]["voxel_size"] == pytest.approx([h, 2 * h])


# ---------------------------------------------------------------------------------------------
# surface areas


def test_cubic_lattice_default_settings():
    """at the default voxel (1/8 of the radius) the largest inscribed radius is within 3 % of
    (sqrt(3) - 1) d / 2 (refined: to 1e-9; the voxel map alone gives 0.3248, -11 %), also where
    no voxel centre sits on the cell centre (slab from 2.25); the pore-size bins are 1/8 of the
    radius wide whatever the voxel, and at the default more than the 2 of a voxel of 1/4"""
    p, box = cubic_lattice()
    R = (math.sqrt(3) - 1) * D / 2
    r = pores.analyse(p, box, 2.25, 6.25)
    assert r["voxel_size"] == pytest.approx(pores.VOXEL_FRACTION * SPHERE_R)
    assert abs(r["largest_inscribed_radius"] / R - 1) < 0.03
    assert r["largest_inscribed_radius"] == pytest.approx(R, abs=1e-9)
    assert r["convergence"]["largest_inscribed_radius"][1] == pytest.approx(R, abs=1e-9)
    psd = r["pore_size_distribution"]
    w = pore_voxels.BIN_FRACTION * SPHERE_R
    assert psd["bin_width"] == w
    np.testing.assert_allclose(psd["radius"], (np.arange(len(psd["radius"])) + 0.5) * w)
    assert len(psd["radius"]) >= 6 and psd["radius"][-1] - w / 2 <= R < psd["radius"][-1] + w / 2
    coarse = pores.analyse(p, box, 2.25, 6.25, voxel=2 * r["voxel_size"])
    assert coarse["pore_size_distribution"]["bin_width"] == w


def test_spheroid_areas_closed_form():
    a, c = 1.0, 2.5    # prolate: a = b < c
    e = math.sqrt(1 - a * a / (c * c))
    prolate = 2 * math.pi * a * a * (1 + c / (a * e) * math.asin(e))
    a, c = 2.0, 0.7    # oblate: a = b > c
    e = math.sqrt(1 - c * c / (a * a))
    oblate = 2 * math.pi * a * a * (1 + (1 - e * e) / e * math.atanh(e))
    got = pore_surface.ellipsoid_area(np.array([[1.0, 2.5, 1.0], [0.7, 2.0, 2.0]]))
    np.testing.assert_allclose(got, [prolate, oblate], rtol=1e-13)
    assert pore_surface.ellipsoid_area(np.array([0.3, 0.3, 0.3])) == pytest.approx(4 * math.pi * 0.09,
                                                                           rel=1e-14)


def test_triaxial_area_quadrature():
    a, b, c = 1.3, 0.8, 0.35

    def element(phi, theta):    # |r_theta x r_phi| of (a sin t cos p, b sin t sin p, c cos t)
        st, ct = math.sin(theta), math.cos(theta)
        return st * math.sqrt((b * c * st * math.cos(phi)) ** 2 + (a * c * st * math.sin(phi)) ** 2
                              + (a * b * ct) ** 2)

    ref, _ = integrate.dblquad(element, 0, math.pi, 0, 2 * math.pi, epsabs=1e-13, epsrel=1e-13)
    assert pore_surface.ellipsoid_area(np.array([a, b, c])) == pytest.approx(ref, rel=1e-11)
    # the zone quadrature over the whole surface, for tilted copies
    rng = np.random.default_rng(3)
    R = pores.rotation_matrices(geometry.random_quats(rng, 5))
    semi = np.tile([a, b, c], (5, 1))
    whole, change = pore_surface.converged_zone_area(semi, R, -np.ones(5), np.ones(5))
    assert change <= 1e-12
    np.testing.assert_allclose(whole, ref, rtol=1e-11)


def test_cut_spheroid_against_surface_of_revolution():
    """vertical spheroid (semi-axes a, a, c along z), cut between z1 and z2: area
    int 2 pi rho sqrt(1 + rho'^2) dz with rho(z) = a sqrt(1 - z^2 / c^2)"""
    for a, c in ((0.6, 1.4), (1.1, 0.4)):
        def ring(z):
            u = 1 - z * z / (c * c)
            return 2 * math.pi * a * math.sqrt(u + (a * z / (c * c)) ** 2)
        for z1, z2 in ((-0.3 * c, 0.9 * c), (0.2 * c, c), (-c, -0.5 * c)):
            ref, _ = integrate.quad(ring, z1, z2, epsabs=1e-14, epsrel=1e-13)
            got = pore_surface.converged_zone_area(np.array([[a, a, c]]), np.eye(3)[None],
                                            np.array([z1 / c]), np.array([z2 / c]))[0][0]
            assert got == pytest.approx(ref, rel=1e-11)


def test_tilted_cut_adds_up():
    """planes at several heights split a tilted triaxial ellipsoid into zones whose areas add
    up to the whole (each zone converged on its own)"""
    rng = np.random.default_rng(5)
    semi = np.array([[0.9, 0.5, 0.25]])
    R = pores.rotation_matrices(geometry.random_quats(rng, 1))
    cuts = np.array([-1.0, -0.62, -0.1, 0.33, 0.8, 1.0])
    zones = [pore_surface.converged_zone_area(semi, R, cuts[k:k + 1], cuts[k + 1:k + 2])[0][0]
             for k in range(5)]
    assert sum(zones) == pytest.approx(pore_surface.ellipsoid_area(semi[0]), rel=1e-12)
    assert min(zones) > 0


def sphere_beyond_two_planes(R, a, b):
    """volume and area of a sphere (centre 0) where X > a and Y > b: slices in X, each a disk
    of radius rho cut to Y > b (a circular segment) and a ring whose part with Y > b spans
    2 acos(b / rho) of its angle (the sphere's area element R dX dpsi)"""
    def rho(x):
        return math.sqrt(max(R * R - x * x, 0.0))

    def segment(x):
        r = rho(x)
        if b <= -r:
            return math.pi * r * r
        if b >= r:
            return 0.0
        return r * r * math.acos(b / r) - b * math.sqrt(r * r - b * b)

    def ring(x):
        r = rho(x)
        return 2 * R * math.acos(min(max(b / r, -1.0), 1.0)) if r > 0 else 0.0

    kinks = [x for x in (-math.sqrt(max(R * R - b * b, 0.0)), math.sqrt(max(R * R - b * b, 0.0)))
             if a < x < R]
    volume = integrate.quad(segment, a, R, epsabs=1e-13, epsrel=1e-11, limit=200,
                            points=kinks or None)[0]
    area = integrate.quad(ring, a, R, epsabs=1e-13, epsrel=1e-11, limit=200,
                          points=kinks or None)[0]
    return volume, area


def test_box_part_at_edges_and_corners():
    """spheres (turned at random, so that no quadrature node lies on a face) near an edge and
    a corner of the box, against one- and two-dimensional integrals of the sphere cut by
    planes; the tolerance the quadrature stops at holds for the box's totals; wholly inside
    and outside exact"""
    R = 0.5
    centres = np.array([[0.1, 2.0, 0.15], [3.8, 0.3, 1.5], [0.1, 0.15, 0.2],
                        [2.0, 2.0, 1.5], [9.0, 2.0, 1.5]])
    rng = np.random.default_rng(8)
    p = pores.Particles(centres, geometry.random_quats(rng, len(centres)),
                        np.full((len(centres), 3), R))
    fractions, areas, change = pore_surface.box_part(p, ((0.0, 4.0), (0.0, 4.0), (0.0, 3.0)),
                                                     rtol=1e-5)
    sphere_v, sphere_a = 4 / 3 * math.pi * R ** 3, 4 * math.pi * R ** 2
    edge = [sphere_beyond_two_planes(R, -0.1, -0.15), sphere_beyond_two_planes(R, -0.2, -0.3)]

    def corner_slice(x):    # the area of the slice X = x with Y > -0.15 and Z > -0.2
        r2 = R * R - x * x
        if r2 <= 0:
            return 0.0

        def height(y):
            top = math.sqrt(max(r2 - y * y, 0.0))
            return top - max(-0.2, -top)
        kink = [y for y in (math.sqrt(max(r2 - 0.04, 0.0)),) if -0.15 < y < math.sqrt(r2)]
        return integrate.quad(height, -0.15, math.sqrt(r2), epsabs=1e-12, epsrel=1e-10,
                              points=kink or None)[0]
    kink = [x for x in (math.sqrt(R * R - 0.04), math.sqrt(R * R - 0.15 ** 2),
                        math.sqrt(R * R - 0.04 - 0.15 ** 2)) if -0.1 < x < R]
    with warnings.catch_warnings():    # QUADPACK's roundoff note: its error estimate holds
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        corner, corner_error = integrate.quad(corner_slice, -0.1, R, epsabs=1e-10, epsrel=1e-9,
                                              limit=200, points=kink)
    assert corner_error < 1e-8
    want_v = [edge[0][0], edge[1][0], corner]
    np.testing.assert_allclose(fractions[:3] * sphere_v, want_v, rtol=1e-4)
    np.testing.assert_allclose(areas[:2], [edge[0][1], edge[1][1]], rtol=2e-3)
    assert change <= 1e-5
    assert fractions[:4].sum() * sphere_v == pytest.approx(sphere_v + sum(want_v), rel=2e-5)
    assert fractions[3] == 1.0 and areas[3] == pytest.approx(sphere_a, rel=1e-14)
    assert fractions[4] == 0.0 and areas[4] == 0.0


def test_box_part_along_one_axis_is_the_slab_turned():
    """tilted ellipsoids that only the faces of x (or y) cut: the exact slab of the same
    particles with x (or y) and z swapped; and the direction quadrature itself against the
    slab's closed forms"""
    rng = np.random.default_rng(9)
    n = 6
    semi = np.tile([0.9, 0.5, 0.25], (n, 1))
    quats = geometry.random_quats(rng, n)
    for axis in (0, 1):
        c = np.column_stack([rng.uniform(3, 7, n), rng.uniform(3, 7, n), rng.uniform(3, 7, n)])
        c[:, axis] = rng.uniform(0.6, 1.4, n)
        p = pores.Particles(c, quats, semi)
        box = [(0.0, 10.0)] * 3
        box[axis] = (0.9, 1.3)
        fractions, areas, change = pore_surface.box_part(p, box)
        assert change == 0.0    # no edge: no quadrature
        swap = [0, 1, 2]
        swap[axis], swap[2] = 2, axis
        turned = copy.copy(p)
        turned.centres = p.centres[:, swap]
        turned.half_extent = p.half_extent[:, swap]
        turned.rotations = p.rotations[:, swap, :]
        np.testing.assert_allclose(fractions, pore_surface.slab_fraction(turned, 0.9, 1.3),
                                   rtol=1e-13)
        h = turned.half_extent[:, 2]
        t1 = np.clip((0.9 - turned.centres[:, 2]) / h, -1, 1)
        t2 = np.clip((1.3 - turned.centres[:, 2]) / h, -1, 1)
        zones, _ = pore_surface.converged_zone_area(semi, turned.rotations, t1, t2)
        np.testing.assert_allclose(areas, zones, rtol=1e-11)
        if axis == 1:
            continue
        # the quadrature converges to them at first order at least (the area's integrand is an
        # indicator): its error falls eightfold or more from 128 to 1024 nodes
        lo, hi = np.array([b[0] for b in box]), np.array([b[1] for b in box])
        errors = []
        for nodes in ((128, 256), (1024, 2048)):
            f, a = pore_surface.box_quadrature(semi, p.rotations, c, lo, hi, nodes)
            errors.append((np.abs(f - fractions).max(), np.abs(a / areas - 1).max()))
        assert errors[1][0] < 1e-5 and errors[1][1] < 1e-4
        assert errors[1][0] < errors[0][0] / 8 and errors[1][1] < errors[0][1] / 8


# ---------------------------------------------------------------------------------------------
# voxel algorithms


def brute_local_thickness(pore, h, nlevels):
    """max over centres c of floor_h(dist(c)) such that |p - c| <= floor_h(dist(c)), with
    periodic minimum-image distances in x and y and plain ones in z"""
    n = np.array(pore.shape)
    idx = np.argwhere(np.ones(pore.shape, bool))
    solid = np.argwhere(~pore)

    def periodic(a, b):
        d = np.abs(a[:, None, :] - b[None, :, :]).astype(float)
        d[..., :2] = np.minimum(d[..., :2], n[:2] - d[..., :2])
        return h * np.sqrt((d * d).sum(-1))

    dist = periodic(idx, solid).min(axis=1)
    level = np.minimum(np.floor(dist / h + 1e-9), nlevels) * h
    centres = level > 0
    out = np.zeros(len(idx))
    pts = idx[pore.ravel()]
    d = periodic(pts, idx[centres])
    ok = d <= level[centres][None, :] + 1e-9
    out[pore.ravel()] = np.where(ok, level[centres][None, :], 0).max(axis=1)
    return out.reshape(pore.shape)


def test_local_thickness_brute_force():
    rng = np.random.default_rng(8)
    shape = (13, 11, 12)
    pore = rng.uniform(size=shape) > 0.015
    pore[:, :, [0, -1]] &= rng.uniform(size=(13, 11, 2)) > 0.5
    h = 1.0    # integer distances: ties at r = k h compare exactly in both computations
    radius_max = 4.5
    want = brute_local_thickness(pore, h, int(radius_max / h))
    for window in (slice(0, shape[2]), slice(4, 9)):    # balls from outside the window too
        got, _ = pore_voxels.local_thickness(pore, (h, h, h), h * np.arange(1, 5), window,
                                       lambda m: None)
        np.testing.assert_allclose(got, want[:, :, window], atol=1e-12)
        assert got.max() > 2 * h    # several levels really occur


def test_periodic_connectivity():
    """a pore path that reaches the top only by crossing the periodic x (then y) face"""
    for axis in (0, 1):
        pore = np.zeros((6, 6, 5), bool)
        pore[0, 2, 0:3] = True            # up from the bottom at x = 0 ...
        if axis == 0:
            pore[5, 2, 2:5] = True        # ... across x = 0 | x = 5 and up to the top
        else:
            pore[0, 2, 2] = pore[0, 1, 2] = pore[0, 0, 2] = True
            pore[0, 5, 2:5] = True        # ... along y, across y = 0 | y = 5, up
        labels, _ = pore_voxels.periodic_labels(pore)
        assert labels[0, 2, 0] == labels[pore][-1] > 0
        top = labels[:, :, -1][labels[:, :, -1] > 0]
        assert labels[0, 2, 0] in top
        closed = pore.copy()
        closed[:, :, 3] = False           # a solid layer closes it
        labels, _ = pore_voxels.periodic_labels(closed)
        assert not np.intersect1d(labels[:, :, 0][labels[:, :, 0] > 0],
                                  labels[:, :, -1][labels[:, :, -1] > 0]).size


def test_geometric_tortuosity(monkeypatch):
    """an open slab: 1; a one-voxel channel climbing diagonally in x and z, wrapping around
    the periodic x face: sqrt(1 + (hx/hz)^2); a closed slab: None; above the voxel limit:
    None"""
    spacing = (0.3, 0.2, 0.4)
    assert pore_voxels.geometric_tortuosity(np.ones((5, 4, 9), bool), spacing) == pytest.approx(1.0)
    pore = np.zeros((7, 5, 12), bool)
    k = np.arange(12)
    pore[(k + 3) % 7, 2, k] = True
    tau = pore_voxels.geometric_tortuosity(pore, spacing)
    assert tau == pytest.approx(math.hypot(0.3, 0.4) / 0.4, rel=1e-12)
    pore[:, :, 6] = False
    assert pore_voxels.geometric_tortuosity(pore, spacing) is None
    monkeypatch.setattr(pore_voxels, "TORTUOSITY_MAX_VOXELS", 179)    # the open slab has 180
    assert pore_voxels.geometric_tortuosity(np.ones((5, 4, 9), bool), spacing) is None


def test_voxel_porosity_converges():
    """randomly oriented triaxial ellipsoids (bounding radius 0.45) jittered on a unit lattice
    (so none overlap), crossing the periodic faces and cut by the slab planes: the voxel
    porosity approaches the closed-form porosity as h shrinks"""
    rng = np.random.default_rng(12)
    cells = np.array([[i, j, k + 0.5] for i in range(3) for j in range(3) for k in range(4)])
    n = len(cells)
    p = pores.Particles(cells + rng.uniform(-0.05, 0.05, size=(n, 3)), geometry.random_quats(rng, n),
                        np.tile([0.45, 0.3, 0.2], (n, 1)))
    box = np.array([[0, 3], [0, 3], [0, 4]], float)
    zlo, zhi = 0.83, 3.27
    exact = 1 - (pore_surface.slab_fraction(p, zlo, zhi) * p.volumes).sum() / (9 * (zhi - zlo))
    errors = []
    for h in (0.1, 0.05, 0.025):
        grid = pore_voxels.Grid(box, zlo, zhi, h, margin=0.0)
        solid = pore_voxels.voxelize(p, grid, lambda m: None)[:, :, grid.slab]
        errors.append(abs((1 - solid.mean()) - exact))
    assert errors[2] < errors[0] / 4
    assert errors[2] < 1e-3


# ---------------------------------------------------------------------------------------------
# a real deposit


@pytest.fixture(scope="module")
def deposit(tmp_path_factory):
    """examples/deposit/in.deposit with 200 mono-sized particles (about 7 d high, so the slab
    below the column surface is 4 d thick), stopped once all are in and their kinetic energy
    is below 0.05 m g d each (checked every 500 steps): small but real"""
    out = tmp_path_factory.mktemp("deposit")
    lmp = new_lammps()
    # the runner passes the tangential law words explicitly, as here
    for name, value in (("N", 200), ("dr", 0), ("ketol", 5e-2), ("chunk", 500), ("image", 0),
                        ("out", str(out)), ("seed", 17), ("tangential", '"history 2.0e3 0.5"')):
        lmp.command(f"variable {name} index {value}")
    lmp.file(os.path.join(root_dir(), "examples", "deposit", "in.deposit"))
    phi = lmp.extract_compute("pack", 0, 1)[0]
    lmp.close()
    return str(out), phi


def test_deposit_porosity_matches_packing_compute(deposit):
    out, phi = deposit
    particles, box = pores.read_dump(os.path.join(out, "deposit.dump"))
    pk = pores.read_packing(os.path.join(out, "packing.dat"))
    assert len(particles) == 200
    zlo, zhi = pk["zlo"], pk["zhi"]
    assert zhi > zlo + 2.0
    v_slab = (box[0, 1] - box[0, 0]) * (box[1, 1] - box[1, 0]) * (zhi - zlo)
    porosity = 1 - (pore_surface.slab_fraction(particles, zlo, zhi) * particles.volumes).sum() / v_slab
    # the dump holds 10 significant digits and packing.dat's zlo, zhi 6 decimals
    assert porosity == pytest.approx(1 - phi, abs=2e-5)
    assert porosity == pytest.approx(1 - pk["phi"], abs=2e-5)
    assert 0.25 < porosity < 0.75


def test_tool_on_the_run_folder(deposit):
    out, phi = deposit
    result = pores.run_folder(out, voxel=0.12, quiet=True)
    with open(os.path.join(out, "pores.json")) as f:
        saved = json.load(f)
    assert saved["porosity"] == pytest.approx(result["porosity"], rel=1e-15)
    assert abs(saved["porosity_check"]["difference"]) < 2e-5
    assert abs(saved["porosity_voxel"] - saved["porosity"]) < 0.03
    assert saved["specific_surface"] > 0 and saved["kozeny_carman_permeability"] > 0
    fine, coarse = saved["convergence"]["voxel_size"]    # fitted to whole voxels per box edge
    assert fine == saved["voxel_size"] and coarse == pytest.approx(2 * fine, rel=0.05)
    assert sum(saved["pore_size_distribution"]["volume_fraction"]) == pytest.approx(1.0)
    img = saved["voxel_image"]
    raw = np.fromfile(os.path.join(out, img["file"]), dtype=np.uint8)
    nx, ny, nz = img["shape_xyz"]
    assert raw.size == nx * ny * nz and set(np.unique(raw)) <= {0, 1}
    assert 1 - raw.mean() == pytest.approx(saved["porosity_voxel"], rel=1e-12)
    with open(os.path.join(out, img["header"])) as f:
        assert f"DimSize = {nx} {ny} {nz}" in f.read()
    assert os.path.getsize(os.path.join(out, "pores.png")) > 10000
    # the study figure path: several run folders against the shape
    table = pores.compare([out, out], os.path.join(out, "compare.png"))
    assert table[0]["runs"] == 2 and table[0]["porosity"] == pytest.approx(saved["porosity"])
    assert os.path.exists(os.path.join(out, "compare.png"))
    with open(os.path.join(out, "compare.csv")) as f:
        (row,) = list(csv.DictReader(f))
    assert int(row["runs"]) == 2 and float(row["porosity"]) == pytest.approx(saved["porosity"])
    assert float(row["porosity_sem"]) == 0.0    # the same run twice


def test_compare_errors_pool_the_seed_scatter(tmp_path):
    """--compare's error of a shape is the seed SD pooled over its group / sqrt(its seeds):
    two spheroids with two seeds each at +-0.01 (SD 0.01 sqrt 2) and one with a single seed,
    which gets the pooled SD instead of no error"""
    values = {(1.0, 1.0): [0.40, 0.42], (1.2, 1.0): [0.38, 0.40], (1.4, 1.0): [0.37]}
    folders = []
    for (eta, zeta), porosities in values.items():
        for seed, p in enumerate(porosities):
            d = tmp_path / ("eta%g_s%d" % (eta, seed))
            d.mkdir()
            (d / "packing.dat").write_text("eta %g\nzeta %g\n" % (eta, zeta))
            (d / "pores.json").write_text(json.dumps({
                "porosity": p, "specific_surface": 3.0, "kozeny_carman_permeability": 1e-3}))
            folders.append(str(d))
    table = {(r["eta"], r["zeta"]): r for r in pores.compare(folders, str(tmp_path / "c.png"))}
    sd = 0.01 * math.sqrt(2)
    assert table[(1.0, 1.0)]["porosity"] == pytest.approx(0.41)
    assert table[(1.0, 1.0)]["porosity_sem"] == pytest.approx(sd / math.sqrt(2))
    assert table[(1.4, 1.0)]["porosity_sem"] == pytest.approx(sd)
