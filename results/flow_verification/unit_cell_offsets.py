"""unit cell of the simple cubic lattice, flow along x: voxelisation methods against Zick & Homsy
centre: voxel solid when its centre is in the sphere; pv05: partial volume (s^3 sub-points) >= 0.5;
pvm: partial volume, threshold matched to the exact solid fraction"""
import sys, math, time
import numpy as np
sys.path.insert(0, __import__("os").path.join(__import__("os").path.dirname(__file__), "../../tools/pores"))
import pore_flow
from zick_homsy import permeability as zh
c = float(sys.argv[1]); methods = sys.argv[2].split(","); ns = [float(x) for x in sys.argv[3].split(",")]
shifts = [tuple(float(v) for v in s.split(":")) for s in sys.argv[4].split(",")]
S = int(sys.argv[5]) if len(sys.argv) > 5 else 4
kzh, a = zh(c)
if c > 0.5: a = 0.5
L = 1.0   # cell edge; d = 2a
d = 2 * a
cexact = 4 / 3 * math.pi * a ** 3
def inside(pts, sh):
    r2 = 0
    for ax in range(3):
        x = pts[ax] - (0.5 + sh[ax])
        x = (x + 0.5) % 1.0 - 0.5
        r2 = r2 + x * x
    return r2 <= a * a
for n in ns:
    m = int(round(n * L / d)); h = L / m
    for sh in shifts:
        shv = [s * h for s in sh]
        for meth in methods:
            if meth == "centre":
                x = (np.arange(m) + 0.5) * h
                P = np.meshgrid(x, x, x, indexing="ij")
                solid = inside(P, shv); thr = None
            else:
                xs = (np.arange(m * S) + 0.5) * h / S
                P = np.meshgrid(xs, xs, xs, indexing="ij")
                f = inside(P, shv).reshape(m, S, m, S, m, S).mean(axis=(1, 3, 5))
                if meth == "pv05":
                    thr = 0.5
                else:
                    levels = np.unique(f)
                    fr = np.array([(f >= t).mean() for t in levels])
                    thr = levels[np.argmin(abs(fr - cexact))]
                solid = f >= thr
            t = time.time()
            k = pore_flow.permeability(solid, (h,) * 3, ("xx",), periodic=(True, True, True))
            kk = k["xx"] / L ** 2
            print("%s c %.4f n/d %.1f m %d shift %s S %d thr %s cvox %.4f k %.6g ZH %.6g err %+.2f%% it %d %.0fs" % (
                meth, c, n, m, ":".join("%.2f" % s for s in sh), S, thr, solid.mean(), kk, kzh,
                100 * (kk / kzh - 1), k["iterations"]["xx"], time.time() - t), flush=True)
