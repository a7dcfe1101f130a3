"""compute packing/ellipsoid, contact/histo, orient/histo (doc/compute_*.rst).

Every configuration is placed by hand (run 0: no motion), so the expected values are known:
- a lattice of randomly oriented, non-touching triaxial ellipsoids: volume fraction exact when
  the slab planes fall between layers; when they cut the ellipsoids, compared with a Monte Carlo
  estimate (fixed seed, tolerance 5 standard errors) that never uses the kernel's closed form;
- a designed contact network (tetrahedron of spheres + dangling ellipsoid + touching oblate
  pair across the periodic boundary + a near-miss prolate pair whose bounding spheres overlap)
  with known Z, rattlers and Z without rattlers;
- many sphere pairs with isotropic random contact normals: flat P(theta) = 1/(4 pi) within
  5 standard errors per bin and fabric tensor I/3 within 5 standard errors;
- stacks of slightly tilted flat oblate ellipsoids: contact normals peak at theta = 0, pi and
  have their minimum at pi/2; their short axes are vertical and long axes horizontal;
- under pair_style hybrid: an ERROR at init when another sub-style (not zero) could make
  contacts the computes cannot see; with zero and none the contacts are counted.
"""
import math
import os
import re
import tempfile

import numpy as np
import pytest

import geometry
from conftest import new_lammps
from placed_scenes import (SEMI, SPACING, array, assert_needs_ellipsoids, build_system,
                           lattice, mc_slab_volume, network, oblate_stacks, random_pairs,
                           section_area, vector)

from lammps import LMP_STYLE_ATOM, LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY, LMP_TYPE_VECTOR

# ----------------------------------------------------------------------------------------------
# packing/ellipsoid


def test_lattice_volume_fraction_whole_layers():
    box, parts = lattice()
    lmp = build_system(box, parts)
    # slab from z = 1 to 4: three whole layers (centres 1.5, 2.5, 3.5; half-heights <= 0.45)
    lmp.command("compute pk all packing/ellipsoid 1.0 4.0")
    lmp.command("run 0")
    v = vector(lmp, "pk")
    lmp.close()
    nx, ny = 4, 4
    expected = 3 * nx * ny * geometry.volume(SEMI) / (nx * ny * SPACING ** 2 * 3.0)
    assert v[0] == pytest.approx(expected, rel=1e-12)
    assert v[1] == 3 * nx * ny
    assert v[2] == 0.0 and v[3] == 0.0    # nothing touches
    assert v[6] == 3 * nx * ny            # all rattlers
    assert (v[4], v[5]) == (1.0, 4.0)
    assert v[7] == pytest.approx(2 * np.prod(SEMI) ** (1 / 3), rel=1e-12)
    assert v[8] == pytest.approx(3 * nx * ny * geometry.volume(SEMI), rel=1e-12)


def test_slab_cuts_ellipsoids_monte_carlo():
    box, parts = lattice(n=(2, 2, 3), seed=5)
    zlo, zhi = 0.63, 2.31     # cuts the first and third layers
    lmp = build_system(box, parts)
    lmp.command(f"compute pk all packing/ellipsoid {zlo} {zhi}")
    lmp.command("run 0")
    v = vector(lmp, "pk")
    lmp.close()
    rng = np.random.default_rng(2024)
    total, var = 0.0, 0.0
    for x, s, q in parts:
        est, err = mc_slab_volume(x, s, q, zlo, zhi, rng)
        total += est
        var += err ** 2
    area = (box[0][1] - box[0][0]) * (box[1][1] - box[1][0])
    # the cut layers really are cut (the test would not notice a whole-particle count otherwise)
    whole = sum(geometry.volume(s) for x, s, q in parts if zlo <= x[2] < zhi)
    assert abs(total - whole) > 20 * math.sqrt(var)
    assert v[8] == pytest.approx(total, abs=5 * math.sqrt(var))
    assert v[0] == pytest.approx(v[8] / (area * (zhi - zlo)), rel=1e-12)
    assert v[1] == sum(1 for x, _, _ in parts if zlo <= x[2] < zhi)


