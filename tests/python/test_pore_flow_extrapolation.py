"""The flow solve's default (tools/pores/pore_flow_domain.py, tools/pores/pore_flow_fit.py): several voxels,
each the mean over offsets of the grid, extrapolated to a vanishing voxel, a box cut out of a
wider slab, and the progress lines.

- the fit k = k0 + C h^p: p and k0 recovered from three exact values, the fixed-p least
  squares with its standard error, non-monotone values (no fitted p), the values' own errors
  carried into k0's; the plane slit, whose discrete k is exactly of that form, extrapolated
  to Poiseuille's k;
- the grid's offsets: an offset moves the voxels against the particles; on a touching lattice
  (each offset's k differs) a voxel's k is the mean of all offsets, and the same for the
  lattice moved by half a voxel;
- a cut box whose faces are mirror planes of a simple cubic lattice: mirrored along the flow
  and symmetry planes across it, it is the periodic lattice (k of the periodic cell);
- the progress lines name the resolution, the direction, the iteration and the residual.
OpenFOAM must be installed for all but the fit (see test_pore_flow.py).
"""
import json
import math
import os

import numpy as np
import pytest

import pore_flow
import pore_flow_domain
import pores
import zick_homsy
from pore_flow_fit import P_FIXED, extrapolate, fitted_order


def test_extrapolation_brackets_every_order_from_two_up():
    """three exact values of k0 + C h^p at the default voxels: for p = 2, 3 and 6 the limit
    lies between the fixed-p (p = 2) extrapolation and the finest value, k0 is their middle
    and its error covers the limit; at p = 2 the fixed-p fit is exact (no residual); the
    fitted p and k0 at it are reported (exact here)"""
    h = [1 / 13, 1 / 16, 1 / 20]
    for p in (2.0, 3.0, 6.0):
        k = [2.0 + 5.0 * x ** p for x in h]
        e = extrapolate(h, k)
        assert e["p_fixed"] == P_FIXED == 2.0
        assert e["p_fitted"] == pytest.approx(p, rel=1e-6)
        assert e["k0_fitted_p"] == pytest.approx(2.0, rel=1e-9)
        assert e["k_finest"] == k[-1]
        assert e["k0"] == pytest.approx(0.5 * (e["k0_fixed_p"] + k[-1]), rel=1e-15)
        assert min(e["k0_fixed_p"], k[-1]) <= 2.0 + 1e-12 and 2.0 <= max(e["k0_fixed_p"], k[-1])
        assert abs(e["k0"] - 2.0) <= e["error"]
    # an order below 2, outside the bracket's assumption: the fitted p and k0 at it are still
    # exact, and the line in h^2 stays within k0's error
    coarse = [1 / 8, 1 / 12, 1 / 16]
    e = extrapolate(coarse, [2.0 + 5.0 * x ** 1.5 for x in coarse])
    assert e["p_fitted"] == pytest.approx(1.5, rel=1e-9)
    assert e["k0_fitted_p"] == pytest.approx(2.0, rel=1e-12)
    assert e["p_fixed"] == P_FIXED
    assert abs(e["k0_fixed_p"] - e["k0"]) <= e["error"]
    e2 = extrapolate(h[::-1], [2.0 - 3.0 * x ** 2 for x in h[::-1]])
    assert e2["k0_fixed_p"] == pytest.approx(2.0, rel=1e-12)
    assert e2["fixed_p_standard_error"] == pytest.approx(0.0, abs=1e-12)
    assert e2["error"] == pytest.approx(0.5 * abs(e2["k0_fixed_p"] - e2["k_finest"]), abs=1e-12)


