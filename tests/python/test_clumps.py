"""The clump benchmark's pieces (bench/clumps): the fitter's Monte Carlo volume and area against
the exact union of collinear spheres, the exact ellipsoid area, and the per-radius mapping of
our Hertz law to LAMMPS's pair granular and fix wall/gran (the coefficient files the fitter
writes), checked by the forces LAMMPS computes; a tiny clump pour.
"""
import math
import os
import sys

import numpy as np
import pytest

from conftest import new_lammps, root_dir

sys.path.insert(0, os.path.join(root_dir(), "bench", "clumps"))
import clump_analysis    # noqa: E402
import fit_clumps    # noqa: E402

KN, K, KT, MU = 1.0e4, 200.0, 2.0e3, 0.5


def cap_height(r, other_r, dist):
    """Height of the cap of a sphere of radius r inside another one (radius other_r) at dist."""
    x = (dist * dist + r * r - other_r * other_r) / (2 * dist)    # plane of the circle
    return r - x


def exact_chain(r0, x1, r1):
    """Volume and area of a sphere r0 at 0 and two r1 at +-x1 (ends not touching each other)."""
    h0, h1 = cap_height(r0, r1, x1), cap_height(r1, r0, x1)
    lens = math.pi / 3 * (h0 * h0 * (3 * r0 - h0) + h1 * h1 * (3 * r1 - h1))
    volume = 4 / 3 * math.pi * (r0 ** 3 + 2 * r1 ** 3) - 2 * lens
    area = 4 * math.pi * (r0 * r0 + 2 * r1 * r1) - 2 * (2 * math.pi * r0 * h0) - \
        2 * (2 * math.pi * r1 * h1)
    return volume, area


def test_union_volume_and_area_match_the_exact_values_within_their_errors():
    r0, x1, r1 = 0.43, 0.41, 0.34
    assert 2 * x1 > 2 * r1    # the two end spheres are apart: only two lenses
    axes = fit_clumps.semi_axes(1.4, 1.8)
    centres, radii, _ = fit_clumps.spheres_of("OX", [r0, x1, r1])
    props = fit_clumps.union_properties(centres, radii, axes)
    volume, area = exact_chain(r0, x1, r1)
    assert abs(props["volume"] - volume) <= 4 * props["volume_se"]
    assert abs(props["area"] - area) <= 4 * props["area_se"]
    # the stated errors are the Monte Carlo's size, not a loose bound
    assert props["volume_se"] < 2e-3 * volume and props["area_se"] < 5e-3 * area
    # mirror symmetry: the centre of mass at the origin to the Monte Carlo noise
    assert np.abs(props["com"]).max() < 3e-3


def test_ellipsoid_area_exact_limits():
    assert fit_clumps.ellipsoid_area([0.5, 0.5, 0.5]) == pytest.approx(math.pi)
    a, c = 2.0, 1.0    # prolate spheroid: 2 pi c^2 (1 + a/(c e) asin e)
    e = math.sqrt(1 - c * c / (a * a))
    assert fit_clumps.ellipsoid_area([a, c, c]) == pytest.approx(
        2 * math.pi * c * c * (1 + a / (c * e) * math.asin(e)), rel=1e-12)


def test_layouts_are_mirror_symmetric_and_sized():
    for k, layouts in fit_clumps.LAYOUTS.items():
        for layout in layouts:
            nparam = len(fit_clumps.bounds_of(layout, np.ones(3)))
            centres, radii, _ = fit_clumps.spheres_of(layout, np.linspace(0.1, 0.3, nparam))
            assert len(radii) == k
            for axis in range(3):
                mirrored = centres * np.where(np.arange(3) == axis, -1, 1)
                assert {tuple(np.round(c, 12)) for c in mirrored} == \
                    {tuple(np.round(c, 12)) for c in centres}


def two_spheres(lmp, r1, r2, gap, vz, include, mass):
    lmp.commands_string(f"""
        units lj
        atom_style sphere
        atom_modify map array
        boundary p p f
        comm_modify vel yes
        region box block -3 3 -3 3 0 6
        create_box 2 box
        create_atoms 1 single 0 0 {1 + r1}
        create_atoms 2 single 0 0 {1 + r1 + r1 + r2 - gap}
        set atom 1 diameter {2 * r1}
        set atom 2 diameter {2 * r2}
        set atom * mass {mass}
        velocity all set 0 0 0
        set atom 2 vz {vz}
        variable kn equal {KN}
        variable K equal {K}
        variable kt equal {KT}
        variable mu equal {MU}
        variable mstar equal {mass / 2}
        variable mbody equal {mass}
        pair_style granular
        include {include}
        run 0
        """)