def test_slab_volume_exact_integral():
    """one tilted ellipsoid cut by many planes: compute against a scipy quadrature of the
    cross-section area obtained from the quadratic form (independent of the kernel's M_zz path)"""
    from scipy.integrate import quad
    rng = np.random.default_rng(11)
    q = geometry.random_quats(rng, 1)[0]
    semi = np.array([0.9, 0.5, 0.3])
    c = np.array([2.0, 2.0, 3.0])
    box = [(0.0, 4.0), (0.0, 4.0), (0.0, 6.0)]
    lmp = build_system(box, [(c, semi, q)])
    cuts = [(2.5, 3.1), (2.0, 4.0), (3.2, 3.9), (1.0, 2.95)]
    for k, (a, b) in enumerate(cuts):
        lmp.command(f"compute pk{k} all packing/ellipsoid {a} {b}")
    lmp.command("run 0")
    for k, (a, b) in enumerate(cuts):
        v = vector(lmp, f"pk{k}")
        ref, _ = quad(lambda z: section_area(c, semi, q, z), a, b, epsabs=1e-13, epsrel=1e-12,
                      limit=200)
        assert v[8] == pytest.approx(ref, rel=1e-8, abs=1e-12)
    lmp.close()


@pytest.mark.parametrize("newton", ["off", "on"])
def test_designed_network_coordination(newton):
    box, parts, expected = network()
    lmp = build_system(box, parts, newton=newton)
    lmp.commands_string("""
        compute z2 all packing/ellipsoid EDGE EDGE
        compute z4 all packing/ellipsoid EDGE EDGE rattler 4
        compute z0 all packing/ellipsoid EDGE EDGE rattler 0
        compute zt all packing/ellipsoid 1.2 6.0
        compute ch all contact/histo bins 6
        """)
    lmp.command("run 0")
    n = len(parts)
    v2, v4, v0, vt = (vector(lmp, c) for c in ("z2", "z4", "z0", "zt"))
    nsamples = vector(lmp, "ch")[8]
    lmp.close()
    assert nsamples == expected.sum(), "contact count per side"
    assert v2[1] == n
    assert v2[2] == pytest.approx(expected.sum() / n, rel=1e-14)
    # rattler 2: 5, 6, 7, 8, 9 removed; the tetrahedron keeps 3 contacts each
    assert v2[3] == pytest.approx(3.0, rel=1e-14)
    assert v2[6] == 5
    # rattler 4: atom 4 alone has 4 contacts; once 1-3 and 5 go it has none: all removed
    assert v4[3] == 0.0 and v4[6] == n
    # rattler 0: nothing removed
    assert v0[3] == pytest.approx(v0[2]) and v0[6] == 0
    # slab [1.2, 6): atoms 4 (z ~ 1.81), 5 (z ~ 3.29), 8, 9 (z = 1.5): 4 + 1 + 1 + 1 contacts;
    # rattlers are found in the whole group: 4 keeps its 3 tetrahedron contacts, 5, 8, 9 go
    assert vt[1] == 4
    assert vt[2] == pytest.approx(7 / 4, rel=1e-14)
    assert vt[3] == pytest.approx(3.0, rel=1e-14)
    assert vt[6] == 3


def test_subgroup_counts_contacts_with_any_particle():
    """group = the tetrahedron: its atom 4 also touches atom 5 (not in the group)"""
    box, parts, expected = network()
    lmp = build_system(box, parts)
    lmp.commands_string("""
        group tet id 1:4
        compute pk tet packing/ellipsoid EDGE EDGE
        compute ch tet contact/histo
        """)
    lmp.command("run 0")
    v, c = vector(lmp, "pk"), vector(lmp, "ch")
    lmp.close()
    assert v[1] == 4
    assert v[2] == pytest.approx(13 / 4, rel=1e-14)
    assert v[3] == pytest.approx(3.0, rel=1e-14)    # 5 is a rattler of the whole packing
    assert v[6] == 0
    assert c[8] == 13
    vol = sum(geometry.volume(s) for _, s, _ in parts[:4])
    assert v[8] == pytest.approx(vol, rel=1e-12)


