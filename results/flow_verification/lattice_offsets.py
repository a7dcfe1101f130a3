"""a simple cubic lattice deposit, 2 x 2 cells wide (narrower than the default box: the flow
domain is the whole periodic slab), slab of `layers` cells on the lattice's mirror planes;
the tool's flow_permeability at one voxel per call with all 4 offsets; one json line per voxel"""
import sys, json, math, time, os
import numpy as np
sys.path.insert(0, __import__("os").path.join(__import__("os").path.dirname(__import__("os").path.abspath(__file__)), "../../tools/pores"))
import pores, pore_flow_domain as D
D.OFFSET_PRECISION = -1.0    # all offsets, for the record
from zick_homsy import permeability as zh
c, shift, layers, out = float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]), sys.argv[5]
ns = [float(v) for v in sys.argv[4].split(",")]
kzh, a = zh(c)
if c > 0.5: a = 0.5
d = 2 * a
cen = np.array([[i + 0.5 + shift, j + 0.5 + shift, k + 0.5] for i in range(2) for j in range(2) for k in range(layers + 4)])
p = pores.Particles(cen, np.tile([1.0, 0, 0, 0], (len(cen), 1)), np.full((len(cen), 3), a))
box = np.array([[0, 2], [0, 2], [0, layers + 4]], float)
done = {json.loads(l)["n"] for l in open(out)} if os.path.exists(out) else set()
for n in ns:
    if n in done: continue
    t = time.time()
    k = D.flow_permeability(p, box, 2.0, 2.0 + layers, [d / n], directions=("xx", "zz"))
    r = k["resolutions"][0]
    row = {"c": c, "shift_d": shift, "layers": layers, "n": n, "zick_homsy_d2": kzh / d ** 2,
           "seconds": time.time() - t, "resolution": r}
    with open(out, "a") as f:
        f.write(json.dumps(row) + "\n")
    print(n, "xx %+.2f%% zz %+.2f%%" % (100 * (r["xx"] * d ** 2 / kzh - 1), 100 * (r["zz"] * d ** 2 / kzh - 1)), flush=True)
