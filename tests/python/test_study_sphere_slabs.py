"""The spheres' contact normals per slab (tools/study/study_sphere_slabs.py): the seeds' mean
deviation per bin, its counting error 1 / sqrt(contacts over the seeds) and chi^2 against
isotropy, on rows made by hand and computed here independently."""
import math

import pytest
from scipy import stats

from study_sphere_slabs import sphere_slabs_summary


def rows(law, slab, seed, deviations, contacts):
    return [{"law": law, "seed": seed, "slab": slab, "theta": "%.4f" % (0.1 + k),
             "deviation": "%g" % d, "contacts": "%g" % c}
            for k, (d, c) in enumerate(zip(deviations, contacts))]


def test_mean_counting_error_and_chi2_per_law_and_slab():
    data = (rows("viscous", "low", 1, [0.2, -0.1, -0.1], [100, 400, 900])
            + rows("viscous", "low", 2, [0.4, -0.3, -0.1], [300, 500, 700])
            + rows("viscous", "high", 1, [0.0, 0.0, 0.0], [400, 400, 400])
            + rows("coulomb", "low", 4, [0.1, 0.0, -0.05], [400, 400, 400]))
    s = sphere_slabs_summary(data)
    assert set(s) == {("viscous", "low"), ("viscous", "high"), ("coulomb", "low")}
    low = s[("viscous", "low")]
    assert low["seeds"] == [1, 2] and low["theta"] == pytest.approx([0.1, 1.1, 2.1])
    assert low["deviation"] == pytest.approx([0.3, -0.2, -0.1])
    assert low["se"] == pytest.approx([1 / 20, 1 / 30, 1 / 40])
    chi2 = (0.3 * 20) ** 2 + (0.2 * 30) ** 2 + (0.1 * 40) ** 2
    assert low["chi2"] == pytest.approx(chi2) and low["dof"] == 2
    assert low["p"] == pytest.approx(stats.chi2.sf(chi2, 2))
    assert s[("viscous", "high")]["chi2"] == 0.0 and s[("viscous", "high")]["p"] == 1.0
    assert s[("coulomb", "low")]["se"][0] == pytest.approx(1 / math.sqrt(400))
