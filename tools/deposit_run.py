#!/usr/bin/env python3
"""Run the default ELLIPSOID_DEP deposit (examples/deposit/in.deposit) and post-process it.

    ./ellipsoid-dep run [--N 1000] [--np 2] [--out DIR] [--eta 1.4 --zeta 1.8 --dr 0.6]
                        [--seed S] [--ketol 1e-4] [--no-image] [--input FILE] [--quiet]

Runs `mpirun -np NP $LAMMPS_BUILD/lmp -in in.deposit -var ...` in the run folder
(default runs/deposit-<timestamp>/), streams its progress (inserted particles, kinetic energy per
particle against the rest criterion, wall time and an estimate of the time left from the
decay rate of the kinetic energy), then plots the histograms to PNG (matplotlib, Agg), prints
the volume fraction and coordination number and lists the files written.
The entry script sets LAMMPS_BUILD, LAMMPS_PLUGIN_PATH, LD_LIBRARY_PATH and the OpenMPI
run-as-root variables.
"""
import argparse
import datetime
import glob
import math
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.environ.get("ELLIPSOID_DEP_ROOT",
                      os.path.abspath(os.path.join(os.path.dirname(__file__), "..")))
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


def lammps_command(args, out):
    cmd = []
    if args.np > 1:
        cmd = ["mpirun", "-np", str(args.np)]
    cmd += [lmp_binary(), "-in", os.path.abspath(args.input), "-log", os.path.join(out, "log.lammps"),
            "-nocite", "-var", "N", str(args.N), "-var", "eta", str(args.eta), "-var", "zeta",
            str(args.zeta), "-var", "dr", str(args.dr), "-var", "seed", str(args.seed),
            "-var", "ketol", str(args.ketol), "-var", "out", out,
            "-var", "image", "0" if args.no_image else "1", "-var", "tangential", args.tangential]
    return cmd


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


def run_lammps(args, out):
    cmd = lammps_command(args, out)
    env = dict(os.environ)
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    env.setdefault("OMPI_MCA_rmaps_base_oversubscribe", "1")
    print("deposit_run: " + " ".join(cmd), flush=True)
    screen = open(os.path.join(out, "screen.txt"), "w")
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
        sys.exit("deposit_run: LAMMPS failed (exit %d); log in %s" % (proc.returncode, out))
    return result, wall


def read_histo(path):
    """fix ave/time mode vector file: last block -> (theta, P, fraction) lists"""
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
                block.append([float(x) for x in w[1:4]])
    if not rows or not rows[-1]:
        raise ValueError("no histogram in %s" % path)
    b = rows[-1]
    return [r[0] for r in b], [r[1] for r in b], [r[2] for r in b]


def read_packing(path):
    d = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            k, v = line.split(None, 1)
            try:
                d[k] = float(v)
            except ValueError:
                d[k] = v.strip()
    return d


