#!/usr/bin/env python3
"""Run the default ELLIPSOID_DEP deposit (examples/deposit/in.deposit) and post-process it.

    ./ellipsoid-dep run [--N 1000] [--np 2] [--out DIR] [--eta 1.4 --zeta 1.8 --dr 0.6]
                        [--seed S] [--ketol 1e-3] [--checkpoint-every 5000] [--no-image]
                        [--normal "hertz/material E nu e"] [--input FILE] [--quiet]
    ./ellipsoid-dep run --resume DIR          # continue an interrupted run from its checkpoint

Runs `mpirun -np NP $LAMMPS_BUILD/lmp -in in.deposit -var ...` in the run folder
(default runs/deposit-<timestamp>/), streams its progress (inserted particles, kinetic energy per
particle against the rest criterion, wall time and an estimate of the time left from the
decay rate of the kinetic energy), then plots the histograms to PNG (matplotlib, Agg), prints
the volume fraction and coordination number and lists the files written. A deposit too
shallow for its measuring slab is refused before it runs, with the smallest N for the shape
(deposit_depth.py), and fails if its measured slab is thinner than slabmin (packing.dat
says slab_ok 0); --var slabmin 0 asks for no check (an empty slab still says slab_ok 0).

Checkpoints: every --checkpoint-every steps LAMMPS writes a restart file, alternately
checkpoint.a and checkpoint.b in the run folder, so a kill while one is being written leaves
the other intact. The run's settings are stored in settings.json; --resume DIR continues from
the newer complete checkpoint with those settings, records `resumed_from STEP` in packing.dat
and counts the earlier segments in its wall_seconds (deposit_checkpoint.py); the checkpoints
are removed once the deposit is finished.
The entry script sets LAMMPS_BUILD, LAMMPS_PLUGIN_PATH, LD_LIBRARY_PATH and the OpenMPI
run-as-root variables.
"""
import argparse
import datetime
import glob
import json
import math
import os
import re
import shlex
import subprocess
import sys
import time

import deposit_report
from deposit_checkpoint import (CHECKPOINTS, checkpoint_step, earlier_segments_seconds,  # noqa
                                 newest_checkpoint, resume_log, segment_logs)
from deposit_depth import too_shallow

