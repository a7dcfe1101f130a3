"""the lattice deposits' k at the default voxels (d/13, d/16, d/20), each the mean over the
grid's offsets as the tool takes them (two, four unless the two agree), extrapolated with the
tool's fit; against Zick & Homsy (doc/howto_pores.md, "Simple cubic lattices at the defaults")"""
import json
import os
import sys

sys.path.insert(0, os.environ.get("PORES", os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                        "../../tools/pores")))
import numpy as np
import pore_flow_domain as D
from pore_flow_fit import extrapolate

NS = (13.0, 16.0, 20.0)
cases = {}
for path in sys.argv[1:]:
    for r in map(json.loads, open(path)):
        cases.setdefault((r["c"], r["shift_d"]), {})[r["n"]] = r
for (c, shift), rows in cases.items():
    if not all(n in rows for n in NS):
        print("c %g shift %g d: not every default voxel solved" % (c, shift))
        continue
    want = rows[NS[0]]["zick_homsy_d2"]
    h = [1 / n for n in NS]
    line, values = [], {}
    for key in ("xx", "zz"):
        used = [D.offsets_taken(rows[n]["resolution"]["offsets"], ("xx", "zz")) for n in NS]
        k = [np.mean([s[key] for s in u]) for u in used]
        e = extrapolate(h, k, [D.offset_error([s[key] for s in u], len(u) == 2) for u in used])
        values[key] = k
        line.append("%s: %s; k0 %+.1f +- %.1f %% (p=2 %+.1f, finest %+.1f; fitted p %s; offsets %s)" % (
            key, ", ".join("%+.1f" % (100 * (v / want - 1)) for v in k),
            100 * (e["k0"] / want - 1), 100 * e["error"] / want,
            100 * (e["k0_fixed_p"] / want - 1), 100 * (e["k_finest"] / want - 1),
            "none" if e["p_fitted"] is None else "%.1f" % e["p_fitted"],
            ",".join(str(len(u)) for u in used)))
    ratio, ratio_se = [], []
    for n in NS:
        u = D.offsets_taken(rows[n]["resolution"]["offsets"], ("xx", "zz"))
        each = [s["xx"] / s["zz"] for s in u]
        ratio.append(np.mean(each))
        ratio_se.append(D.offset_error(each, len(u) == 2))
    e = extrapolate(h, ratio, ratio_se)
    print("c %g shift %g d | %s | xx/zz %s; k0 %.3f +- %.3f" % (
        c, shift, " | ".join(line), ", ".join("%.3f +- %.3f" % v for v in zip(ratio, ratio_se)),
        e["k0"], e["error"]))
