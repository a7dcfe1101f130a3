"""Helpers for test_robustness.py and test_restart_pour.py: run a scene with a log file,
sample per-atom and per-contact data, and reduce them to the robustness checks (finite
state, no lost atom, bounded kinetic energy, largest overlap, solver counters).

Everything is read back from LAMMPS output files written at full precision, so the checks
do not depend on the plugin's own kernel.
"""
import json
import os
import re

import numpy as np

import ed_helpers_pour as h
import geometry

COUNTER_PREFIX = "granular/ellipsoid counters: "

# ELLIPSOID_DEP_LONG=1: more collision poses, more particles and steps in the pours
LONG = os.environ.get("ELLIPSOID_DEP_LONG", "0") not in ("", "0")
NEAR = 1.0 + 1e-9    # eta = zeta = NEAR: a near-sphere

ATOM_COLS = ("id x y z vx vy vz fx fy fz tqx tqy tqz quatw quati quatj quatk "
             "shapex shapey shapez").split()


def counters(log):
    """The pair's counters by name from the last JSON line it printed at the end of a run
    (cumulative over the runs of the instance), plus mean_iterations = iterations/contacts."""
    found = [line[len(COUNTER_PREFIX):] for line in log.splitlines()
             if line.startswith(COUNTER_PREFIX)]
    assert found, "the pair printed no counter line"
    c = json.loads(found[-1])
    c["mean_iterations"] = c["iterations"] / c["contacts"] if c["contacts"] else 0.0
    return c


def read_dump_frames(path):
    """All frames of a LAMMPS text dump: list of (timestep, 2d array). nan/inf parse."""
    frames = []
    if not os.path.exists(path):
        return frames
    with open(path) as f:
        lines = f.read().splitlines()
    k = 0
    while k < len(lines):
        if lines[k].startswith("ITEM: TIMESTEP"):
            step = int(lines[k + 1])
            n = int(lines[k + 3])
            start = next(i for i in range(k, len(lines))
                         if lines[i].startswith(("ITEM: ATOMS", "ITEM: ENTRIES"))) + 1
            rows = [l.split() for l in lines[start:start + n]]
            arr = np.array(rows, dtype=float).reshape(n, -1) if n else np.zeros((0, 0))
            frames.append((step, arr))
            k = start + n
        else:
            k += 1
    return frames


def instrument(lmp, work, every, wall_z=None):
    """Dumps every `every` steps: per-atom state (full precision) and per-contact overlaps
    with the two atom ids; thermo with translational and rotational kinetic energy."""
    lmp.command("compute rb_ke all ke")
    lmp.command("compute rb_er all erotate/asphere")
    lmp.command("compute rb_sh all property/atom shapex shapey shapez quatw quati quatj quatk")
    lmp.command("compute rb_pl all pair/local p1")
    lmp.command("compute rb_pa all property/local patom1 patom2")
    cols = "id x y z vx vy vz fx fy fz tqx tqy tqz " + \
        " ".join(f"c_rb_sh[{k}]" for k in (4, 5, 6, 7, 1, 2, 3))
    lmp.command(f"dump rb_a all custom {every} {work}/atoms.dump {cols}")
    lmp.command("dump_modify rb_a sort id format float %.17g")
    lmp.command(f"dump rb_c all local {every} {work}/contacts.dump c_rb_pa[1] c_rb_pa[2] "
                "c_rb_pl")
    lmp.command("dump_modify rb_c format float %.17g")
    lmp.command("thermo_style custom step atoms c_rb_ke c_rb_er")
    lmp.command("thermo_modify format float %.10g lost error")
    lmp.command(f"thermo {every}")


def analyse(lmp, work, wall_z=None):
    """Reduce the dumps and the log to the robustness quantities."""
    lmp.command("undump rb_a")   # flush and close the dumps
    lmp.command("undump rb_c")
    log = h.read_log(lmp)
    frames = read_dump_frames(os.path.join(work, "atoms.dump"))
    contacts = read_dump_frames(os.path.join(work, "contacts.dump"))
    finite = all(np.isfinite(a).all() for _, a in frames)
    thermo = []
    for m in re.finditer(r"^\s*(\d+)\s+(\d+)\s+(\S+)\s+(\S+)\s*$", log, re.M):
        thermo.append((int(m.group(1)), int(m.group(2)), float(m.group(3)),
                       float(m.group(4))))
    thermo = np.array(thermo)
    finite = finite and np.isfinite(thermo[:, 2:]).all()
    # smallest semi-axis per id (shapes do not change)
    last = frames[-1][1]
    cmin = dict(zip(last[:, 0].astype(int), 0.5 * last[:, 17:20].min(axis=1)))
    worst_pair = 0.0
    for _, c in contacts:
        if c.size == 0:
            continue
        c = c[c[:, 2] > 0]
        if len(c) == 0:
            continue
        ref = np.array([min(cmin[int(i)], cmin[int(j)]) for i, j in c[:, :2]])
        worst_pair = max(worst_pair, float((c[:, 2] / ref).max()))
    worst_wall = 0.0
    if wall_z is not None:
        for _, a in frames:
            for row in a:
                low = geometry.lowest_z(row[13:17], 0.5 * row[17:20], row[3])
                worst_wall = max(worst_wall, (wall_z - low) / (0.5 * row[17:20].min()))
    return {
        "log": log, "frames": frames, "finite": bool(finite), "thermo": thermo,
        "natoms": lmp.get_natoms(), "counters": counters(log),
        "ke_max": float((thermo[:, 2] + thermo[:, 3]).max()),
        "ke_last": float(thermo[-1, 2] + thermo[-1, 3]),
        "overlap_pair": worst_pair, "overlap_wall": worst_wall,
    }


def assert_robust(res, natoms, ke_bound, overlap_frac, min_contacts=1, label=""):
    """The five robustness checks (module docstring), with a message naming the case and the
    numbers."""
    c = res["counters"]
    msg = (f"{label}: natoms {res['natoms']}, ke_max {res['ke_max']:.4g} (bound "
           f"{ke_bound:.4g}), overlap pair {res['overlap_pair']:.4g} wall "
           f"{res['overlap_wall']:.4g} (bound {overlap_frac}), counters {c}")
    assert res["finite"], "non-finite value: " + msg
    assert res["natoms"] == natoms, "lost atoms: " + msg
    assert res["ke_max"] <= ke_bound, "kinetic energy: " + msg
    assert max(res["overlap_pair"], res["overlap_wall"]) < overlap_frac, "overlap: " + msg
    assert c["contacts"] >= min_contacts, "no contact exercised: " + msg
    assert c["not_converged"] <= 1e-6 * c["contacts"], "not converged: " + msg


def mass_of(semi):
    """Mass of a body of density 1."""
    return geometry.volume(semi)


def report(case, res):
    """One `ROBUST case: ...` line of the measured numbers (doc/robustness.md; pytest -s)."""
    c = res["counters"]
    print(f"\nROBUST {case}: overlap/c_min pair {res['overlap_pair']:.3g} wall "
          f"{res['overlap_wall']:.3g}, ke_max {res['ke_max']:.4g}, contacts {c['contacts']}, "
          f"not converged {c['not_converged']}, mean iterations {c['mean_iterations']}")


def assert_shapeless_atom_refused(lmp, commands, message):
    """The scene (scenes.shapeless_deposit) stops with `message` at step 1, when fix deposit
    brings its first atom without a shape, instead of running on."""
    import pytest

    lmp.commands_string(commands)
    with pytest.raises(Exception, match=re.escape(message)):
        lmp.command("run 3000")
    assert lmp.extract_global("ntimestep") == 1