def plot_histograms(out, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    written = []
    for name, xlabel, what in (
            ("contact_histo", r"$\theta$ (contact normal vs +z)", "contact normals"),
            ("orient_histo", r"$\theta$ (long axis a vs +z)", "long axes")):
        th, p, frac = read_histo(os.path.join(out, name + ".dat"))
        fig, ax = plt.subplots(figsize=(5.0, 3.6))
        ax.plot(th, p, "o-", label="deposit")
        ax.axhline(1.0 / (4.0 * math.pi), color="gray", ls="--", label=r"isotropic $1/4\pi$")
        ax.set_xlim(0, math.pi)
        ax.set_xticks([0, math.pi / 4, math.pi / 2, 3 * math.pi / 4, math.pi])
        ax.set_xticklabels(["0", r"$\pi/4$", r"$\pi/2$", r"$3\pi/4$", r"$\pi$"])
        ax.set_xlabel(xlabel)
        ax.set_ylabel(r"$P(\Omega(\theta))$")
        ax.set_title("%s: %s" % (what, title), fontsize=9)
        ax.legend(fontsize=8)
        fig.tight_layout()
        png = os.path.join(out, name + ".png")
        fig.savefig(png, dpi=120)
        plt.close(fig)
        written.append(png)
    return written


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--np", type=int, default=int(os.environ.get("NP", 2)), help="MPI ranks (default 2)")
    ap.add_argument("--N", type=int, default=1000, help="number of particles (default 1000)")
    ap.add_argument("--out", default=None, help="run folder (default runs/deposit-<timestamp>/)")
    ap.add_argument("--eta", type=float, default=1.4)
    ap.add_argument("--zeta", type=float, default=1.8)
    ap.add_argument("--dr", type=float, default=0.6, help="size polydispersity delta_r")
    ap.add_argument("--seed", type=int, default=4928)
    ap.add_argument("--tangential", default="history 2.0e3 0.5",
                    help='tangential law words (default "history 2.0e3 0.5"; the paper\'s '
                         'viscous law: "viscous 0.5")')
    ap.add_argument("--ketol", type=float, default=1e-4,
                    help="rest criterion: KE per particle / (m g d) (default 1e-4)")
    ap.add_argument("--input", default=DEFAULT_INPUT, help="LAMMPS input (default in.deposit)")
    ap.add_argument("--no-image", action="store_true", help="skip the dump image picture")
    ap.add_argument("--no-plots", action="store_true", help="skip the matplotlib PNGs")
    ap.add_argument("--quiet", action="store_true", help="no progress lines")
    args = ap.parse_args(argv)

    out = args.out or os.path.join(os.getcwd(), "runs",
                                   "deposit-" + datetime.datetime.now().strftime("%Y%m%d-%H%M%S"))
    out = os.path.abspath(out)
    os.makedirs(out, exist_ok=True)
    result, wall = run_lammps(args, out)

    # the picture: dump image names it by step; keep a stable name too
    pics = sorted(glob.glob(os.path.join(out, "deposit-*.png")))
    if pics:
        shutil.copyfile(pics[-1], os.path.join(out, "deposit.png"))
        for p in pics:
            os.remove(p)
    pk = read_packing(os.path.join(out, "packing.dat"))
    pk["wall_seconds"] = round(wall, 2)
    pk["np"] = args.np
    with open(os.path.join(out, "packing.dat"), "a") as f:
        f.write("wall_seconds %.2f\nnp %d\n" % (wall, args.np))
    title = r"$\eta$=%g $\zeta$=%g $\delta_r$=%g N=%d" % (args.eta, args.zeta, args.dr, args.N)
    if not args.no_plots:
        plot_histograms(out, title)

    print("\ndeposit_run: N %d  eta %g  zeta %g  delta_r %g  (%d ranks, %.0f s, %d steps)"
          % (args.N, args.eta, args.zeta, args.dr, args.np, wall, int(pk.get("steps", 0))))
    print("  volume fraction phi = %.4f   (slab z in [%.3f, %.3f], %d particles)"
          % (pk["phi"], pk["zlo"], pk["zhi"], int(pk["Nslab"])))
    print("  coordination number Z = %.3f   without rattlers %.3f (%d rattlers)"
          % (pk["Z"], pk["Z_no_rattlers"], int(pk["rattlers"])))
    print("  files in %s:" % out)
    notes = {"log.lammps": "LAMMPS log", "screen.txt": "LAMMPS screen output",
             "packing.dat": "phi, Z and more as 'key value'",
             "contact_histo.dat": "contact-normal histogram (theta, P(Omega), fraction)",
             "orient_histo.dat": "long-axis histogram (theta, P(Omega), fraction)",
             "contact_histo.png": "plot", "orient_histo.png": "plot",
             "deposit.dump": "OVITO dump: semi-axes (radii) and quaternion w,i,j,k",
             "deposit.png": "picture (dump image)"}
    for name in sorted(os.listdir(out)):
        print("    %-18s %s" % (name, notes.get(name, "")))
    return pk


if __name__ == "__main__":
    main()
