"""the lattice deposits' k at the default voxels (d/13, d/16, d/20), each the mean over the
grid's offsets, extrapolated with the tool's fit; against Zick & Homsy"""
import sys, json, os
sys.path.insert(0, os.environ.get("PORES", os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../tools/pores")))
import numpy as np
import pore_flow_domain as D
from pore_flow_fit import extrapolate
for path in sys.argv[1:]:
    rows = {r["n"]: r for r in map(json.loads, open(path))}
    for ns in ((13.0, 16.0, 20.0), (10.0, 13.0, 16.0)):
        if not all(n in rows for n in ns):
            continue
        want = rows[ns[0]]["zick_homsy_d2"]
        out = []
        for key in ("xx", "zz"):
            res = [rows[n]["resolution"] for n in ns]
            # the tool's rule: two offsets, four unless the first two agree within 1 %
            used = []
            for r in res:
                each = [s[key] for s in r["offsets"]]
                two = each[:2]
                agree = all(D.standard_error([s[k] for s in r["offsets"][:2]]) <= D.OFFSET_PRECISION * np.mean([s[k] for s in r["offsets"][:2]]) for k in ("xx", "zz"))
                used.append(two if agree else each)
            k = [np.mean(u) for u in used]
            se = [D.standard_error(u) for u in used]
            e = extrapolate([1 / n for n in ns], k, se)
            out.append("%s: %s; k0 %+.1f +- %.1f %% (p %s; offsets %s)" % (
                key, ", ".join("%+.1f" % (100 * (v / want - 1)) for v in k),
                100 * (e["k0"] / want - 1), 100 * e["error"] / want,
                "none" if e["p_fitted"] is None else "%.1f" % e["p_fitted"], ",".join(str(len(u)) for u in used)))
            if key == "xx": kxx, exx = k, e
            else: kzz, ezz = k, e
        ratio = [a / b for a, b in zip(kxx, kzz)]
        ea = extrapolate([1 / n for n in ns], ratio)
        print(os.path.basename(path), "d/%s" % ",".join("%g" % n for n in ns), " | ".join(out),
              "| xx/zz %s; k0 %.3f +- %.3f (k0 ratio %.3f)" % (", ".join("%.3f" % r for r in ratio), ea["k0"], ea["error"], exx["k0"] / ezz["k0"]))