def test_auto_slab():
    box, parts = lattice(n=(3, 3, 6), seed=9)
    lmp = build_system(box, parts)
    lmp.commands_string("""
        compute pa all packing/ellipsoid auto bottom 1.5 top 2
        compute pf all packing/ellipsoid auto bottom 1 top 1 floor 0.0
        compute pc all packing/ellipsoid auto bottom 1 top 1 surface columns
        """)
    lmp.command("run 0")
    va, vf, vc = vector(lmp, "pa"), vector(lmp, "pf"), vector(lmp, "pc")
    lmp.close()
    d = 2 * np.prod(SEMI) ** (1 / 3)
    h = [geometry.half_height(q, s) for _, s, q in parts]
    bottom = min(x[2] - hz for (x, _, _), hz in zip(parts, h))
    top = max(x[2] + hz for (x, _, _), hz in zip(parts, h))
    assert va[7] == pytest.approx(d, rel=1e-12)
    assert va[4] == pytest.approx(bottom + 1.5 * d, rel=1e-12)
    assert va[5] == pytest.approx(top - 2 * d, rel=1e-12)
    assert vf[4] == pytest.approx(d, rel=1e-12)
    # columns: grid of int(3 / d) per side; mean of the highest top in each column
    nc = int(3.0 / d)
    tops = {}
    for (x, _, _), hz in zip(parts, h):
        key = (min(nc - 1, int(x[0] / 3.0 * nc)), min(nc - 1, int(x[1] / 3.0 * nc)))
        tops[key] = max(tops.get(key, -1e300), x[2] + hz)
    assert vc[5] == pytest.approx(np.mean(list(tops.values())) - d, rel=1e-12)


def test_errors():
    box, parts = lattice(n=(2, 2, 2))
    lmp = build_system(box, parts)
    lmp.command("pair_style zero 1.0")
    lmp.command("pair_coeff * *")
    lmp.command("compute pk all packing/ellipsoid 0 1")
    with pytest.raises(Exception, match="granular/ellipsoid"):
        lmp.command("run 0")
    lmp.close()
    assert_needs_ellipsoids("compute ch all contact/histo")


# ----------------------------------------------------------------------------------------------
# contact/histo


def test_random_normals_flat_histogram():
    nbins = 10
    box, parts, normals = random_pairs()
    lmp = build_system(box, parts, periodic="p p p")
    lmp.command(f"compute ch all contact/histo bins {nbins}")
    lmp.command("run 0")
    a, v = array(lmp, "ch"), vector(lmp, "ch")
    lmp.close()
    npairs = len(normals)
    assert v[8] == 2 * npairs
    theta = np.linspace(0, math.pi, nbins + 1)
    domega = 2 * math.pi * (np.cos(theta[:-1]) - np.cos(theta[1:]))
    np.testing.assert_allclose(a[:, 0], 0.5 * (theta[:-1] + theta[1:]), rtol=1e-14)
    assert (a[:, 1] * domega).sum() == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_allclose(a[:, 1], a[::-1, 1], rtol=1e-12)     # symmetric about pi/2
    np.testing.assert_allclose(a[:, 2], a[:, 1] * domega, rtol=1e-12)
    # bin fraction f_k = Binomial(N, 2 p_k) / 2N with p_k = dOmega_k / 4 pi
    p = domega / (4 * math.pi)
    sigma = np.sqrt(2 * p * (1 - 2 * p) / npairs) / 2
    assert np.all(np.abs(a[:, 2] - p) < 5 * sigma), (a[:, 2], p, sigma)
    assert np.all(np.abs(a[:, 1] * 4 * math.pi - 1) < 0.4)
    # the exact histogram of the normals we placed
    ref = np.histogram(np.arccos(np.concatenate([normals[:, 2], -normals[:, 2]])),
                       bins=theta)[0]
    np.testing.assert_allclose(a[:, 2] * 2 * npairs, ref, atol=1e-6)
    # fabric: I/3 with standard error ~ sqrt(var(n_z^2) / N) = sqrt(4/45 / N)
    tol = 5 * math.sqrt(4 / 45 / npairs)
    np.testing.assert_allclose(v[:3], 1 / 3, atol=tol)
    np.testing.assert_allclose(v[3:6], 0.0, atol=tol)
    assert abs(v[6]) < 2 * tol
    F = np.einsum("ni,nj->ij", normals, normals) / npairs
    assert v[2] == pytest.approx(F[2, 2], rel=1e-10)
    dev = F - np.trace(F) / 3 * np.eye(3)
    assert v[7] == pytest.approx(math.sqrt(1.5 * (dev * dev).sum()), rel=1e-9)


