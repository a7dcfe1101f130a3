"""The flow solve of tools/pores/pore_flow.py (OpenFOAM's simpleFoam on the voxel image) against
exact and published results, on meshes small enough for seconds.

- plane Poiseuille flow in a slit of n cells: the finite-volume solution is known exactly
  (walls at half a cell from the wall-cell centres), k = (H^2 / 12)(1 + 2 / n^2), which the
  solve must reproduce to its residual; that is k = H^2 / 12 within 2 / n^2. Along x (the
  slab's planes as symmetry planes) and along z (the mirrored slab) for walls normal to y,
  and a half slit against a symmetry plane (walls normal to z);
- Stokes flow through a simple cubic array of spheres against Zick & Homsy (1982), Table 2;
- 2 ranks against 1; a write cut short by the end of the solve is not read;
- the whole tool (pores.py --flow) on a simple cubic lattice's run folder: cubic symmetry
  k_xx = k_yy = k_zz, units of d^2, Zick & Homsy's value at the touching fraction.
OpenFOAM must be installed (`./ellipsoid-dep pores DIR --flow` installs Debian's openfoam);
without it every test here fails with that message.
"""
import json
import math
import os

import numpy as np
import pytest

import pore_flow
import pores
from zick_homsy import permeability as zick_homsy_permeability

def discrete_poiseuille(n, h):
    """k of a slit of n cells of width h from the finite-volume equations (exact): the profile
    is g / (2 nu) (y (H - y) + h^2 / 4) at the cell centres, whose mean is
    g / (2 nu) (H^2 / 6 + h^2 / 3)"""
    H = n * h
    return H * H / 12.0 * (1.0 + 2.0 / n ** 2)


def test_openfoam_is_installed():
    pore_flow.require_openfoam()    # the message names the set-up's apt package


@pytest.mark.parametrize("n", [6, 10])
def test_slit_poiseuille(n):
    """walls normal to y (one solid layer of n + 1 per period), a slab 3 cells high: along x
    the slab's planes are symmetry planes, along z the slab is mirrored; the geometry does
    not depend on z, so both give the slit's k times its porosity n / (n + 1)"""
    h = 0.1
    solid = np.zeros((2, n + 1, 3), bool)
    solid[:, 0, :] = True
    k = pore_flow.permeability(solid, (h, h, h), ("xx", "zz"))
    want = discrete_poiseuille(n, h) * n / (n + 1)
    exact = (n * h) ** 2 / 12.0 * n / (n + 1)
    for key in ("xx", "zz"):
        assert k[key] == pytest.approx(want, rel=1e-4)
        assert abs(k[key] / exact - 1) <= 2.0 / n ** 2 + 1e-4
        assert k["residuals"][key]["U" + key[0]] <= pore_flow.TOLERANCE
    assert k["cells"] == {"xx": 2 * n * 3, "zz": 2 * n * 6}


def test_half_slit_against_the_symmetry_plane():
    """a solid bottom layer and n pore layers up to the slab's top plane, a symmetry plane:
    the upper half of a slit of 2 n cells"""
    n, h = 8, 0.05
    solid = np.zeros((2, 3, n + 1), bool)
    solid[:, :, 0] = True
    k = pore_flow.permeability(solid, (h, h, h), ("xx", "yy"))
    want = discrete_poiseuille(2 * n, h) * n / (n + 1)
    assert k["xx"] == pytest.approx(want, rel=1e-4)
    assert k["yy"] == pytest.approx(want, rel=1e-4)


def cubic_cell(c, n):
    """one cell of the simple cubic array, n voxels per edge, the sphere in the middle"""
    _, a = zick_homsy_permeability(c)
    x = (np.arange(n) + 0.5) / n - 0.5
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    return X * X + Y * Y + Z * Z <= a * a


@pytest.mark.parametrize("c", [0.125, 0.216, 0.343, 0.45])
def test_simple_cubic_array_zick_homsy(c):
    """the periodic cell at 16 voxels per edge (sphere diameters 10 to 15 voxels): the voxel
    sphere's volume differs from the sphere's by up to 6 %, so the reference is Zick & Homsy at
    the voxel image's solid fraction; within 4 %, the stair-step error at this resolution
    (doc/howto_pores.md, "Verification": -1.1, 0.0, +2.1, +3.5 %; the touching fraction
    0.5236 is left out: its voxelised contacts open and close with the resolution)"""
    n = 16
    solid = cubic_cell(c, n)
    k = pore_flow.permeability(solid, (1.0 / n,) * 3, ("xx",), periodic=(True, True, True))
    want, _ = zick_homsy_permeability(float(solid.mean()))
    assert abs(k["xx"] / want - 1) < 0.04