def test_extrapolation_of_values_that_do_not_converge_monotonically():
    """differences of both signs: no fitted p; the same bracket between the fixed-p fit and
    the finest value, the error its half-width plus the fit's standard error"""
    h = [1 / 8, 1 / 12, 1 / 16]
    k = [1.2, 0.9, 1.0]
    assert fitted_order(h, k) is None
    e = extrapolate(h, k)
    assert e["p_fitted"] is None and e["k0_fitted_p"] is None
    x = np.array(h) ** P_FIXED
    c, k0 = np.polyfit(x, k, 1)
    resid = np.array(k) - k0 - c * x
    se = math.sqrt(resid @ resid / 1 * np.linalg.inv(np.column_stack([np.ones(3), x]).T
                                                     @ np.column_stack([np.ones(3), x]))[0, 0])
    assert e["k0_fixed_p"] == pytest.approx(k0, rel=1e-12)
    assert e["k0"] == pytest.approx(0.5 * (k0 + 1.0), rel=1e-12)
    assert e["fixed_p_standard_error"] == pytest.approx(se, rel=1e-9)
    assert e["error"] == pytest.approx(0.5 * abs(k0 - 1.0) + se, rel=1e-9)
    with pytest.raises(ValueError, match="three or more different voxel sizes"):
        extrapolate(h[:2], k[:2])


# the default flow voxels of a unit sphere (fractions of its semi-axis 1/2): d/13, d/16, d/20
DEFAULT_VOXELS_PER_D = [round(2 / f, 9) for f in pore_flow_domain.FLOW_VOXEL_FRACTIONS]


def measured(name):
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "results",
                        "flow_verification", name)


def test_defaults_meet_zick_homsy_on_the_measured_lattices():
    """the measured solves of the simple cubic lattices (touching and c = 0.3, aligned and
    shifted by 0.0237 d; results/flow_verification/lattice_offsets.jsonl, four offsets per
    voxel) taken as the tool takes them (two offsets, four unless the two agree) at the
    default voxels d/13, d/16, d/20: k0 of both directions within 5 % of Zick & Homsy and
    within its error of it; k_xx / k_zz within 2 % of 1 at the finest voxel and its k0
    within its error of 1"""
    rows = [json.loads(line) for line in open(measured("lattice_offsets.jsonl"))]
    cases = {}
    for r in rows:
        cases.setdefault((r["c"], r["shift_d"]), {})[r["n"]] = r
    checked = 0
    for (c, shift), res in cases.items():
        if not all(n in res for n in DEFAULT_VOXELS_PER_D):
            continue
        want = res[13.0]["zick_homsy_d2"]
        k_cell, a = zick_homsy.permeability(c)
        assert want == pytest.approx(k_cell / (2 * a) ** 2, rel=1e-5)    # c to 4 digits
        voxels, k, err, ratio, ratio_err = [], {"xx": [], "zz": []}, {"xx": [], "zz": []}, [], []
        for n in DEFAULT_VOXELS_PER_D:
            used = pore_flow_domain.offsets_taken(res[n]["resolution"]["offsets"], ("xx", "zz"))
            agreed = len(used) == 2
            voxels.append(1 / n)
            for key in k:
                k[key].append(np.mean([s[key] for s in used]))
                err[key].append(pore_flow_domain.offset_error([s[key] for s in used], agreed))
            each = [s["xx"] / s["zz"] for s in used]
            ratio.append(np.mean(each))
            ratio_err.append(pore_flow_domain.offset_error(each, agreed))
        for key in k:
            e = extrapolate(voxels, k[key], err[key])
            assert abs(e["k0"] / want - 1) < 0.05, (c, shift, key, e["k0"] / want)
            assert abs(e["k0"] - want) <= e["error"], (c, shift, key)
        assert abs(ratio[-1] - 1) < 0.02, (c, shift, ratio)
        e = extrapolate(voxels, ratio, ratio_err)
        assert abs(e["k0"] - 1) <= e["error"], (c, shift, e["k0"], e["error"])
        checked += 1
    assert checked == 4


def test_defaults_bracket_a_random_pack_fine_solve():
    """k_zz of a 2.5 d cube of a random sphere deposit solved from d/10 to d/32
    (results/flow_verification/cube2.5d_zz.json, the grid's first offset): the default
    voxels' k0 covers, within its error, both the finest solve (d/32) and the extrapolation
    of the three finest (d/20, d/24, d/32) at their fitted p"""
    runs = {r["per_d"]: r["zz"] for r in json.load(open(measured("cube2.5d_zz.json")))}
    e = extrapolate([1 / n for n in DEFAULT_VOXELS_PER_D], [runs[n] for n in DEFAULT_VOXELS_PER_D])
    fine = extrapolate([1 / 20, 1 / 24, 1 / 32], [runs[20.0], runs[24.0], runs[32.0]])
    for reference in (runs[32.0], fine["k0_fitted_p"]):
        assert abs(e["k0"] - reference) <= e["error"], (e["k0"], e["error"], reference)


