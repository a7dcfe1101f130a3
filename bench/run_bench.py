#!/usr/bin/python3
"""ELLIPSOID_DEP benchmarks: peers side by side, speed-accuracy trade, scaling.

  ./ellipsoid-dep bench            quick (N ~ 1000, M = 500, 3 repeats; a few minutes)
  ./ellipsoid-dep bench --full     N ~ 4000 side by side, scaling 1e3..1e5
  ./ellipsoid-dep bench kernel     the kernel micro-benchmarks (build/bench/bench_kernel)
  ./ellipsoid-dep bench clumps     multi-sphere clumps against the ellipsoids, whole deposits
                                   (bench/clumps/run_clumps.py; hours on 2 shared cores)
  ./ellipsoid-dep bench accuracy   the contact knobs' cost against phi, Z and the contact
                                   normals of whole default deposits (bench/accuracy/
                                   run_accuracy.py; hours on 2 shared cores)
  ./ellipsoid-dep bench replicate  a settled deposit copied k x k times: the code's own cost
                                   growth with N (bench/cost_curve/run_replicate.py; minutes)

Needs the environment set by ./ellipsoid-dep (LAMMPS_BUILD, LAMMPS_PLUGIN_PATH).  Every number
comes from this one invocation; timings are medians over interleaved repeats.  Output (logs,
data files, tables as JSON and markdown, the Pareto plot) goes to --out (default
runs/bench/quick or runs/bench/full).
"""
import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from bench_rows import LOOP, commit, read_rows  # noqa: E402
SCENES = os.path.join(ROOT, "bench", "scenes")
SPACING = 1.6      # drop lattice spacing (> longest axis 2a = 1.52)
FLOOR_D = 1.0      # frozen floor spheres
NWARM = 20         # untimed warm-up steps before every timed run (history, planes)

# Knob grid of pair_style granular/ellipsoid (label, pair_style arguments).
KNOBS = [
    ("default", "planes yes"),
    ("preset accurate", "preset accurate"),
    ("preset fast", "preset fast"),
    ("tolerance 1e-6", "tolerance 1e-6"),
    ("tolerance 1e-8", "tolerance 1e-8"),
    ("tolerance 1e-10", "tolerance 1e-10"),
    ("iterations 3", "iterations 3"),
    ("iterations 5", "iterations 5"),
    ("iterations 10", "iterations 10"),
    ("correction 1", "correction 1.0"),
    ("correction 5", "correction 5.0"),
    ("correction 15", "correction 15.0"),
    ("planes no", "planes no"),
    ("wang no", "wang no"),
    ("planes no wang no", "planes no wang no"),
    ("fast + correction 5", "preset fast correction 5.0"),
]


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


def liggghts_path():
    """LIGGGHTS 3.8 binary built by tools/liggghts/setup.sh, or None (peer (d) is skipped)."""
    try:
        r = subprocess.run(["bash", os.path.join(ROOT, "tools", "liggghts", "setup.sh"), "path"],
                           stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                           timeout=60)
    except (OSError, subprocess.SubprocessError):
        return None
    exe = r.stdout.strip().splitlines()[-1] if r.stdout.strip() else ""
    return exe if r.returncode == 0 and os.access(exe, os.X_OK) else None


def liggghts_atoms(out, data):
    """Convert our LAMMPS data file (atom_style ellipsoid superellipsoid) into a LIGGGHTS include
    file: create_atoms single (ids in the same order) + set density, blockiness, shape
    (semi-axes) and quat_direct per atom.  Velocities zero, as in the settled data file.
    Returns (include file, box dict)."""
    lines = open(os.path.join(out, data)).read().split("\n")

    def section(name):
        i = next(k for k, x in enumerate(lines) if x.split("#")[0].strip() == name) + 2
        rows = []
        while i < len(lines) and lines[i].strip():
            rows.append(lines[i].split())
            i += 1
        return rows
    box = {}
    for x in lines[:20]:
        m = re.match(r"\s*(\S+)\s+(\S+)\s+([xyz])lo\s+[xyz]hi", x)
        if m:
            box[m.group(3)] = (float(m.group(1)), float(m.group(2)))
    atoms = sorted((int(p[0]), p) for p in section("Atoms"))
    ell = {int(p[0]): p for p in section("Ellipsoids")}
    inc = os.path.join(out, data + ".liggghts")
    with open(inc, "w") as f:
        for tag, p in atoms:   # id type ellipsoidflag density x y z [ix iy iz]
            f.write(f"create_atoms {p[1]} single {p[4]} {p[5]} {p[6]} units box\n")
        for tag, p in atoms:   # id shapex shapey shapez (diameters) qw qi qj qk block1 block2
            e = ell[tag]
            f.write(f"set atom {tag} density {p[3]} blockiness {e[8]} {e[9]} shape "
                    f"{0.5 * float(e[1])!r} {0.5 * float(e[2])!r} {0.5 * float(e[3])!r} "
                    f"quat_direct {e[4]} {e[5]} {e[6]} {e[7]}\n")
    if len(atoms) != len(ell):
        raise RuntimeError(f"{data}: {len(atoms)} atoms but {len(ell)} ellipsoids")
    return inc, box