@pytest.fixture(scope="module")
def coefficient_files(tmp_path_factory):
    out = tmp_path_factory.mktemp("coeff")
    clump = {"k": 3, "radii": [0.43, 0.34, 0.34], "orbit": [0, 1, 1]}
    fit_clumps.write_coefficients(str(out / "c.coeff"), str(out / "c.walls"),
                                  str(out / "c.groups"), clump)
    return out


@pytest.mark.parametrize("gap,vz", [(0.01, 0.0), (0.004, -0.3), (0.02, 0.5)])
def test_pair_mapping_gives_our_hertz_law(coefficient_files, gap, vz):
    """Unlike radii (types 1 and 2): F = kn xi^3/2 + K xi^1/2 dxi/dt whatever the radii."""
    lmp = new_lammps()
    two_spheres(lmp, 0.43, 0.34, gap, vz, coefficient_files / "c.coeff", mass=0.53)
    f = lmp.numpy.extract_atom("f")
    expected = KN * gap ** 1.5 + K * math.sqrt(gap) * (-vz)    # dxi/dt = -vz of the upper one
    assert f[1][2] == pytest.approx(expected, rel=1e-10)
    assert f[0][2] == pytest.approx(-expected, rel=1e-10)
    lmp.close()


@pytest.mark.parametrize("radius_type,xi,vz", [(1, 0.006, 0.0), (2, 0.003, -0.4)])
def test_wall_mapping_gives_our_hertz_law(coefficient_files, radius_type, xi, vz):
    r = {1: 0.43, 2: 0.34}[radius_type]
    lmp = new_lammps()
    lmp.commands_string(f"""
        units lj
        atom_style sphere
        boundary p p f
        region box block -3 3 -3 3 0 6
        create_box 2 box
        create_atoms {radius_type} single 0 0 {r - xi}
        set atom 1 diameter {2 * r}
        set atom 1 mass 0.53
        velocity all set 0 0 {vz}
        variable kn equal {KN}
        variable K equal {K}
        variable kt equal {KT}
        variable mu equal {MU}
        variable mbody equal 0.53
        pair_style zero 1.0
        pair_coeff * *
        include {coefficient_files / "c.walls"}
        run 0
        """)
    f = lmp.numpy.extract_atom("f")
    assert f[0][2] == pytest.approx(KN * xi ** 1.5 + K * math.sqrt(xi) * (-vz), rel=1e-10)
    lmp.close()


def test_tiny_clump_pour_comes_to_rest_and_is_measured(tmp_path):
    """Six 3-sphere clumps through in.clump_deposit (fix pour + rigid/small + pair granular,
    a floor per sphere radius) come to rest by its criterion, on the floor, and are measured."""
    import run_clumps
    lmp = new_lammps()
    assert lmp.has_style("fix", "rigid/small"), \
        "LAMMPS was built without RIGID: ./ellipsoid-dep setup builds it with PKG_RIGID"
    lmp.close()
    fit_dir = tmp_path / "fit"
    fit_dir.mkdir()
    clump = fit_clumps.describe("OX", [0.43, 0.41, 0.34], 1.4, 1.8)
    fit_clumps.write_files(str(fit_dir / "clump_k3"), clump)
    n = 6
    dt = run_clumps.deposit_timestep(n, str(tmp_path / "probe"))
    row = run_clumps.run_clump(3, 11, n, 1, str(tmp_path / "k3"), str(fit_dir), dt)
    assert row["at_rest"] == 1
    final = clump_analysis.read_final(str(tmp_path / "k3" / "final.txt"))
    assert len(np.unique(final["mol"])) == n and len(final["radius"]) == 3 * n
    # every sphere type is held by its floor (a missing wall would let it sink through)
    assert (final["x"][:, 2] - final["radius"]).min() > -0.02
    # a clump keeps its shape: its spheres stay at the template's distances
    for body in np.unique(final["mol"]):
        x = final["x"][final["mol"] == body]
        assert np.linalg.norm(x[1] - x[0]) == pytest.approx(0.41, abs=1e-6)
        assert np.linalg.norm(x[2] - x[0]) == pytest.approx(0.41, abs=1e-6)
