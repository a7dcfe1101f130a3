"""The flow solve at its defaults (three voxels, extrapolated; tools/pore_flow_domain.py) on
simple cubic lattices of spheres against Zick & Homsy (1982, J. Fluid Mech. 115, 13, Table 2;
test_pore_flow.py): a slab of 2 x 2 x 1 cells, whose planes are mirror planes of the lattice,
flow along x (periodic, the slab's planes symmetry planes) and z (the mirrored slab).

- touching spheres with the voxels aligned to the cells (the contact planes on voxel faces at
  every voxel): the values do not converge monotonically (-0.5, -7.6, -4.0 % along z at d/10,
  d/13, d/16) and Zick & Homsy lie within the reported error (k0 9 % low, its error 11 %);
  isotropic within 2 % at each voxel (measured 1.6e-3 on a slab of 2 cells: the symmetry
  planes against the mirror).
The lattices' other cases are measurements in doc/howto_pores.md ("Verification at the
defaults"), not tests: a lattice repeats one contact, so its voxel error is coherent and k0
lands 3 to 9 % from Zick & Homsy depending on how the voxels fit the cells (c = 0.3: +3.0 %
on a slab 2 cells high, +7.1 % on this one, -2.6 % and -3.4 % shifted by 0.0237 d; touching
and shifted: +5.7 % and -6.1 %), which no test could state without choosing the case that
passes.
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