def test_two_ranks_give_the_serial_answer(monkeypatch):
    """above PARALLEL_CELLS the solve runs on 2 ranks (decomposePar, mpirun): the same k"""
    solid = np.tile(cubic_cell(0.343, 8), (2, 1, 1))
    serial = pore_flow.permeability(solid, (1 / 8,) * 3, ("xx",), periodic=(True, True, True))
    monkeypatch.setattr(pore_flow, "PARALLEL_CELLS", 100)
    parallel = pore_flow.permeability(solid, (1 / 8,) * 3, ("xx",), periodic=(True, True, True))
    assert serial["ranks"]["xx"] == 1 and parallel["ranks"]["xx"] == 2
    assert parallel["xx"] == pytest.approx(serial["xx"], rel=1e-5)


def write_run_folder(folder, centres, semi, box, zlo, zhi):
    """a run folder as the runner writes it: deposit.dump (its columns) and packing.dat"""
    os.makedirs(folder, exist_ok=True)
    n = len(centres)
    with open(os.path.join(folder, "deposit.dump"), "w") as f:
        f.write("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n%d\nITEM: BOX BOUNDS pp pp ff\n" % n)
        for lo, hi in box:
            f.write("%g %g\n" % (lo, hi))
        f.write("ITEM: ATOMS id type x y z quatw quati quatj quatk semi_a_x semi_a_y semi_a_z\n")
        for i, (c, s) in enumerate(zip(centres, semi)):
            f.write("%d 1 %r %r %r 1 0 0 0 %r %r %r\n" % ((i + 1,) + tuple(c) + tuple(s)))
    with open(os.path.join(folder, "packing.dat"), "w") as f:
        f.write("# test\nN %d\neta 1\nzeta 1\nzlo %r\nzhi %r\n" % (n, zlo, zhi))


def cubic_lattice_folder(folder, n=2, layers=8):
    centres = [(i + 0.5, j + 0.5, k + 0.5) for i in range(n) for j in range(n)
               for k in range(layers)]
    write_run_folder(folder, centres, [(0.5, 0.5, 0.5)] * len(centres),
                     [(0, n), (0, n), (0, layers)], 2.0, 6.0)


def test_tool_flow_on_the_cubic_lattice(tmp_path):
    """pores.py --flow at one flow voxel (8 per diameter) on touching unit spheres in a
    slab of 4 whole periods, whose planes are mirror planes of the lattice (and of its voxel
    image): the mirrored image for z is then the periodic lattice, so k_zz equals k of the
    periodic unit cell at the same voxels; the symmetry planes for x and y are OpenFOAM's
    symmetryPlane patches, whose discretisation is not the exact mirror: measured -9.0e-4
    (k_xx = k_yy by the lattice's symmetry); in d^2 (d = 1). The box is narrower than the
    default cut box: the flow domain is the slab. One offset: the grid on the slab's corner, as
    the cell's."""
    folder = str(tmp_path / "lattice")
    cubic_lattice_folder(folder)
    n = 8
    pores.main([folder, "--flow", "--flow-voxel", str(1.0 / n), "--flow-offsets", "1",
                "--quiet"])
    with open(os.path.join(folder, "pores.json")) as f:
        k = json.load(f)["permeability_flow"]
    assert k["units"] == "d^2" and k["d"] == pytest.approx(1.0)
    assert k["domain"]["kind"] == "slab" and "extrapolation" not in k
    (r,) = k["resolutions"]
    assert r["voxels_per_d"] == pytest.approx(n)
    x = (np.arange(int(n)) + 0.5) / n - 0.5
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    cell = pore_flow.permeability(X * X + Y * Y + Z * Z <= 0.25, (1 / n,) * 3, ("xx",),
                                  periodic=(True, True, True))
    assert k["zz"] == r["zz"] == pytest.approx(cell["xx"], rel=1e-5)
    assert k["xx"] == pytest.approx(cell["xx"], rel=2e-3)
    assert k["yy"] == pytest.approx(k["xx"], rel=1e-6)
    assert r["cells"]["zz"] == 2 * r["cells"]["xx"] == 2 * 16 * cell["cells"]["xx"]
    assert r["filled_pore_fraction"] == 0.0
    # k / k_KC of the flow domain itself, here the slab: porosity 1 - pi/6, S_v = pi / d
    porosity = 1 - math.pi / 6
    assert k["medium"]["porosity"] == pytest.approx(porosity, rel=1e-12)
    assert k["medium"]["specific_surface"] == pytest.approx(math.pi, rel=1e-12)
    assert k["ratio_to_kozeny_carman"]["zz"] == pytest.approx(
        k["zz"] * 5 * math.pi ** 2 / porosity ** 3, rel=1e-12)
    for key, res in r["residuals"].items():
        assert res["U" + key[0]] <= pore_flow.TOLERANCE