def test_oblate_stacks_peak_vertical():
    box, parts = oblate_stacks()
    lmp = build_system(box, parts)
    lmp.commands_string("""
        compute ch all contact/histo bins 9
        compute os all orient/histo axis short bins 9
        compute ol all orient/histo axis long bins 9
        compute of all orient/histo axis short bins 9 fold yes
        """)
    lmp.command("run 0")
    a, v = array(lmp, "ch"), vector(lmp, "ch")
    os_a, os_v = array(lmp, "os"), vector(lmp, "os")
    ol_a, ol_v = array(lmp, "ol"), vector(lmp, "ol")
    of_a = array(lmp, "of")
    lmp.close()
    ncol, height = 4, 6
    assert v[8] == 2 * ncol * ncol * (height - 1), "every stacked pair touches, nothing else"
    P = a[:, 1]
    assert P[0] == pytest.approx(P.max(), rel=1e-12) and P[-1] == pytest.approx(P.max(), rel=1e-12)
    assert P[len(P) // 2] == P.min() == 0.0
    assert v[6] > 0.9    # Fzz - (Fxx+Fyy)/2 close to 1
    # short axes within 8 degrees of the vertical: only the first and last bin (20 degrees)
    assert os_a[0, 2] == pytest.approx(0.5) and os_a[-1, 2] == pytest.approx(0.5)
    assert of_a[0, 2] == pytest.approx(1.0)
    assert of_a[0, 1] * 2 * math.pi * (1 - math.cos(math.pi / 18)) == pytest.approx(1.0)
    assert os_v[0] > 0.95 and os_v[3] > 0.99 and os_v[4] > 0.95
    assert os_v[6] == ncol * ncol * height
    # oblate a = b: "long" is body x (tie resolved by index); it lies nearly horizontal
    assert ol_a[len(ol_a) // 2, 1] == ol_a[:, 1].max()
    assert ol_v[4] < -0.45


def test_orient_known_directions():
    """every long axis along z gives S = 1; random orientations give S ~ 0 and flat P"""
    box, parts = lattice(n=(6, 6, 6), seed=4)
    lmp = build_system(box, parts)
    lmp.commands_string("""
        compute ol all orient/histo bins 6
        compute om all orient/histo axis middle bins 6
        group half id <= 108
        compute oh half orient/histo bins 6 zlo 100 zhi 200
        """)
    lmp.command("run 0")
    a, v = array(lmp, "ol"), vector(lmp, "ol")
    vm = vector(lmp, "om")
    tilt = lmp.numpy.extract_compute("ol", LMP_STYLE_ATOM, LMP_TYPE_VECTOR).copy()
    tilt_m = lmp.numpy.extract_compute("om", LMP_STYLE_ATOM, LMP_TYPE_VECTOR).copy()
    tilt_h = lmp.numpy.extract_compute("oh", LMP_STYLE_ATOM, LMP_TYPE_VECTOR).copy()
    ids = lmp.numpy.extract_atom("id")[:len(parts)].copy()
    lmp.close()
    n = len(parts)
    u = np.array([geometry.rotation(q)[:, 0] for _, _, q in parts])   # longest = body x
    Q = 1.5 * np.einsum("ni,nj->ij", u, u) / n - 0.5 * np.eye(3)
    w, vec = np.linalg.eigh(Q)
    assert v[0] == pytest.approx(w[-1], rel=1e-10)
    assert abs(abs(np.dot(v[1:4], vec[:, -1])) - 1) < 1e-8
    assert v[4] == pytest.approx(Q[2, 2], abs=1e-12)
    assert v[5] == pytest.approx((u[:, 2] ** 2).mean(), rel=1e-12)
    assert v[6] == n
    theta = np.linspace(0, math.pi, 7)
    ref = np.histogram(np.arccos(np.concatenate([u[:, 2], -u[:, 2]])), bins=theta)[0]
    np.testing.assert_allclose(a[:, 2] * 2 * n, ref, atol=1e-6)
    um = np.array([geometry.rotation(q)[:, 1] for _, _, q in parts])
    assert vm[5] == pytest.approx((um[:, 2] ** 2).mean(), rel=1e-12)
    # per atom: the angle of the chosen axis to the vertical, in id order
    np.testing.assert_allclose(tilt[np.argsort(ids)], np.arccos(np.abs(u[:, 2])), atol=1e-12)
    np.testing.assert_allclose(tilt_m[np.argsort(ids)], np.arccos(np.abs(um[:, 2])), atol=1e-12)
    # a group and a slab that holds no atom: the group's atoms as before, the others 0
    half = np.sort(ids) <= 108
    by_id = tilt_h[np.argsort(ids)]
    np.testing.assert_allclose(by_id[half], np.arccos(np.abs(u[half, 2])), atol=1e-12)
    assert np.all(by_id[~half] == 0.0) and half.sum() == 108

    # all long axes vertical
    R = np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])
    parts = [(x, s, geometry.quat_from_matrix(R)) for x, s, _ in parts]
    lmp = build_system(box, parts)
    lmp.command("compute ol all orient/histo bins 6")
    lmp.command("run 0")
    a, v = array(lmp, "ol"), vector(lmp, "ol")
    lmp.close()
    assert v[0] == pytest.approx(1.0, abs=1e-12)
    assert v[4] == pytest.approx(1.0, abs=1e-12)
    assert a[0, 2] == pytest.approx(0.5) and a[-1, 2] == pytest.approx(0.5)


