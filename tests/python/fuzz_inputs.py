"""Mutation fuzzer of the package's command lines (the engine; test_fuzz_inputs.py drives it).

Two valid base inputs (lj units with *hertz*, si units with named materials) use every style
of the package (pair granular/ellipsoid, fix wall/gran/ellipsoid, fix pour/ellipsoid, compute
packing/ellipsoid, contact/histo, force/histo, orient/histo, packing/profile). A mutant changes one of
the package's command lines by one to three operations: replace, drop, duplicate, swap or
insert tokens, or truncate the line; replacements are
special numbers (nan, inf, 1e308, -0, 2^31, ...), scaled numbers, or words of the styles'
other keywords. Each mutant runs in its own `lmp` process with a time limit and an address
space limit, then writes every atom's state (x, v, f, torque, angular momentum, quaternion)
to a dump.

Outcomes:
  ok         the run finished; positions, velocities, forces, torques and every printed
             value of the package's computes are finite
  error      LAMMPS stopped with an ERROR message and a normal exit code (the correct
             answer to bad input)
  crash      killed by a signal, or a non-zero exit without an ERROR message
  sanitizer  an AddressSanitizer / UndefinedBehaviorSanitizer report with a frame in the
             package (sanitized build)
  host       such a report whose stacks never enter the package, or a known crash of
             LAMMPS itself (HOST_CRASH) (listed, not a failure)
  hang       the time limit was reached
  nonfinite  the run finished with a non-finite value in the state or the thermo output
"""
import math
import os
import random
import re
import resource
import signal
import subprocess
import tempfile

# Lines starting with '@' are fuzz targets (the package's commands). The thermo line prints
# every compute's first values; FINAL (run, then the state at full precision into {dump})
# follows every input.
LJ_BASE = """
units lj
atom_style ellipsoid
atom_modify map array
boundary p p f
comm_modify vel yes
region box block 0 4 0 4 0 6
create_box 2 box
create_atoms 1 single 1.0 1.0 0.40
create_atoms 1 single 1.9 1.1 0.45
create_atoms 2 single 1.4 1.2 1.10
create_atoms 1 single 3.0 3.0 0.60
set type 1 mass 1.0
set type 2 mass 0.8
set type 1 shape 1.2 0.9 0.7
set type 2 shape 1.0 1.0 1.0
set atom 2 quat 1 1 0 40
set atom 4 quat 0 1 1 70
velocity all set 0.1 -0.2 -0.5
@pair_style granular/ellipsoid tolerance 1e-12 iterations 50 correction 5.0 planes yes wang yes
@pair_coeff * * hertz 1e4 50 tangential history 1e3 0.5 rolling constant 0.02
@pair_coeff 1 2 hertz 2e4 60 limit_damping tangential viscous 0.3
@fix w all wall/gran/ellipsoid hertz 1e4 50 tangential history 1e3 0.5 rolling constant 0.02 zplane 0.0 NULL
region ins block 0 4 0 4 3.5 5.5
fix g all gravity 1.0 vector 0 0 -1
@fix p all pour/ellipsoid 6 1 4711 region ins size mean 0.4 delta_r 0.3 alpha 2 beta 3 shape 1.4 1.2 dshape 0.1 0.1 density 1.0 vol 0.1 50 vel 0 0 0 0 -1 every 50
fix i all nve/asphere
@compute pk all packing/ellipsoid auto bottom 0.5 top 0.5 rattler 2 surface columns
@compute pe all packing/ellipsoid EDGE 1.5 rattler 0
@compute ch all contact/histo bins 8 slab pk select center
@compute cz all contact/histo bins 6 zlo 0.0 zhi 2.0 select point
@compute oh all orient/histo axis short bins 9 fold yes zlo 0 zhi 3
@compute pp all packing/profile 0.5 zlo 0.0 zhi 3.0
@compute cw all contact/histo bins 5 weight force
@compute fh all force/histo bins 6 max 4 slab pk select center
thermo_style custom step atoms ke c_pk[1] c_pk[3] c_pe[1] c_ch[1] c_cz[7] c_oh[1] c_pp[1][2] c_cw[7] c_cw[2][4] c_fh[1] c_fh[4] c_fh[2][2]
thermo_modify lost error
thermo 50
timestep 1e-3
"""