def run_tool(args, capsys):
    with pytest.raises(SystemExit) as e:
        pores.main(args)
    return e.value.code, capsys.readouterr().err


def test_bad_input(tmp_path, capsys):
    """a clear message and exit 2, no traceback: a folder without a deposit, a voxel too large
    for the particles, a slab without a pore path from bottom to top"""
    empty = tmp_path / "empty"
    empty.mkdir()
    code, err = run_tool([str(empty), "--quiet"], capsys)
    assert code == 2 and "no deposit.dump" in err and "Traceback" not in err
    code, err = run_tool([str(tmp_path / "missing"), "--quiet"], capsys)
    assert code == 2 and "no such folder" in err
    lattice = str(tmp_path / "lattice")
    cubic_lattice_folder(lattice)
    code, err = run_tool([lattice, "--quiet", "--voxel", "0.3"], capsys)
    assert code == 2 and "voxel 0.3 too large" in err
    code, err = run_tool([lattice, "--quiet", "--voxel-fraction", "0.9"], capsys)
    assert code == 2 and "--voxel-fraction 0.9: needs 0 < fraction <= 0.5" in err
    code, err = run_tool([lattice, "--quiet", "--flow", "--flow-voxel", "0.6"], capsys)
    assert code == 2 and "flow voxel 0.6" in err
    code, err = run_tool([lattice, "--quiet", "--flow", "--flow-box", "-1"], capsys)
    assert code == 2 and "--flow-box -1: needs L >= 0" in err
    code, err = run_tool([lattice, "--quiet", "--flow", "--flow-box-at", "1"], capsys)
    assert code == 2 and "--flow-box-at 1: needs X,Y" in err
    code, err = run_tool([lattice, "--quiet", "--flow", "--flow-offsets", "3"], capsys)
    assert code == 2 and "--flow-offsets 3: needs 1, 2 or 4" in err
    # a closed layer: overlapping spheres of radius 0.75 on the lattice at z = 4
    closed = str(tmp_path / "closed")
    centres = [(i + 0.5, j + 0.5, k + 0.5) for i in range(2) for j in range(2) for k in range(8)]
    semi = [(0.75,) * 3 if c[2] == 4.5 else (0.5,) * 3 for c in centres]
    write_run_folder(closed, centres, semi, [(0, 2), (0, 2), (0, 8)], 2.0, 6.0)
    code, err = run_tool([closed, "--quiet", "--flow"], capsys)
    assert code == 2 and "no connected pore path" in err


def test_a_write_cut_short_is_not_read(tmp_path):
    """simpleFoam can be ended while it writes a later time than the converged one (its output
    reaches the monitor through a pipe, late): the newest time whose U every rank wrote to its
    trailer line is read, never one older than the converged write"""
    trailer = "\n\n// " + "*" * 73 + " //\n"

    def write_u(folder, time, whole):
        os.makedirs(folder / time, exist_ok=True)
        (folder / time / "U").write_text("internalField nonuniform List<vector> 1\n((1 0 0))\n;"
                                         + (trailer if whole else "\n"))

    case = tmp_path / "case"
    write_u(case, "0", True)
    write_u(case, "250", True)
    write_u(case, "260", False)
    assert pore_flow.newest_complete_time([str(case)], 250) == "250"
    with pytest.raises(pore_flow.FlowError, match="older than the converged"):
        pore_flow.newest_complete_time([str(case)], 255)
    ranks = [tmp_path / "processor0", tmp_path / "processor1"]
    for rank in ranks:
        write_u(rank, "250", True)
        write_u(rank, "260", True)
    write_u(ranks[1], "260", False)    # one rank cut short
    assert pore_flow.newest_complete_time(list(map(str, ranks)), 250) == "250"
    write_u(ranks[1], "260", True)
    assert pore_flow.newest_complete_time(list(map(str, ranks)), 250) == "260"
    cut = tmp_path / "cut"
    write_u(cut, "10", False)
    with pytest.raises(pore_flow.FlowError, match="no complete result"):
        pore_flow.newest_complete_time([str(cut)], None)
