"""The spheres' contact normals per slab (tools/study/study_sphere_slabs.py) on rows made by hand,
computed here independently: the seeds' counts pooled per bin against the isotropic
expectation (deviation, Poisson error, Pearson's chi^2), the seeds' consistency and the Birge
scaling when they scatter beyond counting."""
import math

import numpy as np
import pytest
from scipy import stats

from study_sphere_slabs import sphere_slabs_summary


def rows(law, slab, seed, deviations, contacts):
    return [{"law": law, "seed": seed, "slab": slab, "theta": "%.4f" % (0.1 + k),
             "deviation": "%g" % d, "contacts": "%g" % c}
            for k, (d, c) in enumerate(zip(deviations, contacts))]


def test_pooled_counts_poisson_errors_and_pearson_chi2():
    # two seeds that agree exactly: expected 100, 400, 900 each, counts 20 % high, 10 % low
    dev = [0.2, -0.1, 0.0]
    data = (rows("viscous", "low", 1, dev, [120, 360, 900])
            + rows("viscous", "low", 2, dev, [120, 360, 900]))
    low = sphere_slabs_summary(data)[("viscous", "low")]
    assert low["seeds"] == [1, 2] and low["theta"] == pytest.approx([0.1, 1.1, 2.1])
    assert low["deviation"] == pytest.approx(dev)
    assert low["se"] == pytest.approx([math.sqrt(240) / 200, math.sqrt(720) / 800,
                                       math.sqrt(1800) / 1800])
    chi2 = 40 ** 2 / 200 + 80 ** 2 / 800
    assert low["chi2"] == pytest.approx(chi2) and low["dof"] == 2
    assert low["p"] == pytest.approx(stats.chi2.sf(chi2, 2))
    assert low["seeds_chi2"] == pytest.approx(0.0) and low["seeds_dof"] == 2


def test_seeds_beyond_counting_scale_the_errors():
    # seed 1 40 % high in the first bin, seed 2 exact: expected 100 in every bin
    data = (rows("coulomb", "high", 4, [0.4, -0.2, -0.2], [140, 80, 80])
            + rows("coulomb", "high", 5, [0.0, 0.0, 0.0], [100, 100, 100]))
    s = sphere_slabs_summary(data)[("coulomb", "high")]
    n, e = np.array([[140, 80, 80], [100, 100, 100]]), np.full((2, 3), 100.0)
    mean = n.sum(0) / e.sum(0) - 1
    fitted = (1 + mean) * e
    seeds_chi2 = float(np.sum((n - fitted) ** 2 / fitted))
    birge = math.sqrt(seeds_chi2 / 2)
    assert birge > 1 and s["birge"] == pytest.approx(birge)
    assert s["se"] == pytest.approx((birge * np.sqrt(n.sum(0)) / e.sum(0)).tolist())
    chi2 = float(np.sum((n.sum(0) - e.sum(0)) ** 2 / e.sum(0)))
    assert s["chi2"] == pytest.approx(chi2 / birge ** 2)
    one = sphere_slabs_summary(rows("viscous", "high", 1, [0.0] * 3, [100] * 3))
    flat = one[("viscous", "high")]
    assert flat["birge"] is None    # one seed: no consistency to test
    # counts equal to the isotropic expectation: chi^2 0, p 1, Poisson errors sqrt(100) / 100
    assert flat["chi2"] == 0.0 and flat["p"] == 1.0
    assert flat["se"] == pytest.approx([0.1] * 3)
    # laws and slabs stay apart
    both = sphere_slabs_summary(data + rows("viscous", "high", 1, [0.0] * 3, [100] * 3))
    assert set(both) == {("coulomb", "high"), ("viscous", "high")}