SI_BASE = """
units si
atom_style ellipsoid
atom_modify map array
boundary f p f
comm_modify vel yes
region box block 0 0.02 0 0.02 0 0.03
create_box 2 box
create_atoms 1 single 0.005 0.005 0.0021
create_atoms 2 single 0.00969 0.005 0.00199
set type 1 mass 3.0e-5
set type 2 mass 2.0e-5
set type 1 shape 0.006 0.004 0.003
set type 2 shape 0.004 0.004 0.004
set atom 1 quat 1 0 1 30
velocity all set 0.01 0 -0.05
@pair_style granular/ellipsoid preset fast impact_velocity 0.5
@pair_coeff * * hertz/material glass tangential history 1e4 0.4
@pair_coeff 2 2 hertz/material 1e9 0.6 0.3 damping coeff_restitution limit_damping rolling constant 0.01
@fix w all wall/gran/ellipsoid hertz/material glass tangential history 1e4 0.4 zplane 0.0 NULL xplane 0.0 0.02 wall_material steel impact_velocity 0.3
region ins block 0 0.02 0 0.02 0.012 0.025
fix g all gravity 9.81 vector 0 0 -1
@fix p all pour/ellipsoid 4 2 977 region ins size 0.0015 0.0025 shape 1.3 1.1 density 2500 vol 0.05 40
fix i all nve/asphere
@compute pk all packing/ellipsoid 0.0 0.01 rattler 1
@compute pa all packing/ellipsoid auto bottom 1 top 1 floor 0.0 surface max
@compute ch all contact/histo bins 10
@compute oh all orient/histo axis long bins 12 fold no slab pa
@compute pp all packing/profile 0.002
thermo_style custom step atoms ke c_pk[1] c_pa[1] c_ch[1] c_oh[1] c_pp[2][2]
thermo_modify lost error
thermo 50
timestep 5e-7
"""

FINAL = """compute q all property/atom quatw quati quatj quatk
run 150
write_dump all custom {dump} id x y z vx vy vz fx fy fz tqx tqy tqz angmomx angmomy angmomz &
  c_q[*] modify format float %.17g
"""

BASES = {"lj": LJ_BASE, "si": SI_BASE}

SPECIAL_NUMBERS = ["nan", "NaN", "inf", "-inf", "1e308", "-1e308", "1e-308", "4.9e-324",
                   "-0", "0", "-1", "1", "2", "0.5", "1e20", "-1e-20", "2147483647",
                   "2147483648", "-2147483648", "4294967296", "9223372036854775808",
                   "1e", "0x10", "1.5.5", ""]
KEYWORDS = """hertz hertz/material tangential none viscous history rolling constant
limit_damping damping coeff_restitution viscoelastic tsuji mindlin linear_history
zplane xplane yplane NULL wall_material rigid impact_velocity region size mean delta_r alpha
beta shape dshape density vol rate vel every tolerance iterations correction planes wang
preset accurate fast yes no bins zlo zhi slab select point center axis long middle short fold
auto bottom top rattler floor surface max columns EDGE glass steel unobtainium * 1*2 2* ins
box pk pe pa ch p w all granular/ellipsoid pour/ellipsoid wall/gran/ellipsoid
packing/ellipsoid contact/histo orient/histo packing/profile pp weight force none force/histo
cw fh""".split()

NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


def targets(base):
    """Indices of the fuzz-target lines of a base input (its lines without the '@')."""
    lines = base.strip("\n").split("\n")
    return [k for k, line in enumerate(lines) if line.startswith("@")]


def base_lines(base):
    return [line.lstrip("@") for line in base.strip("\n").split("\n")]


# Tokens a mutation leaves alone: the command word, and for fix/compute/pair_style the ID,
# group and style name (their errors are LAMMPS's own, not the package's).
PROTECTED = {"fix": 4, "compute": 4, "pair_style": 2, "pair_coeff": 1}


def _replacement(rng, token):
    choice = rng.random()
    if NUMBER.match(token) and choice < 0.4:
        value = float(token)
        factor = rng.choice([-1.0, 0.0, 1e-12, 1e-6, 1e-3, 0.5, 2.0, 1e3, 1e6, 1e12, 1e300])
        return repr(value * factor) if math.isfinite(value * factor) else "inf"
    if choice < 0.75:
        return rng.choice(SPECIAL_NUMBERS)
    return rng.choice(KEYWORDS)


def mutate_tokens(rng, tokens):
    """One random operation on a line's tokens after the protected ones."""
    op = rng.choice(["replace", "replace", "replace", "replace", "drop", "duplicate", "swap",
                     "truncate", "insert"])
    head = PROTECTED[tokens[0]]
    body = tokens[head:]
    if not body:
        return tokens, op
    k = rng.randrange(len(body))
    if op == "replace":
        body[k] = _replacement(rng, body[k])
    elif op == "drop":
        del body[k]
    elif op == "duplicate":
        body.insert(k, body[k])
    elif op == "swap":
        j = rng.randrange(len(body))
        body[k], body[j] = body[j], body[k]
    elif op == "truncate":
        body = body[:k]
    else:
        body.insert(k, _replacement(rng, rng.choice(body)))
    return tokens[:head] + [t for t in body if t != ""], op