def test_offset_errors_propagate_to_k0():
    """the values' own standard errors (a mean over the grid's offsets) reach k0 through the
    fixed-p least squares, which is linear in the values: sqrt(sum (dk0/dk_i sigma_i)^2) from
    finite differences, added to the error"""
    h = [1 / 13, 1 / 16, 1 / 20]
    k = [1.2, 1.1, 1.05]
    sigma = [0.03, 0.02, 0.01]
    plain = extrapolate(h, k)
    e = extrapolate(h, k, sigma)
    slopes = []
    for i in range(3):
        bumped = list(k)
        bumped[i] += 1e-6
        slopes.append((extrapolate(h, bumped)["k0_fixed_p"] - plain["k0_fixed_p"]) / 1e-6)
    want = math.sqrt(sum((a * s) ** 2 for a, s in zip(slopes, sigma)))
    assert plain["offset_error"] == 0.0
    assert e["offset_error"] == pytest.approx(want, rel=1e-5)
    assert e["error"] == pytest.approx(plain["error"] + want, rel=1e-9)
    assert e["k0"] == plain["k0"] and e["k_offset_errors"] == sigma


def test_slit_extrapolates_to_poiseuille():
    """a slit of width H between walls at n = 6, 8, 12 cells: the finite-volume k is exactly
    (H^2 / 12)(1 + 2 / n^2), k0 + C h^2, so the extrapolation recovers p = 2 and Poiseuille's
    H^2 / 12 to the solve's residual (per pore area: one solid layer of n + 1 per period)"""
    H = 1.0
    h, k = [], []
    for n in (6, 8, 12):
        solid = np.zeros((2, n + 1, 3), bool)
        solid[:, 0, :] = True
        r = pore_flow.permeability(solid, (H / n,) * 3, ("xx",))
        h.append(H / n)
        k.append(r["xx"] * (n + 1) / n)
    e = extrapolate(h, k)
    # each k to about 1e-5 (the residual), their differences 1 to 3 % of k: p to 1e-3 (1.9973)
    assert e["p_fitted"] == pytest.approx(2.0, rel=3e-3)
    assert e["k0_fixed_p"] == pytest.approx(H * H / 12, rel=1e-4)
    assert abs(e["k0"] - H * H / 12) <= e["error"]


def lattice(n, layers, radius=0.5):
    """a simple cubic lattice of spheres in unit cells, box n x n x layers"""
    c = np.array([[i + 0.5, j + 0.5, k + 0.5]
                  for i in range(n) for j in range(n) for k in range(layers)])
    p = pores.Particles(c, np.tile([1.0, 0, 0, 0], (len(c), 1)), np.full((len(c), 3), radius))
    return p, np.array([[0, n], [0, n], [0, layers]], dtype=float)


