"""Running LAMMPS on the side-by-side benchmark's scenes (bench/scenes) and reading its logs:
the settled ellipsoid and sphere deposits every table starts from, their k x k replicas, the
contacts per particle at a configuration, and the tables' markdown."""
import math
import os
import re
import statistics
import subprocess
import sys
import time

from bench_rows import LOOP

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "bench", "scenes")
SPACING = 1.6      # drop lattice spacing (> longest axis 2a = 1.52)
FLOOR_D = 1.0      # frozen floor spheres
NWARM = 20         # untimed warm-up steps before every timed run (history, planes)


def lmp_path():
    build = os.environ.get("LAMMPS_BUILD")
    if not build or not os.access(os.path.join(build, "lmp"), os.X_OK):
        sys.exit("run_bench.py: LAMMPS_BUILD/lmp not found; run through ./ellipsoid-dep bench")
    return os.path.join(build, "lmp")


def run_lmp(workdir, inp, log, variables, np=1, check=True):
    cmd = [lmp_path(), "-in", os.path.join(SCENES, inp), "-log", log, "-screen", "none",
           "-nocite"]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    if np > 1:
        cmd = ["mpirun", "-np", str(np), "--oversubscribe", "--bind-to", "none"] + cmd
    r = subprocess.run(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    if check and r.returncode != 0:
        tail = ""
        logp = os.path.join(workdir, log)
        if os.path.exists(logp):
            tail = "".join(open(logp).readlines()[-15:])
        raise RuntimeError(f"lmp {inp} failed ({r.returncode}):\n{r.stdout[-2000:]}\n{tail}")
    return os.path.join(workdir, log)


def parse_log(path):
    """Last run of a LAMMPS log: loop time, steps, atoms, Pair %total, our counters."""
    text = open(path).read()
    loops = [m.groups() for m in map(LOOP.match, text.splitlines()) if m]
    if not loops:
        raise RuntimeError(f"no loop time in {path}")
    t, procs, steps, atoms = loops[-1]
    pair = re.findall(r"^Pair\s*\|.*\|\s*([\d.]+)\s*$", text, re.M) or \
        re.findall(r"^Pair\s+time \(%\) = \S+ \(([\d.eE+-]+)\)", text, re.M)    # LIGGGHTS
    res = {"loop": float(t), "procs": int(procs), "steps": int(steps), "atoms": int(atoms),
           "pair_pct": float(pair[-1]) if pair else float("nan")}
    c = re.findall(r"granular/ellipsoid: (.*)", text)
    if c:
        res["counters"] = c[-1].strip()
        m = re.search(r"(\d+) contacts", c[-1])
        if m:
            res["contact_evals"] = int(m.group(1))
    return res


def scene_geometry(n_target):
    nx = max(3, round(math.sqrt(n_target / 16.0)))
    nz = max(2, round(n_target / nx ** 2))
    L = SPACING * nx
    nf = round(L / FLOOR_D)
    rhof = (nf / L) ** 3
    zt = SPACING * (nz + 1)
    return {"L": L, "zt": zt, "rhof": rhof, "nmobile": nx * nx * nz, "nfloor": nf * nf,
            "nfall": int(2000 + 250 * nz)}


def make_scenes(out, n_target, seed=4321):
    """Settle the ellipsoid deposit and the equal-volume sphere deposit (same lattice)."""
    g = scene_geometry(n_target)
    t0 = time.time()
    common = {"L": g["L"], "zt": g["zt"], "rhof": g["rhof"], "nfall": g["nfall"]}
    run_lmp(out, "in.settle_ellipsoid", "log.settle_ellipsoid",
            dict(common, seed=seed, out="ellipsoid.data"))
    run_lmp(out, "in.settle_sphere", "log.settle_sphere", dict(common, out="sphere.data"))
    print(f"  settled {g['nmobile']} ellipsoids + {g['nfloor']} floor spheres "
          f"(and the sphere deposit) in {time.time() - t0:.0f} s", flush=True)
    return g


def replicate(out, g, k):
    """k x k copies of both deposits (periodic in x, y): N grows by k^2."""
    if k == 1:
        return "ellipsoid.data", "sphere.data"
    names = []
    for style, src in (("ellipsoid superellipsoid", "ellipsoid.data"), ("sphere", "sphere.data")):
        dst = f"{src.split('.')[0]}_x{k}.data"
        if not os.path.exists(os.path.join(out, dst)):
            run_lmp(out, "in.replicate", f"log.replicate_{dst}",
                    {"style": style, "data": src, "nx": k, "ny": k, "out": dst})
        names.append(dst)
    return tuple(names)


def contacts_per_particle(out, data, nfloor, nmobile, sphere=False, knobs="planes yes",
                          tag="c"):
    """Contacts per mobile particle at the configuration of `data` (floor contacts count)."""
    dump = f"dump.{tag}"
    if sphere:
        run_lmp(out, "in.contacts_sphere", f"log.{tag}", {"data": data, "out": dump})
    else:
        run_lmp(out, "in.contacts_ours", f"log.{tag}", {"data": data, "knobs": knobs,
                                                       "out": dump})
    rows = read_local(os.path.join(out, dump))
    seen = {}
    for r in rows:
        key = (min(r[0], r[1]), max(r[0], r[1]))
        seen[key] = r
    z = 0
    for r in seen.values():
        touching = (r[2] < 1.0) if sphere else (r[2] > 0.0)
        if touching:
            z += (r[-2] != 1) + (r[-1] != 1)    # type 1 = frozen floor
    return z / nmobile, seen


def read_local(path):
    rows = []
    with open(path) as f:
        lines = f.readlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: ENTRIES"):
            i += 1
            while i < len(lines) and not lines[i].startswith("ITEM:"):
                p = lines[i].split()
                if p:    # id1 id2 values... type1 type2
                    rows.append([int(p[0]), int(p[1])] + [float(x) for x in p[4:]] +
                                [int(p[2]), int(p[3])])
                i += 1
        else:
            i += 1
    return rows


def med(xs):
    return statistics.median(xs) if xs else float("nan")


def fmt_table(headers, rows):
    out = ["| " + " | ".join(headers) + " |", "|" + "|".join("---" for _ in headers) + "|"]
    for r in rows:
        out.append("| " + " | ".join(str(x) for x in r) + " |")
    return "\n".join(out)