ROOT = os.environ.get("ELLIPSOID_DEP_ROOT",
                      os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
DEFAULT_INPUT = os.path.join(ROOT, "examples", "deposit", "in.deposit")

PROGRESS = re.compile(r"^PROGRESS step (\d+) inserted (\S+) of (\d+) KE/particle (\S+) target (\S+)")


def lmp_binary():
    build = os.environ.get("LAMMPS_BUILD")
    if build and os.path.exists(os.path.join(build, "lmp")):
        return os.path.join(build, "lmp")
    exe = os.environ.get("ELLIPSOID_DEP_LMP")
    if exe and os.path.exists(exe):
        return exe
    sys.exit("deposit_run: LAMMPS not found: run through ./ellipsoid-dep run (it sets LAMMPS_BUILD)")


def lammps_command(settings, out, resume_from=None, log_name="log.lammps"):
    cmd = []
    if settings["np"] > 1:
        cmd = [w.replace("{np}", str(settings["np"])) for w in shlex.split(settings["launcher"])]
    cmd += [lmp_binary(), "-in", settings["input"], "-log", os.path.join(out, log_name),
            "-nocite"]
    variables = {"N": settings["N"], "eta": settings["eta"], "zeta": settings["zeta"],
                 "dr": settings["dr"], "seed": settings["seed"], "ketol": settings["ketol"],
                 "out": out, "image": 1 if settings["image"] else 0,
                 "tangential": settings["tangential"],
                 "checkpoint": settings["checkpoint_every"]}
    normal, material = normal_words(settings)
    if normal != "hertz":    # the default law's words stay in.deposit's (kn and K)
        variables.update(normal=normal, material=material)
    variables.update(settings["vars"])
    if resume_from:
        variables["resume"] = resume_from
    for name, value in variables.items():
        cmd += ["-var", name, str(value)]
    return cmd


def normal_words(settings):
    """the normal law as in.deposit's normal and material variables: "hertz" (kn and K of
    --var) or "hertz/material NAME" or "hertz/material E nu e"
    (doc/pair_granular_ellipsoid.rst)"""
    words = settings.get("normal", DEFAULTS["normal"]).split()
    return words[0], " ".join(words[1:])


class Eta:
    """Estimate of the time left: while pouring, from the inserted fraction; once all are in,
    from the exponential decay rate of the kinetic energy towards the rest criterion."""

    def __init__(self):
        self.t0 = time.time()
        self.hist = []    # (wall, log KE)

    def update(self, inserted, n, ke, target):
        now = time.time()
        el = now - self.t0
        if inserted < n:
            return el, None
        if ke <= 0:
            return el, 0.0
        self.hist.append((now, math.log(ke)))
        self.hist = self.hist[-12:]
        if len(self.hist) < 4:
            return el, None
        (ta, la), (tb, lb) = self.hist[0], self.hist[-1]
        rate = (la - lb) / max(tb - ta, 1e-9)    # decades of e per second
        if rate <= 0:
            return el, None
        return el, max(0.0, (math.log(ke) - math.log(target)) / rate)


def mpi_env():
    """the environment for mpirun, as the entry script sets it: Open MPI may run as root
    (containers) and oversubscribe the cores (a value the caller set is kept)"""
    env = dict(os.environ)
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    env.setdefault("OMPI_MCA_rmaps_base_oversubscribe", "1")
    return env


def run_lammps(args, settings, out, resume_from=None, log_name="log.lammps"):
    cmd = lammps_command(settings, out, resume_from, log_name)
    env = mpi_env()
    print("deposit_run: " + " ".join(cmd), flush=True)
    screen = open(os.path.join(out, "screen.txt"), "w" if resume_from is None else "a")
    eta = Eta()
    result = None
    t0 = time.time()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            cwd=out, env=env, bufsize=1)
    for line in proc.stdout:
        screen.write(line)
        m = PROGRESS.match(line)
        if m:
            step, ins, n, ke, target = (int(m.group(1)), float(m.group(2)), int(m.group(3)),
                                        float(m.group(4)), float(m.group(5)))
            el, left = eta.update(ins, n, ke, target)
            if not args.quiet:
                phase = "pouring" if ins < n else "settling"
                left_s = "?" if left is None else "%.0f s" % left
                print("  %-8s step %8d  inserted %5d/%d  KE/particle %.2e (rest < %.0e)  "
                      "elapsed %5.0f s  left ~%s" % (phase, step, ins, n, ke, target, el, left_s),
                      flush=True)
        elif line.startswith("RESULT") or line.startswith("ELLIPSOID_DEP") or \
                line.startswith("ERROR") or "WARNING" in line:
            if line.startswith("RESULT"):
                result = line.strip()
            if not args.quiet or line.startswith("ERROR"):
                print("  " + line.rstrip(), flush=True)
    proc.wait()
    screen.close()
    wall = time.time() - t0
    if proc.returncode != 0:
        tail = open(os.path.join(out, "screen.txt")).read().splitlines()[-25:]
        print("\n".join(tail))
        sys.exit("deposit_run: LAMMPS failed (exit %d); log in %s" % (proc.returncode, out)
                 + ("; continue with --resume %s" % out if newest_checkpoint(out)[0] else ""))
    return result, wall


def read_histo(path, columns=3):
    """fix ave/time mode vector file: its last block's first `columns` value columns as lists
    (e.g. theta, P, fraction)"""
    rows, block = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            w = line.split()
            if len(w) == 2:    # "step nrows" opens a block
                block = []
                rows.append(block)
            else:
                block.append([float(x) for x in w[1:1 + columns]])
    if not rows or not rows[-1]:
        raise ValueError("no histogram in %s" % path)
    b = rows[-1]
    return tuple([r[k] for r in b] for k in range(columns))


def read_packing(path):
    d = {}
    with open(path) as f:
        for number, line in enumerate(f, 1):
            if line.startswith("#") or not line.strip():
                continue
            if len(line.split(None, 1)) != 2:
                raise ValueError("%s line %d: not a 'key value' line (a truncated file?)"
                                 % (path, number))
            k, v = line.split(None, 1)
            try:
                d[k] = float(v)
            except ValueError:
                d[k] = v.strip()
    return d


# what a run is: stored in its folder, so that --resume continues the same deposit
DEFAULTS = {"N": 1000, "eta": 1.4, "zeta": 1.8, "dr": 0.6, "seed": 4928,
            "tangential": "history 2.0e3 0.5", "normal": "hertz", "ketol": 1e-3, "input": DEFAULT_INPUT,
            "checkpoint_every": 5000, "image": True, "vars": {}}