def test_cut_box_of_a_lattice_is_the_periodic_lattice():
    """a 2 x 2 x 2 box cut out of a 4 x 4 lattice's slab with its faces on the lattice's
    mirror planes (x, y in [1, 3], z cut to [3, 5] about the slab's middle): mirrored along
    the flow it is the periodic lattice, and the symmetry planes across it are its mirror
    planes, so k_xx = k_yy = k_zz (the cube's symmetry) = k of the periodic cell at the same
    voxels to the symmetry planes' discretisation: two pairs of them across each flow,
    measured -2.4e-3 (one pair: -9e-4, test_pore_flow.py). A box across the deposit's
    periodic edge (x, y in [-0.5, 1.5]) needs the particles' periodic images: its image is
    that of the same box inside (the lattice's period is 1)."""
    p, box = lattice(4, 8, radius=0.4)
    n = 8
    h = 1.0 / n
    k = pore_flow_domain.flow_permeability(p, box, 2.0, 6.0, [h], side=2.0 / 0.8,
                                           offset_count=1)
    assert k["domain"]["kind"] == "box"
    assert k["domain"]["x"] == pytest.approx([1.0, 3.0], abs=1e-12)
    assert k["domain"]["z"] == pytest.approx([3.0, 5.0], abs=1e-12)
    r = k["resolutions"][0]
    assert r["image_xyz"] == [2 * n, 2 * n, 2 * n] and "extrapolation" not in k
    x = (np.arange(n) + 0.5) / n - 0.5
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    cell = pore_flow.permeability(X * X + Y * Y + Z * Z <= 0.16, (h,) * 3, ("xx",),
                                  periodic=(True, True, True))
    d = 0.8
    for key in ("xx", "yy", "zz"):
        assert k[key] * d ** 2 == pytest.approx(cell["xx"], rel=3e-3)
        assert k[key] == pytest.approx(k["xx"], rel=1e-6)
        assert r["cells"][key] == 2 * 8 * cell["cells"]["xx"]
    # across the deposit's periodic edge: the images fill the box as the lattice does
    domain = pore_flow_domain.flow_domain(box, 2.0, 6.0, d, 2.5, at=(0.5, 0.5))
    solid, _, filled = pore_flow_domain.flow_image(p, box, domain, h, lambda m: None)
    inner = pore_flow_domain.flow_domain(box, 2.0, 6.0, d, 2.5, at=(1.5, 1.5))
    same, _, _ = pore_flow_domain.flow_image(p, box, inner, h, lambda m: None)
    assert np.array_equal(solid, same) and filled == 0.0
    # the domain's own medium: 8 whole spheres of radius 0.4 in the 2 x 2 x 2 box, and the
    # same (2 x 2 periods) from the parts of spheres and images that a box across the edge
    # cuts, its faces 0.05 from their centres
    porosity = 1 - 8 * 4 / 3 * math.pi * 0.4 ** 3 / 8
    s_v = 8 * 4 * math.pi * 0.4 ** 2 / 8
    kc = porosity ** 3 / (5 * s_v ** 2) / d ** 2
    across = pore_flow_domain.flow_domain(box, 2.0, 6.0, d, 2.5, at=(0.55, 0.45))
    for medium in (k["medium"], pore_flow_domain.domain_medium(p, box, across, d)):
        assert medium["porosity"] == pytest.approx(porosity, rel=1e-4)
        assert medium["specific_surface"] == pytest.approx(s_v, rel=1e-4)
        assert medium["kozeny_carman"] == pytest.approx(kc, rel=3e-4)
    assert k["ratio_to_kozeny_carman"]["zz"] == pytest.approx(k["zz"] / k["medium"][
        "kozeny_carman"], rel=1e-12)


def touching_lattice(shift):
    """unit spheres touching on a simple cubic lattice, 2 x 2 cells wide (narrower than the
    default box: the flow domain is the whole periodic slab), moved by shift in x and y"""
    c = np.array([[i + 0.5 + shift, j + 0.5 + shift, k + 0.5]
                  for i in range(2) for j in range(2) for k in range(5)])
    p = pores.Particles(c, np.tile([1.0, 0, 0, 0], (len(c), 1)), np.full((len(c), 3), 0.5))
    return p, np.array([[0, 2], [0, 2], [0, 5]], dtype=float)


def test_grid_offsets_move_the_voxels_against_the_particles():
    """the flow image at the offset (1/2, 1/2) of a voxel is the image of the lattice moved by
    -1/2 voxel at no offset; and it differs from the image at no offset: the lattice's
    contacts fall on voxel centres there (open between them) and on voxel faces here"""
    h = 1.0 / 6
    p, box = touching_lattice(0.0)
    domain = pore_flow_domain.flow_domain(box, 2.0, 3.0, 1.0)
    assert domain.describe(1.0)["kind"] == "slab"
    half, _, _ = pore_flow_domain.flow_image(p, box, domain, h, lambda m: None, (0.5, 0.5))
    q, _ = touching_lattice(-0.5 * h)
    moved, _, _ = pore_flow_domain.flow_image(q, box, domain, h, lambda m: None)
    corner, _, _ = pore_flow_domain.flow_image(p, box, domain, h, lambda m: None)
    assert np.array_equal(half, moved)
    assert not np.array_equal(half, corner)
    assert pore_flow_domain.grid_offsets(2) == pore_flow_domain.OFFSETS[:2]
    with pytest.raises(ValueError, match="--flow-offsets 3: needs 1, 2 or 4"):
        pore_flow_domain.grid_offsets(3)