def mutants(seed, count):
    """count distinct mutants: (base name, line index, mutated line, description)."""
    rng = random.Random(seed)
    seen = set()
    while len(seen) < count:
        name = rng.choice(sorted(BASES))
        lines = base_lines(BASES[name])
        k = rng.choice(targets(BASES[name]))
        tokens = lines[k].split()
        ops = []
        for _ in range(rng.choice([1, 1, 1, 1, 1, 2, 2, 3])):
            tokens, op = mutate_tokens(rng, tokens)
            ops.append(op)
        line = " ".join(tokens)
        if line == lines[k] or (name, k, line) in seen:
            continue
        seen.add((name, k, line))
        yield name, k, line, "+".join(ops)


def mutant_input(name, k, line, dump):
    lines = base_lines(BASES[name])
    lines[k] = line
    return "\n".join(lines) + "\n" + FINAL.replace("{dump}", dump)


def _limit_memory():
    # a mutant that asks for an absurd allocation gets a failed malloc (a LAMMPS ERROR),
    # not the machine's memory; not under ASan, which needs a large virtual address space
    if "libasan" not in os.environ.get("LD_PRELOAD", ""):
        resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))


def _finite_dump(path):
    with open(path) as f:
        lines = f.read().splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS")) + 1
    for row in lines[start:]:
        if not all(math.isfinite(float(v)) for v in row.split()):
            return False, row
    return True, ""


def _nonfinite_thermo(out):
    """The first thermo row with a non-finite value of a compute (c_ columns; LAMMPS's own
    ke overflows in si units once sum m v^2 / k_B does, which is no fault of the package)."""
    columns = []
    for row in out.splitlines():
        words = row.split()
        if words[:1] == ["Step"]:
            columns = [k for k, w in enumerate(words) if w.startswith("c_")]
        elif words[:1] == ["Loop"]:
            columns = []
        elif columns and words and words[0].isdigit() and len(words) > max(columns):
            if any(words[k].lower() in ("nan", "-nan", "inf", "-inf") for k in columns):
                return row
    return ""


SANITIZER = re.compile(r"AddressSanitizer|LeakSanitizer|runtime error:")
PACKAGE_FRAME = re.compile(r"ellipsoiddepplugin\.so|ELLIPSOID_DEP/")
# Crashes of LAMMPS itself that the package's lines reach: utils::bounds (every pair_coeff's
# type range) lets std::stol's out_of_range escape; `pair_style lj/cut` does the same.
HOST_CRASH = re.compile(r"^Exception: stol$", re.M)


def run_mutant(lmp, name, k, line, timeout=60.0, env=None):
    """Run one mutant; returns (outcome, detail)."""
    with tempfile.TemporaryDirectory(prefix="fuzz_") as work:
        dump = os.path.join(work, "final.dump")
        with open(os.path.join(work, "in.fuzz"), "w") as f:
            f.write(mutant_input(name, k, line, dump))
        try:
            proc = subprocess.run([lmp, "-in", "in.fuzz", "-log", "none", "-echo", "none",
                                   "-nocite"], cwd=work, capture_output=True, text=True,
                                  errors="replace", timeout=timeout, env=env,
                                  preexec_fn=_limit_memory, start_new_session=True)
        except subprocess.TimeoutExpired:
            return "hang", f"no end after {timeout:.0f} s"
        out = proc.stdout + proc.stderr
        if SANITIZER.search(out):
            report = next(l for l in out.splitlines() if SANITIZER.search(l))
            # a report whose stacks never enter the package is the host's (seen: Open MPI's
            # singleton MPI_Abort races a PMIx thread, heap-use-after-free in orte_rml)
            if PACKAGE_FRAME.search(out):
                return "sanitizer", report.strip()
            return "host", report.strip()
        if proc.returncode < 0:
            return "crash", f"signal {signal.Signals(-proc.returncode).name}"
        error = re.search(r"^ERROR.*$", out, re.M)
        host = HOST_CRASH.search(out)
        if host:
            return "host", host.group(0)
        if proc.returncode != 0:
            if error and proc.returncode == 1:
                return "error", error.group(0)
            return "crash", f"exit {proc.returncode}: {out.strip()[-300:]}"
        if error:
            return "crash", "ERROR printed but exit 0: " + error.group(0)
        if not os.path.exists(dump):
            return "crash", "exit 0 without the final dump"
        finite, row = _finite_dump(dump)
        if not finite:
            return "nonfinite", "state: " + row
        row = _nonfinite_thermo(out)
        if row:
            return "nonfinite", "thermo: " + row
        return "ok", ""


BAD = ("crash", "sanitizer", "hang", "nonfinite")
NOTED = ("host",)


def key(name, k, line):
    """How a mutant is named in the lists of known failures and regressions: base input,
    index of the mutated line, the line."""
    return f"{name}:{k}: {line}"


def parse_key(text):
    name, k, line = text.split(":", 2)
    return name, int(k), line[1:]