SETTINGS_FILE = "settings.json"


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ranks = os.environ.get("NP", "2")
    if not ranks.isdigit():
        sys.exit("deposit_run: NP=%s: the number of MPI ranks must be a whole number" % ranks)
    ap.add_argument("--np", type=int, default=int(ranks), help="MPI ranks (default NP or 2)")
    ap.add_argument("--launcher", default="mpirun -np {np}",
                    help='MPI launcher when np > 1, {np} = ranks (default "mpirun -np {np}"; '
                         'on Slurm e.g. "srun -n {np}")')
    ap.add_argument("--N", type=int, help="number of particles (default 1000)")
    ap.add_argument("--out", default=None, help="run folder (default runs/deposit-<timestamp>/)")
    ap.add_argument("--eta", type=float, help="a/b (default 1.4)")
    ap.add_argument("--zeta", type=float, help="b/c (default 1.8)")
    ap.add_argument("--dr", type=float, help="size polydispersity delta_r (default 0.6)")
    ap.add_argument("--seed", type=int, help="random seed of the pour (default 4928)")
    ap.add_argument("--tangential",
                    help='tangential law words (default "history 2.0e3 0.5"; the paper\'s '
                         'viscous law: "viscous 0.5")')
    ap.add_argument("--normal",
                    help='normal law words (default "hertz", its kn and K by --var kn/K; or '
                         '"hertz/material E nu e" in LJ units, e.g. "hertz/material 3e4 0.3 '
                         '0.5"; a material NAME of potentials/ellipsoid_dep.materials holds SI '
                         'values, which LJ units refuse)')
    ap.add_argument("--ketol", type=float,
                    help="rest criterion: KE per particle / (m g d) (default 1e-3)")
    ap.add_argument("--input", help="LAMMPS input (default in.deposit)")
    ap.add_argument("--checkpoint-every", type=int, dest="checkpoint_every", metavar="STEPS",
                    help="steps between two restart checkpoints, 0 = none (default 5000; "
                         "a multiple of the input's chunk of 1000 steps keeps the rest checks "
                         "of a resumed run on the same steps)")
    ap.add_argument("--var", nargs=2, action="append", metavar=("NAME", "VALUE"),
                    help="any other variable of the input, e.g. --var dt 2e-4 --var fins 0.3 "
                         "(repeatable; stored with the run's settings)")
    ap.add_argument("--no-image", dest="image", action="store_const", const=False,
                    help="skip the dump image picture")
    ap.add_argument("--resume", metavar="DIR",
                    help="continue the interrupted run in DIR from its newer complete "
                         "checkpoint, with the settings stored there")
    ap.add_argument("--continue", dest="cont", action="store_true",
                    help="with --out DIR: resume DIR's run if it holds a checkpoint of a run "
                         "with these settings, else start afresh (for workflows)")
    ap.add_argument("--no-plots", action="store_true", help="skip the matplotlib PNGs")
    ap.add_argument("--quiet", action="store_true", help="no progress lines")
    args = ap.parse_args(argv)
    if args.resume and (args.out or args.cont):
        ap.error("--resume DIR is the run folder: give neither --out nor --continue")
    if args.cont and not args.out:
        ap.error("--continue needs --out DIR")
    law = (args.normal or "hertz").split()
    if not (law == ["hertz"] or (law[:1] == ["hertz/material"] and len(law) > 1)):
        sys.exit('deposit_run: --normal "%s": must be "hertz" (kn and K by --var) or '
                 '"hertz/material" with its words' % args.normal)
    for option, value, valid, rule in (
            ("--np", args.np, args.np >= 1, ">= 1"),
            ("--N", args.N, args.N is None or args.N >= 1, ">= 1"),
            ("--eta", args.eta, args.eta is None or args.eta >= 1, "a/b >= 1"),
            ("--zeta", args.zeta, args.zeta is None or args.zeta >= 1, "b/c >= 1"),
            ("--dr", args.dr, args.dr is None or 0 <= args.dr < 1, "in [0, 1)"),
            ("--seed", args.seed, args.seed is None or args.seed >= 1, ">= 1"),
            ("--ketol", args.ketol, args.ketol is None or args.ketol > 0, "> 0"),
            ("--checkpoint-every", args.checkpoint_every,
             args.checkpoint_every is None or args.checkpoint_every >= 0, ">= 0")):
        if not valid:
            sys.exit("deposit_run: %s %s: must be %s" % (option, value, rule))
    return args


def requested_settings(args):
    """Settings given on the command line, over the defaults."""
    given = {k: getattr(args, k) for k in DEFAULTS if k != "vars" and getattr(args, k) is not None}
    if args.var:
        given["vars"] = {name: value for name, value in args.var}
    settings = dict(DEFAULTS, **given)
    settings["input"] = os.path.abspath(settings["input"])
    return settings, given


def read_settings(out):
    path = os.path.join(out, SETTINGS_FILE)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        try:
            stored = json.load(f)
        except ValueError:
            sys.exit("deposit_run: %s is not readable JSON (a truncated file?)" % path)
    stored.setdefault("normal", "hertz")    # runs before it was a setting: hertz kn K
    return stored