# LIGGGHTS hertz + tangential history, mapped onto (a)'s hertz 1e5 20 tangential history 1e4 0.5
# (doc/benchmarks.md): 4/3 Y* sqrt(R*) = 1e5 at R* = 1/4, Y* = E / 2(1 - nu^2); the damping
# 2 sqrt(5/6) beta sqrt(2 Y* sqrt(R* xi) m*) equals (a)'s 20 sqrt(xi) at xi = XI_REF, m* = 1/2.
LIG_NU = 0.25
LIG_XI_REF = 1e-3


def liggghts_material():
    ystar = 1e5 * 0.75 / math.sqrt(0.25)
    E = ystar * 2.0 * (1.0 - LIG_NU ** 2)
    c = 20.0 * math.sqrt(LIG_XI_REF)            # (a)'s damping coefficient at XI_REF
    s = 2.0 * math.sqrt(5.0 / 6.0) * math.sqrt(2.0 * ystar * math.sqrt(0.25 * LIG_XI_REF) * 0.5)
    beta = c / s                                # LIGGGHTS: beta = ln e / sqrt(ln^2 e + pi^2)
    e = math.exp(-math.pi * beta / math.sqrt(1.0 - beta * beta))
    return {"E": E, "nu": LIG_NU, "e": e}


def run_liggghts(exe, workdir, log, variables):
    """LIGGGHTS 3.8 with the screen captured (it segfaults with -screen none on some inputs)."""
    cmd = [exe, "-in", os.path.join(SCENES, "in.run_liggghts"), "-log", log]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    r = subprocess.run(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    open(os.path.join(workdir, log + ".screen"), "w").write(r.stdout)
    if r.returncode != 0 or "Loop time" not in r.stdout:
        raise RuntimeError(f"LIGGGHTS failed ({r.returncode}):\n{r.stdout[-2000:]}")
    return os.path.join(workdir, log)


def liggghts_contacts(exe, out, lvars, nmobile):
    """Contacts per mobile particle in LIGGGHTS (compute pair/gran/local, run 0): touching pairs,
    floor-floor excluded, a contact with the floor counted once."""
    surface = lvars["surface"]
    dump = f"dump.z_liggghts_{surface}"
    run_liggghts(exe, out, f"log.z_liggghts_{surface}",
                 dict(lvars, nsteps=0, nwarm=0, zflag=1, zdump=dump))
    types = {}
    for k, x in enumerate(open(os.path.join(out, lvars["atoms"]))):
        if x.startswith("create_atoms"):
            types[len(types) + 1] = int(x.split()[1])
    pairs = set()
    with open(os.path.join(out, dump)) as f:
        lines = f.readlines()
    i = 0
    while i < len(lines):    # first snapshot only
        if lines[i].startswith("ITEM: ENTRIES"):
            i += 1
            while i < len(lines) and not lines[i].startswith("ITEM:"):
                p = lines[i].split()
                if p:
                    a, b = int(float(p[0])), int(float(p[1]))
                    pairs.add((min(a, b), max(a, b)))
                i += 1
            break
        i += 1
    z = sum((types[a] != 1) + (types[b] != 1) for a, b in pairs)
    return z / nmobile


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


# ----------------------------------------------------------------------------------------
def bench_peers(out, g, data_e, data_s, nsteps, repeats, nmobile, nfloor):
    codes = [("(a) granular/ellipsoid", "in.run_ours", data_e, {"knobs": "planes yes"}),
             ("(b) granular/superellipsoid", "in.run_peer", data_e, {}),
             ("(c) granular, spheres", "in.run_sphere", data_s, {}),
             ("(a') granular/ellipsoid, newton on", "in.run_ours", data_e,
              {"knobs": "planes yes", "newton": "on"})]
    lig = liggghts_path()
    lig_codes = []
    if lig is None:
        print("  (d) LIGGGHTS 3.8: skipped, not built (./ellipsoid-dep liggghts setup)", flush=True)
    else:
        inc, box = liggghts_atoms(out, data_e)
        lvars = dict(liggghts_material(), atoms=os.path.basename(inc), L=box["x"][1],
                     zlo=box["z"][0], zhi=box["z"][1], nsteps=nsteps, nwarm=NWARM)
        if abs(box["x"][1] - box["y"][1]) > 1e-12 or box["x"][0] or box["y"][0]:
            raise RuntimeError(f"{data_e}: box not [0, L]^2 in x, y")
        lig_codes = [("(d) LIGGGHTS surface ellipsoid", "ellipsoid"),
                     ("(d') LIGGGHTS surface superquadric", "superquadric")]
    res = {c[0]: [] for c in codes + lig_codes}
    for r in range(repeats):
        for name, surface in lig_codes:
            try:
                log = run_liggghts(lig, out, f"log.liggghts_{surface}_{r}",
                                   dict(lvars, surface=surface))
                res[name].append(parse_log(log))
            except RuntimeError as e:
                print(f"  {name}: FAILED\n{e}", flush=True)
        for name, inp, data, extra in codes:
            tag = inp.split(".")[1] + ("_newton" if "newton" in extra else "") + f"_{r}"
            try:
                log = run_lmp(out, inp, f"log.{tag}",
                              dict(extra, data=data, nsteps=nsteps, nwarm=NWARM))
                res[name].append(parse_log(log))
            except RuntimeError as e:
                print(f"  {name}: FAILED\n{e}", flush=True)
        print(f"  repeat {r + 1}/{repeats} done", flush=True)
    z_e, _ = contacts_per_particle(out, data_e, nfloor, nmobile, tag="z_ellipsoid")
    z_s, _ = contacts_per_particle(out, data_s, nfloor, nmobile, sphere=True, tag="z_sphere")
    z_lig = {}
    for name, surface in lig_codes:
        try:
            z_lig[name] = liggghts_contacts(lig, out, dict(lvars, surface=surface), nmobile)
        except RuntimeError as e:
            print(f"  {name} contacts: FAILED\n{e}", flush=True)
    table = []
    base = None
    for name in [c[0] for c in codes] + [c[0] for c in lig_codes]:
        runs = res[name]
        if not runs:
            table.append({"code": name, "failed": True})
            continue
        pss = med([nmobile * x["steps"] / x["loop"] for x in runs])
        pair = med([x["pair_pct"] for x in runs])
        row = {"code": name, "pss": pss, "ns": 1e9 / pss, "pair_pct": pair,
               "z": z_lig.get(name, float("nan")) if "LIGGGHTS" in name else
               z_s if "spheres" in name else z_e, "repeats": len(runs),
               "spread": (min(nmobile * x["steps"] / x["loop"] for x in runs),
                          max(nmobile * x["steps"] / x["loop"] for x in runs))}
        if "counters" in runs[-1]:
            row["counters"] = runs[-1]["counters"]
            row["evals_per_step"] = runs[-1]["contact_evals"] / runs[-1]["steps"] / nmobile
        if base is None:
            base = pss
        row["ratio"] = pss / base
        table.append(row)
    return table


def peers_markdown(table, nmobile, nfloor, nsteps):
    rows = []
    for r in table:
        if r.get("failed"):
            rows.append([r["code"], "failed", "", "", "", "", ""])
            continue
        rows.append([r["code"], f"{r['pss']:.3g}", f"{r['ns']:.0f}", f"{r['pair_pct']:.1f}",
                     f"{r['z']:.2f}", f"{r['ratio']:.2f}",
                     f"{r['spread'][0]:.3g}-{r['spread'][1]:.3g}"])
    return fmt_table(["code", "particle-steps/s", "ns/particle-step", "Pair %",
                      "contacts/particle", "speed / (a)", "min-max"], rows)


def bench_knobs(out, data_e, nsteps, repeats, nmobile, nfloor):
    # accuracy: per-contact overlap and normal against `preset accurate`, same configuration
    ref = None
    acc = {}
    for label, knobs in [KNOBS[1]] + [k for k in KNOBS if k[0] != "preset accurate"]:
        tag = "k_" + re.sub(r"\W+", "_", label)
        _, pairs = contacts_per_particle(out, data_e, nfloor, nmobile, knobs=knobs, tag=tag)
        if ref is None:
            ref = pairs
        nerr, oerr, nmiss = [], [], 0
        for key, rr in ref.items():
            if rr[2] <= 0.0:
                continue
            r = pairs.get(key)
            if r is None or r[2] <= 0.0:
                nmiss += 1
                continue
            dot = max(-1.0, min(1.0, sum(a * b for a, b in zip(rr[3:6], r[3:6]))))
            nerr.append(math.degrees(math.acos(abs(dot))))
            oerr.append(abs(r[2] - rr[2]) / rr[2])
        acc[label] = {"n": len(nerr), "missed": nmiss,
                      "normal_max_deg": max(nerr) if nerr else 0.0,
                      "normal_med_deg": med(nerr) if nerr else 0.0,
                      "overlap_max_rel": max(oerr) if oerr else 0.0,
                      "overlap_med_rel": med(oerr) if oerr else 0.0}
    # cost: interleaved timing repeats
    times = {k[0]: [] for k in KNOBS}
    pairs_pct = {k[0]: [] for k in KNOBS}
    counters = {}
    for r in range(repeats):
        for label, knobs in KNOBS:
            tag = "kt_" + re.sub(r"\W+", "_", label) + f"_{r}"
            x = parse_log(run_lmp(out, "in.run_ours", f"log.{tag}",
                                  {"data": data_e, "knobs": knobs, "nsteps": nsteps,
                                   "nwarm": NWARM}))
            times[label].append(1e9 * x["loop"] / (nmobile * x["steps"]))
            pairs_pct[label].append(x["pair_pct"])
            counters[label] = x.get("counters", "")
        print(f"  knob repeat {r + 1}/{repeats} done", flush=True)
    table = []
    for label, knobs in KNOBS:
        row = {"label": label, "knobs": knobs, "ns": med(times[label]),
               "pair_pct": med(pairs_pct[label]), "counters": counters[label]}
        row.update(acc[label])
        table.append(row)
    # Pareto front over (cost, max normal error, max overlap error, contacts missed)
    for row in table:
        row["pareto"] = not any(
            (o["ns"] <= row["ns"] and o["normal_max_deg"] <= row["normal_max_deg"]
             and o["overlap_max_rel"] <= row["overlap_max_rel"] and o["missed"] <= row["missed"])
            and (o["ns"] < row["ns"] or o["normal_max_deg"] < row["normal_max_deg"]
                 or o["overlap_max_rel"] < row["overlap_max_rel"] or o["missed"] < row["missed"])
            for o in table)
    return table


def knobs_markdown(table):
    base = next(r["ns"] for r in table if r["label"] == "default")
    rows = [[r["label"], f"{r['ns']:.0f}", f"{r['ns'] / base:.2f}", f"{r['pair_pct']:.1f}",
             f"{r['normal_max_deg']:.2e}", f"{r['overlap_max_rel']:.2e}",
             f"{r['overlap_med_rel']:.1e}", f"{r['missed']}/{r['n'] + r['missed']}",
             "yes" if r["pareto"] else ""] for r in table]
    return fmt_table(["pair_style knobs", "ns/particle-step", "cost / default", "Pair %",
                      "max normal err (deg)", "max overlap err (rel)", "median overlap err",
                      "contacts missed", "Pareto"], rows)


def plot_knobs(table, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("  (matplotlib missing: no plot)")
        return False
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    for ax, key, name in ((axes[0], "normal_max_deg", "max normal error vs accurate (deg)"),
                          (axes[1], "overlap_max_rel", "max relative overlap error vs accurate")):
        floor = 1e-17
        for r in table:
            y = max(r[key], floor)
            ax.scatter(r["ns"], y, c="C3" if r["pareto"] else "C0", s=30)
            ax.annotate(r["label"], (r["ns"], y), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")
        front = sorted([r for r in table if r["pareto"]], key=lambda r: r["ns"])
        ax.plot([r["ns"] for r in front], [max(r[key], floor) for r in front], "C3--",
                lw=1, label="Pareto front (cost, normal, overlap, missed)")
        ax.set_yscale("log")
        ax.set_xlabel("ns per particle-step (whole step)")
        ax.set_ylabel(name)
        ax.legend(fontsize=7)
    fig.suptitle("granular/ellipsoid knobs: error vs cost (settled deposit)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    return True


def bench_scaling(out, g, ks, nsteps_for, repeats, nps):
    base_m = g["nmobile"]
    rows = []
    for k in ks:
        data_e, _ = replicate(out, g, k)
        nmob = base_m * k * k
        for np_ in nps:
            if np_ > 1 and k != ks[-1]:
                continue
            ms = nsteps_for(nmob)
            vals = []
            for r in range(repeats):
                x = parse_log(run_lmp(out, "in.run_ours", f"log.scale_x{k}_np{np_}_{r}",
                                      {"data": data_e, "knobs": "planes yes", "nsteps": ms,
                                       "nwarm": NWARM},
                                      np=np_))
                vals.append(nmob * x["steps"] / x["loop"])
            rows.append({"N": nmob, "np": np_, "steps": ms, "pss": med(vals),
                         "ns": 1e9 / med(vals)})
            print(f"  N={nmob} np={np_}: {med(vals):.3g} particle-steps/s", flush=True)
    return rows


def scaling_markdown(rows):
    n1 = [r for r in rows if r["np"] == 1]
    base = n1[0]["ns"]
    out = []
    for r in rows:
        same_n1 = next((x for x in n1 if x["N"] == r["N"]), None)
        speedup = r["pss"] / same_n1["pss"] if same_n1 else float("nan")
        out.append([r["N"], r["np"], r["steps"], f"{r['pss']:.3g}", f"{r['ns']:.0f}",
                    f"{r['ns'] / base:.2f}", f"{speedup:.2f}"])
    return fmt_table(["N (mobile)", "MPI ranks", "M", "particle-steps/s", "ns/particle-step",
                      "cost / smallest N", "speed-up vs 1 rank"], out)


# ----------------------------------------------------------------------------------------
def bench_spheres(out, nsteps, repeats):
    """The sphere path: 1024 unit spheres settled on a wall by LAMMPS's styles, then the same
    steps through LAMMPS's pair granular + fix wall/gran + nve/sphere and through this
    package's styles (with nve/ellipsoid, and with nve/asphere), alternating, 1 rank."""
    scene = {"L": 10, "zt": 20}
    run_lmp(out, "in.settle_sphere_wall", "log.settle_sphere_wall",
            dict(scene, nfall=5000, out="spheres_wall.dump"))
    codes = [("LAMMPS: granular, wall/gran, nve/sphere", "in.run_sphere_wall", {}),
             ("ours: granular/ellipsoid, wall/gran/ellipsoid, nve/ellipsoid",
              "in.run_sphere_wall_ours", {"integrator": "nve/ellipsoid"}),
             ("ours with nve/asphere", "in.run_sphere_wall_ours", {"integrator": "nve/asphere"})]
    loops = {name: [] for name, _, _ in codes}
    for r in range(repeats):
        for k, (name, inp, extra) in enumerate(codes):
            log = run_lmp(out, inp, f"log.spheres_{k}_{r}",
                          dict(scene, **extra, dump="spheres_wall.dump", nwarm=NWARM,
                               nsteps=nsteps))
            res = parse_log(log)
            loops[name].append(res["loop"])
            atoms = res["atoms"]
        print(f"  repeat {r + 1}/{repeats} done", flush=True)
    base = med(loops[codes[0][0]])
    return [{"code": name, "atoms": atoms, "steps": nsteps, "loop_s": med(loops[name]),
             "spread": (min(loops[name]), max(loops[name])), "repeats": repeats,
             "ratio": med(loops[name]) / base} for name, _, _ in codes]


def spheres_markdown(rows):
    return fmt_table(["code", "spheres", "steps", "loop time (s, median)", "min-max",
                      "time / LAMMPS"],
                     [[r["code"], r["atoms"], r["steps"], f"{r['loop_s']:.3f}",
                       f"{r['spread'][0]:.3f}-{r['spread'][1]:.3f}", f"{r['ratio']:.2f}"]
                      for r in rows])


# ----------------------------------------------------------------------------------------
DEPOSIT_INPUT = os.path.join(ROOT, "examples", "deposit", "in.deposit")


def run_deposit(out, n, np, seed):
    """The default deposit (eta 1.4, zeta 1.8, delta_r 0.6) of n particles from the empty box
    to rest on np ranks: wall time, steps, phi, Z from its log."""
    work = os.path.join(out, f"deposit_N{n}_np{np}_s{seed}")
    os.makedirs(work, exist_ok=True)
    cmd = [lmp_path(), "-in", DEPOSIT_INPUT, "-log", "log.lammps", "-screen", "none", "-nocite",
           "-var", "N", str(n), "-var", "seed", str(seed), "-var", "out", work,
           "-var", "image", "0", "-var", "tangential", "history 2.0e3 0.5"]    # the runner's
    # as `./ellipsoid-dep run` launches it (Open MPI binds 2 ranks to cores); the other rows run
    # unbound and oversubscribed (run_lmp), as their earlier tables did
    if np > 1:
        cmd = ["mpirun", "-np", str(np)] + cmd
    t0 = time.time()
    subprocess.run(cmd, cwd=work, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)
    wall = time.time() - t0
    text = open(os.path.join(work, "log.lammps")).read()
    steps = re.search(r"^ELLIPSOID_DEP: at rest after (\d+) steps", text, re.M)
    res = re.search(r"^RESULT phi ([\d.eE+-]+) Z ([\d.eE+-]+)", text, re.M)
    if not (steps and res):
        raise RuntimeError(f"deposit did not finish: {work}/log.lammps")
    return {"N": n, "ranks": np, "seed": seed, "wall_s": wall, "steps": int(steps.group(1)),
            "phi": float(res.group(1)), "Z": float(res.group(2)),
            "warnings": len(re.findall(r"^WARNING", text, re.M))}


def bench_deposit(out, n, nps, seed):
    rows = []
    for np in nps:
        print(f"  deposit N = {n} on {np} rank(s), seed {seed}", flush=True)
        rows.append(run_deposit(out, n, np, seed))
    one = next((r["wall_s"] for r in rows if r["ranks"] == 1), None)
    for r in rows:
        r["speedup"] = one / r["wall_s"] if one else float("nan")
    return rows


def deposit_markdown(rows):
    return fmt_table(["N", "MPI ranks", "seed", "wall time (s)", "steps", "phi", "Z",
                      "WARNINGs", "speed-up vs 1 rank"],
                     [[r["N"], r["ranks"], r["seed"], f"{r['wall_s']:.0f}", r["steps"],
                       f"{r['phi']:.5f}", f"{r['Z']:.4f}", r["warnings"],
                       f"{r['speedup']:.2f}"] for r in rows])


def bench_clumps(out, n, seed):
    """the ellipsoids against the closest clump (k = 15) at one seed, as `bench clumps` runs
    them (2 ranks each, CPU time of the run)"""
    sub = os.path.join(out, "clumps")
    subprocess.run([sys.executable, os.path.join(ROOT, "bench", "clumps", "run_clumps.py"),
                    "--N", str(n), "--seeds", str(seed), "--runs", "e", "15", "--out", sub,
                    "--results", os.path.join(sub, "results")], check=True)
    rows = {r["run"]: r for r in read_rows(os.path.join(sub, "rows.csv"))}
    return [{"run": name, "N": n, "seed": seed,
             **{k: float(rows[name][k]) for k in ("cpu_seconds", "steps", "phi", "Z")}}
            for name in ("e", "k15")]


def clumps_markdown(rows):
    base = rows[0]["cpu_seconds"]
    names = {"e": "ellipsoids (granular/ellipsoid)", "k15": "clumps k = 15 (rigid/small)"}
    return fmt_table(["run", "N", "seed", "CPU time (s)", "CPU time / ellipsoids", "steps",
                      "phi", "Z"],
                     [[names[r["run"]], r["N"], r["seed"], f"{r['cpu_seconds']:.0f}",
                       f"{r['cpu_seconds'] / base:.2f}", f"{r['steps']:.0f}", f"{r['phi']:.4f}",
                       f"{r['Z']:.3f}"] for r in rows])


def run_kernel():
    exe = os.path.join(ROOT, "build", "bench", "bench_kernel")
    if not os.access(exe, os.X_OK):
        subprocess.run(["cmake", "--build", os.path.join(ROOT, "build"), "--target",
                        "bench_kernel", "-j1"], check=True)
    os.execv(exe, [exe] + sys.argv[2:])


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "kernel":
        run_kernel()
    whole_deposits = {"clumps": os.path.join("clumps", "run_clumps.py"),
                      "accuracy": os.path.join("accuracy", "run_accuracy.py"),
                      "replicate": os.path.join("cost_curve", "run_replicate.py")}
    if len(sys.argv) > 1 and sys.argv[1] in whole_deposits:
        script = os.path.join(ROOT, "bench", whole_deposits[sys.argv[1]])
        os.execv(sys.executable, [sys.executable, script] + sys.argv[2:])
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--full", action="store_true", help="bigger N, M, repeats; N up to 1e5")
    ap.add_argument("--out", help="output folder (default runs/bench/quick or runs/bench/full)")
    ap.add_argument("--only", choices=["peers", "knobs", "scaling", "spheres", "deposit",
                                       "clumps"],
                    action="append",
                    help="run only these parts (repeatable); deposit (the time to deposit "
                    "N = 4000 on 2 and 1 ranks, minutes) and clumps (the ellipsoids against "
                    "k = 15 clumps, N = 2000, one seed, minutes) run by default only with "
                    "--full")
    ap.add_argument("--repeats", type=int)
    args = ap.parse_args()
    mode = "full" if args.full else "quick"
    out = os.path.abspath(args.out or os.path.join(ROOT, "runs", "bench", mode))
    if os.path.isdir(out):
        shutil.rmtree(out)
    os.makedirs(out)
    parts = args.only or ["peers", "knobs", "scaling", "spheres"] + \
        (["deposit", "clumps"] if args.full else [])
    if args.full:
        cfg = {"n": 1000, "peer_k": 2, "M": 1000, "rep": args.repeats or 5, "knob_M": 500,
               "ks": [1, 2, 4, 8, 10], "nps": [1, 2]}
    else:
        cfg = {"n": 1000, "peer_k": 1, "M": 500, "rep": args.repeats or 3, "knob_M": 300,
               "ks": [1, 2], "nps": [1, 2]}
    meta = {"commit": commit(),
            "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
            "nproc": os.cpu_count(), "mode": mode,
            "load": os.getloadavg()[0]}
    t0 = time.time()
    print(f"[bench] {mode}: output in {out}", flush=True)
    report = {"meta": meta}
    md = [f"commit {meta['commit']}, {meta['date']}, nproc {meta['nproc']}, "
          f"load average at start {meta['load']:.1f}, mode {mode}"]
    if "deposit" in parts:
        print("[bench] 0. time to deposit: the default deposit, N = 4000, empty box to rest",
              flush=True)
        rows = bench_deposit(out, 4000, [2, 1], 4928)
        report["deposit"] = rows
        m = deposit_markdown(rows)
        md += ["\n### 0. Time to deposit (examples/deposit/in.deposit defaults, N = 4000, "
               "from the empty box to rest)\n", m]
        print(m, flush=True)
    if set(parts) & {"peers", "knobs", "scaling"}:
        g = make_scenes(out, cfg["n"])
        report["scene"] = g
    if "peers" in parts:
        data_e, data_s = replicate(out, g, cfg["peer_k"])
        nmob = g["nmobile"] * cfg["peer_k"] ** 2
        nfl = g["nfloor"] * cfg["peer_k"] ** 2
        print(f"[bench] 1. peers: N = {nmob} (+{nfl} frozen floor), M = {cfg['M']}, "
              f"{cfg['rep']} repeats", flush=True)
        tab = bench_peers(out, g, data_e, data_s, cfg["M"], cfg["rep"], nmob, nfl)
        report["peers"] = tab
        m = peers_markdown(tab, nmob, nfl, cfg["M"])
        md += [f"\n### 1. Peers side by side (N = {nmob} mobile + {nfl} frozen floor, "
               f"M = {cfg['M']}, median of {cfg['rep']})\n", m]
        if any("LIGGGHTS" in r["code"] for r in tab):
            mat = liggghts_material()
            note = (f"\n(d), (d'): LIGGGHTS 3.8 (`{os.path.basename(liggghts_path() or '')}`), the "
                    f"same particles, orientations and frozen floor (converted data file), "
                    f"`model hertz tangential history` with E = {mat['E']:.6g}, nu = {mat['nu']}, "
                    f"e = {mat['e']:.4f} (4/3 Y* sqrt(R*) = 1e5 at R* = 1/4; damping matched to "
                    f"(a) at xi = {LIG_XI_REF:g}), `tangential_damping off`, `nve/superquadric`; "
                    f"speed / (a) is across two engines (doc/benchmarks.md).")
            md.append(note)
            print(note, flush=True)
        print(m, flush=True)
        for r in tab:
            if "counters" in r:
                print(f"  {r['code']} counters (last repeat): {r['counters']}")
    if "knobs" in parts:
        nmob, nfl = g["nmobile"], g["nfloor"]
        print(f"[bench] 2. knobs: N = {nmob}, M = {cfg['knob_M']}, {cfg['rep']} repeats",
              flush=True)
        tab = bench_knobs(out, "ellipsoid.data", cfg["knob_M"], cfg["rep"], nmob, nfl)
        report["knobs"] = tab
        m = knobs_markdown(tab)
        plotted = plot_knobs(tab, os.path.join(out, "knobs_pareto.png"))
        md += [f"\n### 2. Speed-accuracy trade (N = {nmob}, M = {cfg['knob_M']}, median of "
               f"{cfg['rep']}; errors on {tab[0]['n'] + tab[0]['missed']} contacts vs "
               f"`preset accurate`, run 0 on the settled configuration)\n", m]
        if plotted:
            md.append(f"\nplot: {os.path.join(out, 'knobs_pareto.png')}")
        print(m, flush=True)
    if "scaling" in parts:
        print(f"[bench] 3. scaling: replicas {cfg['ks']}, ranks {cfg['nps']}", flush=True)

        def nsteps_for(n):
            return max(50, min(cfg["M"], int(4e6 / n))) if args.full else \
                max(100, min(300, int(1.2e6 / n)))
        rows = bench_scaling(out, g, cfg["ks"], nsteps_for, cfg["rep"], cfg["nps"])
        report["scaling"] = rows
        m = scaling_markdown(rows)
        md += [f"\n### 3. Scaling (granular/ellipsoid, median of {cfg['rep']})\n", m]
        print(m, flush=True)
    if "spheres" in parts:
        print(f"[bench] 4. sphere path: 1024 spheres on a wall, M = {4 * cfg['M']}, "
              f"{cfg['rep']} repeats", flush=True)
        rows = bench_spheres(out, 4 * cfg["M"], cfg["rep"])
        report["spheres"] = rows
        m = spheres_markdown(rows)
        md += [f"\n### 4. Sphere path (1024 unit spheres on a wall, 1 rank, "
               f"M = {4 * cfg['M']}, median of {cfg['rep']})\n", m]
        print(m, flush=True)
    if "clumps" in parts:
        print("[bench] 5. multi-sphere clumps: the ellipsoids against k = 15, N = 2000",
              flush=True)
        rows = bench_clumps(out, 2000, 4928)
        report["clumps"] = rows
        m = clumps_markdown(rows)
        md += ["\n### 5. Multi-sphere clumps (the Fig. 3 shape at delta_r 0, N = 2000, one seed, "
               "2 ranks each; whether they agree: `./ellipsoid-dep bench clumps`, 3 seeds)\n", m]
        print(m, flush=True)
    meta["seconds"] = time.time() - t0
    json.dump(report, open(os.path.join(out, "results.json"), "w"), indent=1, default=str)
    open(os.path.join(out, "results.md"), "w").write("\n".join(md) + "\n")
    print(f"[bench] done in {meta['seconds']:.0f} s; tables in {out}/results.md", flush=True)


if __name__ == "__main__":
    main()
