"""doc/study.md's spheres' contact normals near the floor and above it (tools/study/study_doc.py),
from results/study/sphere_slabs.csv (study_sphere_slabs.py): per law and slab the seeds' mean
deviation from isotropy in each bin with its counting error, and chi^2 against isotropy."""
import csv
import os

from study_doc_claims import table
from study_sphere_slabs import SLABS, sphere_slabs_summary


def sphere_slabs_block(results):
    path = os.path.join(results, "sphere_slabs.csv")
    if not os.path.exists(path):
        return "Not measured yet."
    with open(path) as f:
        summary = sphere_slabs_summary(list(csv.DictReader(f)))
    keys = sorted(summary, key=lambda k: (k[0], list(SLABS).index(k[1])))
    theta = summary[keys[0]]["theta"]
    rows = [[law, "%s, z %g-%g d" % ((slab,) + SLABS[slab]),
             ",".join("%d" % s for s in summary[(law, slab)]["seeds"])]
            + ["%+.0f +- %.0f" % (100 * d, 100 * e) for d, e in
               zip(summary[(law, slab)]["deviation"], summary[(law, slab)]["se"])]
            + ["%.0f (%d dof), p %.0e" % (summary[(law, slab)]["chi2"],
                                          summary[(law, slab)]["dof"], summary[(law, slab)]["p"])]
            for law, slab in keys]
    ratio = "; ".join("%s %.1f" % (law, summary[(law, "low")]["chi2"]
                                   / summary[(law, "high")]["chi2"])
                      for law in sorted({k[0] for k in keys})
                      if (law, "low") in summary and (law, "high") in summary)
    return ("chi^2 against isotropy near the floor over chi^2 above it: %s.\n\n" % ratio
            + table(["law", "slab", "seeds"] + ["%.2f (%%)" % t for t in theta]
                    + ["chi^2 (counting errors)"], rows))