def write_settings(out, settings):
    with open(os.path.join(out, SETTINGS_FILE), "w") as f:
        json.dump({k: settings[k] for k in DEFAULTS}, f, indent=1, sort_keys=True)
        f.write("\n")


def start_fresh(out):
    """Remove what an earlier run left that the new one would not overwrite or would count."""
    for path in [os.path.join(out, n) for n in CHECKPOINTS + ("packing.dat",)] + segment_logs(out):
        if os.path.exists(path):
            os.remove(path)


def plan(args):
    """(run folder, settings, checkpoint to resume from or None, its step); changes nothing."""
    settings, given = requested_settings(args)
    if args.resume:
        out = os.path.abspath(args.resume)
        stored = read_settings(out)
        if stored is None:
            sys.exit("deposit_run: %s has no %s: not a run folder" % (out, SETTINGS_FILE))
        changed = {k: v for k, v in given.items()
                   if (os.path.abspath(v) if k == "input" else v) != stored[k]}
        if changed:
            sys.exit("deposit_run: --resume keeps the run's settings; these differ from %s: %s"
                     % (os.path.join(out, SETTINGS_FILE), changed))
        path, step = newest_checkpoint(out)
        if path is None:
            sys.exit("deposit_run: %s holds no complete checkpoint (%s) to resume from"
                     % (out, " or ".join(CHECKPOINTS)))
        return out, dict(stored), path, step
    out = os.path.abspath(args.out or os.path.join(
        os.getcwd(), "runs", "deposit-" + datetime.datetime.now().strftime("%Y%m%d-%H%M%S")))
    if args.cont and read_settings(out) == {k: settings[k] for k in DEFAULTS}:
        path, step = newest_checkpoint(out)
        if path is not None:
            return out, settings, path, step
    return out, settings, None, None


def main(argv=None):
    args = parse_args(argv)
    out, settings, resume_from, resume_step = plan(args)
    if resume_from is None:
        try:
            shallow = too_shallow(settings)
        except ValueError as e:
            sys.exit("deposit_run: %s" % e)
        if shallow:
            sys.exit("deposit_run: " + shallow + " (--var slabmin 0 runs it without the check)")
        try:
            os.makedirs(out, exist_ok=True)
        except OSError as e:
            sys.exit("deposit_run: --out %s: cannot create the run folder (%s)"
                     % (out, e.strerror))
        start_fresh(out)
        write_settings(out, settings)
    settings.update(np=args.np, launcher=args.launcher)
    if resume_from:
        print("deposit_run: resuming %s from step %d (%s)"
              % (out, resume_step, os.path.basename(resume_from)), flush=True)
    log_name = resume_log(out, resume_step) if resume_from else "log.lammps"
    result, wall = run_lammps(args, settings, out, resume_from, log_name)
    earlier = earlier_segments_seconds(out, log_name) if resume_from else None
    for name in CHECKPOINTS:    # the deposit is finished: nothing to resume
        if os.path.exists(os.path.join(out, name)):
            os.remove(os.path.join(out, name))

    # the picture: dump image names it by step; keep a stable name, with the colour bar
    pics = sorted(glob.glob(os.path.join(out, "deposit-*.png")))
    if pics:
        from picture_colorbar import add_colorbar    # matplotlib only when there is a picture
        add_colorbar(pics[-1], os.path.join(out, "deposit.png"))
        for p in pics:
            os.remove(p)
    pk = read_packing(os.path.join(out, "packing.dat"))
    runner = {"wall_seconds": round(wall + (earlier or 0.0), 2), "np": args.np}
    if resume_from:    # no earlier_segments_seconds when their logs are gone: not counted
        runner["resumed_from"] = resume_step
        if earlier is not None:
            runner["earlier_segments_seconds"] = round(earlier, 2)
    pk.update(runner)
    with open(os.path.join(out, "packing.dat"), "a") as f:
        f.writelines("%s %s\n" % kv for kv in runner.items())
    if pk.get("slab_ok", 1) == 0 and pk.get("slabmin", 1) > 0:    # slabmin 0: no check asked
        sys.exit("deposit_run: the deposit is too shallow for its measuring slab (%.3g mean "
                 "diameters thick, slabmin %g): no phi, Z or forces; packing.dat says slab_ok 0; "
                 "run more particles" % (pk["slab_thickness"], pk["slabmin"]))
    st = settings
    title = r"$\eta$=%g $\zeta$=%g $\delta_r$=%g N=%d" % (st["eta"], st["zeta"], st["dr"], st["N"])
    if not args.no_plots:
        deposit_report.plot_run(out, title, pk, read_histo)

    deposit_report.print_summary(out, settings, pk, args.np, wall,
                                 {SETTINGS_FILE: "the run's settings (for --resume)"})
    return pk


if __name__ == "__main__":
    main()
