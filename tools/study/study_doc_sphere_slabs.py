"""doc/study.md's spheres' contact normals near the floor and above it (tools/study/study_doc.py),
from results/study/sphere_slabs.csv (study_sphere_slabs.py): per law and slab the seeds' mean
deviation from isotropy in each bin with its Poisson error (scaled where the seeds scatter
beyond counting), the seeds' consistency, and Pearson's chi^2 against isotropy."""
import csv
import os

from scipy import stats

from study_doc_claims import table
from study_sphere_slabs import SLABS, sphere_slabs_summary
from study_stats import CHANCE_P


def seeds_cell(m):
    if m["birge"] is None:
        return "one seed: not tested"
    return "chi^2 %.1f on %d dof (p %.2g)%s" % (
        m["seeds_chi2"], m["seeds_dof"], stats.chi2.sf(m["seeds_chi2"], m["seeds_dof"]),
        "; errors x %.2f" % m["birge"] if m["birge"] > 1 else "")


def verdict(m):
    """isotropy rejected at 3 sigma (p < CHANCE_P) or not; one seed cannot tell its own
    scatter"""
    if m["birge"] is None:
        return "undecided (one seed)"
    return "not isotropic" if m["p"] < CHANCE_P else "undecided"


def sphere_slabs_block(results):
    path = os.path.join(results, "sphere_slabs.csv")
    if not os.path.exists(path):
        return "Not measured yet."
    with open(path) as f:
        summary = sphere_slabs_summary(list(csv.DictReader(f)))
    keys = sorted(summary, key=lambda k: (k[0], list(SLABS).index(k[1])))
    theta = summary[keys[0]]["theta"]
    rows = []
    for law, slab in keys:
        m = summary[(law, slab)]
        rows.append([law, "%s, z %g-%g d" % ((slab,) + SLABS[slab]),
                     ",".join("%d" % seed for seed in m["seeds"])]
                    + ["%+.0f +- %.0f" % (100 * d, 100 * e) for d, e in
                       zip(m["deviation"], m["se"])]
                    + [seeds_cell(m), "%.0f (%d dof), p %.0e: %s"
                       % (m["chi2"], m["dof"], m["p"], verdict(m))])
    ratio = "; ".join("%s %.1f" % (law, summary[(law, "low")]["chi2"]
                                   / summary[(law, "high")]["chi2"])
                      for law in sorted({k[0] for k in keys})
                      if (law, "low") in summary and (law, "high") in summary)
    return ("chi^2 against isotropy near the floor over chi^2 above it: %s.\n\n" % ratio
            + table(["law", "slab", "seeds"] + ["%.2f (%%)" % t for t in theta]
                    + ["seeds against each other", "chi^2 against isotropy"], rows))
