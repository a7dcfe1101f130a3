"""The flow solve at its defaults (three voxels, extrapolated; tools/pore_flow_domain.py) on
simple cubic lattices of spheres against Zick & Homsy (1982, J. Fluid Mech. 115, 13, Table 2;
test_pore_flow.py): a slab of 2 x 2 x 1 cells, whose planes are mirror planes of the lattice,
flow along x (periodic, the slab's planes symmetry planes) and z (the mirrored slab).

- touching spheres with the voxels aligned to the cells (the contact planes on voxel faces at
  every voxel): the values do not converge monotonically (-0.5, -7.6, -4.0 % along z at d/10,
  d/13, d/16) and Zick & Homsy lie within the reported error (k0 9 % low, its error 11 %);
  isotropic at each voxel (measured 1.6e-3: the symmetry planes against the mirror);
- c = 0.3 (the cells are 12, 15.5 and 19.5 voxels: the voxels fit them differently at each
  size), as it is and shifted in x and y by 0.0237 d (a different fraction of each voxel):
  within 5 % of Zick & Homsy (measured +3.0 % unshifted; -2.6 % along x, -3.4 % along z
  shifted), isotropic within 2 % at the finest voxel and in k0 (measured 1.0001 and 1.0003
  unshifted, 1.007 and 1.008 shifted; the shifted lattice's extrapolated anisotropy, from
  0.975, 1.002, 1.007, is 1.021 +- 0.017).
Touching spheres shifted that way are not a test: their values converge to 5.7 % above
(x) and 6.1 % below (z) Zick & Homsy, 8 % apart at d/16 (doc/howto_pores.md).
"""
import math

import numpy as np
import pytest

import pore_flow_domain
import pores
from test_pore_flow import zick_homsy_permeability


def lattice_k(c, shift=0.0):
    """the tool's k (d^2) of a lattice at solid fraction c, unit cells, x and y shifted by
    shift; and Zick & Homsy's k in d^2 (ln K interpolated in c at 0.3, between 0.216 and
    0.343: K = 12.0)"""
    want, a = zick_homsy_permeability(c)
    if c > 0.5:
        a = 0.5    # touching (0.5236 is pi/6 to 4 digits)
    centres = np.array([[i + 0.5 + shift, j + 0.5 + shift, k + 0.5]
                        for i in range(2) for j in range(2) for k in range(5)])
    p = pores.Particles(centres, np.tile([1.0, 0, 0, 0], (len(centres), 1)),
                        np.full((len(centres), 3), a))
    box = np.array([[0, 2], [0, 2], [0, 5]], float)
    k = pore_flow_domain.flow_permeability(p, box, 2.0, 3.0, directions=("xx", "zz"))
    return k, want / (2 * a) ** 2


def test_touching_lattice_aligned_within_the_error():
    k, want = lattice_k(math.pi / 6)
    assert [r["voxels_per_d"] for r in k["resolutions"]] == pytest.approx([10, 13, 16])
    assert k["domain"]["kind"] == "slab"
    for key in ("xx", "zz"):
        assert abs(k[key] - want) <= k[key + "_error"]
    for r in k["resolutions"]:    # symmetry planes against the mirror, at each voxel
        assert r["anisotropy_xx_zz"] == pytest.approx(1.0, abs=0.02)


@pytest.mark.parametrize("shift", [0.0, 0.0237])
def test_lattice_at_c_0_3_within_five_percent_and_isotropic(shift):
    k, want = lattice_k(0.3, shift)
    for key in ("xx", "zz"):
        assert abs(k[key] / want - 1) < 0.05
        assert abs(k[key] - want) <= k[key + "_error"]
    assert abs(k["xx"] / k["zz"] - 1) < 0.02
    assert abs(k["resolutions"][-1]["anisotropy_xx_zz"] - 1) < 0.02
