"""The angle of repose of examples/repose (repose_angle.py), against heaps of known angle.

- A particle's top: the highest point of a rotated ellipsoid equals the maximum of z over
  points sampled on its surface (an independent computation), for random orientations.
- Ridges of spheres filling the region under h(x) = H - |x| tan(theta), theta 20, 30 and 38
  degrees, left and right flanks: the fitted angle equals theta within 0.01 degrees, also with
  the ridge's centre off the bins' grid and on a ground layer whose height is subtracted.
- A heap too small for its bins is refused with a message, not fitted.
- in.repose builds its rough floor: one sphere per unit cell of the floor, moved randomly by
  at most 0.3 d from the cell's centre; none of the heap's yet.
"""
import math
import os
import sys

import numpy as np
import pytest

from conftest import new_lammps, root_dir

REPOSE = os.path.join(root_dir(), "examples", "repose")
sys.path.insert(0, REPOSE)    # the example's own module, as its scripts import it
import repose_angle    # noqa: E402


def random_quaternions(n, rng):
    q = rng.normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1)[:, None]


def test_particle_tops_match_sampled_surfaces():
    rng = np.random.default_rng(3)
    semi = np.array([[0.7, 0.45, 0.3]] * 20)
    quat = random_quaternions(20, rng)
    tops = repose_angle.particle_tops(np.zeros(20), semi, quat)
    u, v = np.meshgrid(np.linspace(0, np.pi, 400), np.linspace(0, 2 * np.pi, 800))
    body = np.stack([np.sin(u) * np.cos(v), np.sin(u) * np.sin(v), np.cos(u)], -1).reshape(-1, 3)
    for s, (w, i, j, k), top in zip(semi, quat, tops):
        rot = np.array([[1 - 2 * (j*j + k*k), 2 * (i*j - w*k), 2 * (i*k + w*j)],
                        [2 * (i*j + w*k), 1 - 2 * (i*i + k*k), 2 * (j*k - w*i)],
                        [2 * (i*k - w*j), 2 * (j*k + w*i), 1 - 2 * (i*i + j*j)]])
        sampled = ((body * s) @ rot.T)[:, 2].max()
        assert top == pytest.approx(sampled, abs=2e-5)
        assert sampled <= top + 1e-12


def sphere_ridge(theta_deg, centre, ground, height=12.0, spacing=0.05):
    """x and tops of radius-0.5 spheres in columns under the ridge, on the ground: each
    column's highest sphere touches the ridge's surface (columns 0.05 apart, so that a bin's
    highest top lies within 0.05 tan(theta) of the surface at the bin's edge)"""
    slope = math.tan(math.radians(theta_deg))
    half = (height - 1.0) / slope
    x, top = [], []
    for xi in np.arange(centre - half, centre + half, spacing):
        surface = ground + height - abs(xi - centre) * slope
        column = list(np.arange(ground + 1.0, surface, 1.0)) + [surface]
        x += [xi] * len(column)
        top += column
    return np.array(x), np.array(top)


@pytest.mark.parametrize("theta", [20.0, 30.0, 38.0])
@pytest.mark.parametrize("centre, ground", [(0.0, 0.0), (0.37, 1.0)])
def test_ridges_of_known_angle(theta, centre, ground):
    x, top = sphere_ridge(theta, centre, ground)
    centres, height = repose_angle.profile(x, top, ground)
    fit = repose_angle.heap_angle(centres, height)
    assert fit["left"] == pytest.approx(theta, abs=0.01)
    assert fit["right"] == pytest.approx(theta, abs=0.01)
    assert fit["angle"] == pytest.approx(theta, abs=0.01)
    assert min(fit["bins"]) >= 8


def test_small_heap_is_refused():
    x, top = sphere_ridge(30.0, 0.0, 0.0, height=2.0)
    centres, height = repose_angle.profile(x, top)
    with pytest.raises(ValueError, match="too small"):
        repose_angle.heap_angle(centres, height)


def test_rough_floor_of_in_repose():
    lmp = new_lammps()
    lmp.commands_string("variable eta index 1\nvariable zeta index 1\nvariable Lx index 12")
    lmp.file(os.path.join(REPOSE, "in.repose"))
    assert lmp.get_natoms() == 12 * 4
    assert lmp.extract_variable("natoms") == 0.0
    x = lmp.numpy.extract_atom("x")[:48]
    assert lmp.extract_variable("ground") == 1.0
    # each sphere moved off its grid point by at most 0.3 along each axis, not all alike
    grid = np.floor(x) + 0.5
    assert np.all(np.abs(x - grid) <= 0.3 + 1e-12) and np.std(x[:, 2]) > 0.05
    assert abs(np.mean(x[:, 2]) - 0.5) < 0.1
    lmp.close()


def test_table_pools_the_seed_scatter():
    """the cases' errors use the SD pooled over cases; a verdict needs p < 0.0027 under the t
    distribution of the pooled degrees of freedom"""
    def run(eta, mu, angle):
        return {"eta": eta, "zeta": eta, "mu": mu, "angle": angle, "angle_se": 0.1,
                "left": angle, "right": angle, "left_se": 0.1, "right_se": 0.1, "height": 9.0}
    groups = {(1.0, 1.0, 0.5): [run(1.0, 0.5, a) for a in (25.0, 27.0, 26.0)],
              (2.0, 2.0, 0.5): [run(2.0, 0.5, a) for a in (33.0, 35.0)]}
    sd, dof = repose_angle.pooled_sd(groups)
    assert dof == 3 and sd == pytest.approx(math.sqrt((2.0 + 2.0) / 3))
    text = repose_angle.table(groups)
    err = sd * math.sqrt(1 / 3 + 1 / 2)
    assert f"| eta 2 zeta 2 | 0.5 | +8.0 +- {err:.1f} |" in text
    # t = 8.0 / 1.054 = 7.59 on 3 degrees of freedom: p = 0.0047, above 0.0027
    assert text.rstrip().endswith("| 7.6 | 0.0047 | undecided |")
    groups[(2.0, 2.0, 0.5)] = [run(2.0, 0.5, a) for a in (39.0, 41.0)]
    # t = 14.0 / 1.054 = 13.3: p = 0.00092
    assert repose_angle.table(groups).rstrip().endswith("| 13.3 | 0.00092 | decided |")