def test_a_voxel_is_the_mean_over_the_grid_offsets():
    """at one coarse voxel (d/6, k_xx only) on the touching lattice each offset's k differs by
    a factor of up to 2.5 (the contacts open or closed), so all 4 offsets are solved; the
    voxel's k is their mean with its standard error; and the lattice moved by half a voxel
    gives the same mean (the offsets are a set closed under that move)"""
    h = 1.0 / 6
    means = []
    for shift in (0.0, 0.5 * h):
        p, box = touching_lattice(shift)
        k = pore_flow_domain.flow_permeability(p, box, 2.0, 3.0, [h], directions=("xx",))
        (r,) = k["resolutions"]
        each = [s["xx"] for s in r["offsets"]]
        assert [s["offset"] for s in r["offsets"]] == [list(o) for o in
                                                        pore_flow_domain.OFFSETS]
        assert max(each) > 1.5 * min(each)
        assert r["xx"] == pytest.approx(np.mean(each), rel=1e-12) == k["xx"]
        assert r["xx_offset_error"] == pytest.approx(np.std(each, ddof=1) / 2, rel=1e-9)
        means.append(r["xx"])
    assert means[1] == pytest.approx(means[0], rel=1e-5)


def test_kept_solves_resume_without_solving_again(tmp_path, monkeypatch):
    """with a folder for the solves (the lines' runs stop and resume across sessions) each
    offset's solve is kept as it finishes; a rerun takes every kept solve from there and
    solves only what is missing, with the same result"""
    h = 1.0 / 6
    p, box = touching_lattice(0.0)
    first = pore_flow_domain.flow_permeability(p, box, 2.0, 3.0, [h], directions=("xx",),
                                               offset_count=2, solved=str(tmp_path))
    kept = sorted(f.name for f in tmp_path.iterdir())
    assert kept == ["d6_offset1_xx.json", "d6_offset2_xx.json"]
    solve = pore_flow.permeability
    calls = []

    def counted(*args, **kwargs):
        calls.append(args[2])
        return solve(*args, **kwargs)
    monkeypatch.setattr(pore_flow, "permeability", counted)
    again = pore_flow_domain.flow_permeability(p, box, 2.0, 3.0, [h], directions=("xx",),
                                               offset_count=2, solved=str(tmp_path))
    assert calls == [] and again == first
    (tmp_path / "d6_offset2_xx.json").unlink()
    third = pore_flow_domain.flow_permeability(p, box, 2.0, 3.0, [h], directions=("xx",),
                                               offset_count=2, solved=str(tmp_path))
    assert calls == [("xx",)]
    assert third["xx"] == pytest.approx(first["xx"], rel=1e-6)


def test_progress_names_resolution_direction_iteration_and_residual(monkeypatch):
    """every iteration's line (PROGRESS_SECONDS 0): flow, the label, the direction, the
    iteration and the driven component's residual, which ends below the tolerance"""
    monkeypatch.setattr(pore_flow, "PROGRESS_SECONDS", 0.0)
    lines = []
    solid = np.zeros((2, 7, 3), bool)
    solid[:, 0, :] = True
    pore_flow.permeability(solid, (0.1,) * 3, ("xx",), lines.append, label="d/8")
    iterations = [ln for ln in lines if ln.startswith("flow d/8 xx: iteration ")]
    assert len(iterations) >= 5
    numbers = [int(ln.split()[4].rstrip(",")) for ln in iterations]
    assert numbers == sorted(numbers) and numbers[0] == 1
    residual = [float(ln.split("residual Ux ")[1].split()[0]) for ln in iterations]
    assert residual[-1] <= pore_flow.TOLERANCE < residual[0]
    assert any(ln.startswith("flow d/8 xx: simpleFoam on 36 cells") for ln in lines)
    assert any(ln.startswith("flow d/8 xx: k = ") for ln in lines)
