"""compute packing/profile (doc/compute_packing_profile.rst).

Configurations are placed by hand (run 0), so the expected profiles are known:
- a layer of spheres: the volume of a sphere between two planes in closed form
  pi (R^2 (z2 - z1) - ((z2 - c)^3 - (z1 - c)^3) / 3);
- randomly oriented triaxial ellipsoids: each bin's solid volume against a scipy quadrature of
  the cross-section areas (an ellipse from the 2x2 block of the quadratic form), which never
  uses the kernel's closed form;
- the centre counts against numpy's histogram, the sum over the bins against compute
  packing/ellipsoid, periodic z images, fix ave/time output, and bad input.
"""
import math
import os

import numpy as np
import pytest
from scipy.integrate import quad

import geometry
import placed_scenes as ps


def profile(lmp, cid):
    return ps.array(lmp, cid)


def quadrature_volume(x, semi, q, z1, z2):
    h = geometry.half_height(q, semi)
    a, b = max(z1, x[2] - h), min(z2, x[2] + h)
    if b <= a:
        return 0.0
    return quad(lambda z: ps.section_area(x, semi, q, z), a, b, epsabs=1e-14, epsrel=1e-12)[0]


def sphere_slab_volume(c, r, z1, z2):
    a, b = max(z1, c - r), min(z2, c + r)
    if b <= a:
        return 0.0
    return math.pi * (r * r * (b - a) - ((b - c) ** 3 - (a - c) ** 3) / 3)


def test_sphere_layer_closed_form():
    r = 0.4
    unit = np.array([1.0, 0.0, 0.0, 0.0])
    centres = [np.array([i + 0.5, j + 0.5, 1.0 + 0.1 * ((i + j) % 3)])
               for i in range(3) for j in range(3)]
    parts = [(c, np.array([r, r, r]), unit) for c in centres]
    box = [(0.0, 3.0), (0.0, 3.0), (0.0, 3.0)]
    lmp = ps.build_system(box, parts)
    lmp.command("compute prof all packing/profile 0.15 zlo 0.3 zhi 2.0")
    lmp.command("run 0")
    a = profile(lmp, "prof")
    lmp.close()
    nbins = math.ceil((2.0 - 0.3) / 0.15)
    assert a.shape == (nbins, 4)
    edges = 0.3 + 0.15 * np.arange(nbins + 1)
    np.testing.assert_allclose(a[:, 0], 0.5 * (edges[:-1] + edges[1:]), rtol=1e-14)
    want = np.array([sum(sphere_slab_volume(c[2], r, z1, z2) for c in centres)
                     for z1, z2 in zip(edges[:-1], edges[1:])])
    np.testing.assert_allclose(a[:, 2], want, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(a[:, 1], want / (9.0 * 0.15), rtol=1e-12, atol=1e-14)
    assert a[:, 2].sum() == pytest.approx(9 * 4 / 3 * math.pi * r ** 3, rel=1e-12)
    counts, _ = np.histogram([c[2] for c in centres], bins=edges)
    np.testing.assert_array_equal(a[:, 3], counts)


def test_triaxial_against_quadrature_and_packing_compute():
    box, parts = ps.lattice(n=(3, 3, 3), seed=21)
    width = 0.37    # not commensurate with the lattice: the bins cut the particles
    lmp = ps.build_system(box, parts)
    lmp.commands_string(f"""
        compute prof all packing/profile {width}
        compute pk all packing/ellipsoid EDGE EDGE
        """)
    lmp.command("run 0")
    a = profile(lmp, "prof")
    vsolid = ps.vector(lmp, "pk")[8]
    lmp.close()
    zlo, zhi = box[2]
    nbins = math.ceil((zhi - zlo) / width)
    assert a.shape[0] == nbins
    edges = zlo + width * np.arange(nbins + 1)
    want = np.array([sum(quadrature_volume(x, s, q, z1, z2) for x, s, q in parts)
                     for z1, z2 in zip(edges[:-1], edges[1:])])
    assert np.count_nonzero(want) > 5
    np.testing.assert_allclose(a[:, 2], want, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(a[:, 1], want / (9.0 * width), rtol=1e-9, atol=1e-12)
    assert a[:, 2].sum() == pytest.approx(vsolid, rel=1e-12)
    counts, _ = np.histogram([x[2] for x, _, _ in parts], bins=edges)
    np.testing.assert_array_equal(a[:, 3], counts)


def test_periodic_z_images():
    """an ellipsoid across the periodic z boundary: its two parts land at the bottom and top"""
    semi = np.array([0.5, 0.3, 0.45])
    parts = [(np.array([1.0, 1.0, 0.2]), semi, np.array([1.0, 0.0, 0.0, 0.0]))]
    lmp = ps.build_system([(0.0, 2.0), (0.0, 2.0), (0.0, 3.0)], parts, periodic="p p p")
    lmp.command("compute prof all packing/profile 0.75")
    lmp.command("run 0")
    a = profile(lmp, "prof")
    lmp.close()
    v = geometry.volume(semi)
    assert a[:, 2].sum() == pytest.approx(v, rel=1e-12)
    # the part below z = 0 (0.25 of its half-height 0.45) reappears in the top bin [2.25, 3];
    # in units of the half-height it is a unit sphere's cap below 0 for a centre at 0.2 / 0.45
    cap = sphere_slab_volume(0.2 / 0.45, 1.0, -1.0, 0.0) / (4 / 3 * math.pi)
    assert a[-1, 2] == pytest.approx(cap * v, rel=1e-12)
    assert a[0, 2] == pytest.approx((1 - cap) * v, rel=1e-12)
    assert a[0, 3] == 1 and a[1:, 3].sum() == 0


def test_fix_ave_time_output(tmp_path):
    box, parts = ps.lattice(n=(2, 2, 2), seed=3)
    lmp = ps.build_system(box, parts)
    path = os.path.join(str(tmp_path), "profile.dat")
    lmp.commands_string(f"""
        compute prof all packing/profile 0.5
        fix av all ave/time 1 1 1 c_prof[*] mode vector file {path}
        run 0
        """)
    a = profile(lmp, "prof")
    lmp.close()
    rows = [line.split() for line in open(path) if not line.startswith("#")]
    assert int(rows[0][1]) == len(a)
    # fix ave/time writes 6 significant digits
    np.testing.assert_allclose(np.array(rows[1:], dtype=float)[:, 1:], a, rtol=1e-5, atol=1e-9)


@pytest.mark.parametrize("args,message", [
    ("", "Illegal compute packing/profile"),
    ("0", "width must be > 0"),
    ("-1", "width must be > 0"),
    ("0.1 zlo 2 zhi 1", "zhi > zlo"),
    ("0.1 zlo", "Illegal compute packing/profile"),
    ("0.1 bins 3", "Unknown compute packing/profile keyword: bins"),
    ("1e-9", "exceed the limit"),
])
def test_bad_input(args, message):
    box, parts = ps.lattice(n=(2, 2, 2))
    lmp = ps.build_system(box, parts)
    with pytest.raises(Exception, match=message):
        lmp.command(f"compute prof all packing/profile {args}")
    lmp.close()


def test_needs_ellipsoids():
    ps.assert_needs_ellipsoids("compute prof all packing/profile 0.1")