def test_thermo_fix_ave_time():
    box, parts = oblate_stacks(ncol=2, height=6)
    lmp = build_system(box, parts)
    fd, path = tempfile.mkstemp(suffix=".txt", prefix="avetime_")
    os.close(fd)
    try:
        lmp.commands_string(f"""
            compute pk all packing/ellipsoid auto bottom 0.5 top 0.5
            compute ch all contact/histo bins 6 slab pk
            compute or all orient/histo bins 6
            thermo_style custom step c_pk[1] c_pk[3] c_ch[7] c_or[1] c_ch[1][2]
            fix av all ave/time 1 1 1 c_ch[1] c_ch[2] c_or[2] mode vector file {path}
            fix aw all ave/time 1 1 1 c_pk c_ch mode vector
            run 0
            """)
        pk = vector(lmp, "pk")
        ch = array(lmp, "ch")
        orr = array(lmp, "or")
        rows = [[lmp.extract_fix("av", LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY, k, c) for c in range(3)]
                for k in range(6)]
        np.testing.assert_allclose(np.array(rows), np.column_stack([ch[:, 0], ch[:, 1],
                                                                     orr[:, 1]]), rtol=1e-14)
        w0 = lmp.extract_fix("aw", LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY, 0, 0)
        assert w0 == pytest.approx(pk[0])
        lines = [l for l in open(path) if not l.startswith("#")]
        assert len(lines) == 7    # header line + 6 rows
        assert pk[0] > 0.0 and pk[4] < pk[5]
    finally:
        lmp.close()
        os.remove(path)


def test_stale_contacts_error():
    box, parts, _ = network()
    lmp = build_system(box, parts)
    lmp.command("run 0")
    lmp.command("compute pk all packing/ellipsoid EDGE EDGE")
    with pytest.raises(Exception, match="before initialisation"):
        vector(lmp, "pk")
    lmp.command("run 0")    # now initialised: contacts of this step
    assert vector(lmp, "pk")[2] == pytest.approx(16 / 9)
    lmp.close()


# ----------------------------------------------------------------------------------------------
# pair_style hybrid: the computes read granular/ellipsoid's contacts only

