"""Table 1, peers side by side: (a) granular/ellipsoid, (b) granular/superellipsoid, (c)
granular on the equal-volume spheres, (a') with newton on, and (d), (d') LIGGGHTS 3.8 with the
adapter's `surface ellipsoid` and its own `surface superquadric` on the same particles, when
LIGGGHTS is built (`./ellipsoid-dep bench` builds it when this table runs)."""
import math
import os
import re
import subprocess

from .lmp_runs import NWARM, ROOT, SCENES, contacts_per_particle, fmt_table, med, parse_log, \
    run_lmp


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


def liggghts_note():
    """The markdown note under the table on how the LIGGGHTS rows were set up."""
    mat = liggghts_material()
    return (f"\n(d), (d'): LIGGGHTS 3.8 (`{os.path.basename(liggghts_path() or '')}`), the "
            f"same particles, orientations and frozen floor (converted data file), "
            f"`model hertz tangential history` with E = {mat['E']:.6g}, nu = {mat['nu']}, "
            f"e = {mat['e']:.4f} (4/3 Y* sqrt(R*) = 1e5 at R* = 1/4; damping matched to "
            f"(a) at xi = {LIG_XI_REF:g}), `tangential_damping off`, `nve/superquadric`; "
            f"speed / (a) is across two engines (doc/benchmarks.md).")