# two overlapping spheres of type 1 and two of type 2 (every atom has a shape, as
# granular/ellipsoid requires), apart from each other
HYBRID_SCENE = """
units lj
atom_style hybrid sphere ellipsoid
boundary p p p
comm_modify vel yes
region box block 0 10 0 10 0 10
create_box 2 box
create_atoms 1 single 2.0 5 5
create_atoms 1 single 2.9 5 5
create_atoms 2 single 6.0 5 5
create_atoms 2 single 6.9 5 5
set type * diameter 1.0
set type * shape 1 1 1
set type * density 1.0
group two type 2
"""

CONTACT_COMPUTES = [("packing/ellipsoid EDGE EDGE", "Compute packing/ellipsoid"),
                    ("contact/histo", "Compute contact/histo"),
                    ("force/histo", "Compute force/histo")]


@pytest.mark.parametrize("hybrid", ["hybrid", "hybrid/overlay"])
@pytest.mark.parametrize("compute,who", CONTACT_COMPUTES)
def test_hybrid_with_another_contact_style_is_an_error(compute, who, hybrid):
    """the issue's input: type 1's contact belongs to pair granular, which the computes
    cannot see (they reported Z = 0 and no sample): an ERROR at init naming both"""
    lmp = new_lammps()
    try:
        lmp.commands_string(HYBRID_SCENE + f"""
            pair_style {hybrid} granular granular/ellipsoid
            pair_coeff 1 1 granular hooke 1000 0 tangential linear_nohistory 0 0
            pair_coeff 2 2 granular/ellipsoid hertz 1000 0
            pair_coeff 1 2 none
            compute c all {compute}
            """)
        with pytest.raises(Exception, match=re.escape(
                f"{who} counts the contacts of pair granular/ellipsoid only, but pair_style "
                f"{hybrid} also has sub-style granular")):
            lmp.command("run 0")
    finally:
        lmp.close()


def test_hybrid_with_zero_and_none_counts_every_contact():
    """granular/ellipsoid with zero and none, which make no contacts: the computes work and
    see the one contact (of type 2)"""
    lmp = new_lammps()
    try:
        lmp.commands_string(HYBRID_SCENE + """
            pair_style hybrid granular/ellipsoid zero 1.0
            pair_coeff 2 2 granular/ellipsoid hertz 1000 0
            pair_coeff 1 1 zero
            pair_coeff 1 2 none
            compute pk two packing/ellipsoid EDGE EDGE rattler 0
            compute all all packing/ellipsoid EDGE EDGE rattler 0
            compute ch all contact/histo
            run 0
            """)
        assert vector(lmp, "pk")[1:3] == pytest.approx([2, 1.0])
        assert vector(lmp, "all")[1:3] == pytest.approx([4, 0.5])
        assert vector(lmp, "ch")[8] == 2    # one contact, two samples
    finally:
        lmp.close()


def test_slab_keyword_reads_the_packing_computes_zlo_and_zhi():
    """`slab pk` reads elements 5 and 6 of compute packing/ellipsoid's vector (its zlo and zhi)
    through the compute's ID: the histograms equal those with zlo and zhi given as numbers."""
    box, parts = oblate_stacks(ncol=2, height=6)
    lmp = build_system(box, parts)
    try:
        lmp.commands_string("""
            compute pk all packing/ellipsoid auto bottom 0.5 top 0.5
            compute ch all contact/histo bins 6 slab pk
            compute oh all orient/histo bins 6 slab pk
            run 0
            """)
        pk = vector(lmp, "pk")
        zlo, zhi = pk[4], pk[5]
        assert 0.0 < zlo < zhi
        by_id = array(lmp, "ch").copy(), array(lmp, "oh").copy()
        lmp.commands_string(f"""
            compute chz all contact/histo bins 6 zlo {zlo!r} zhi {zhi!r}
            compute ohz all orient/histo bins 6 zlo {zlo!r} zhi {zhi!r}
            run 0
            """)
        assert by_id[0][:, 2].sum() > 0.0
        np.testing.assert_array_equal(by_id[0], array(lmp, "chz"))
        np.testing.assert_array_equal(by_id[1], array(lmp, "ohz"))
    finally:
        lmp.close()
