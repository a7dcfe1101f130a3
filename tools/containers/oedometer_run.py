#!/usr/bin/env python3
"""One oedometer test (examples/oedometer): make a deposit, load it by a servo piston in steps
of vertical stress and unload it; write the table and the stress-strain figure.

    ./ellipsoid-dep python tools/containers/oedometer_run.py [--N 1000] [--eta 1 --zeta 1 --dr 0]
        [--seed S] [--np 2] [--out DIR] [--loads 0.5 1 2 4 2 1 0.5] [--var NAME VALUE ...]

1. The deposit: tools/deposit/deposit_run.py with in.deposit's protocol and `-var save 1` (it then
   writes deposit.restart at rest) into DIR/deposit; a deposit already there is reused if its
   settings.json has the asked N, eta, zeta, dr and seed (and the hertz law), else refused.
2. The loading: examples/oedometer/in.oedometer reads it and loads it by the piston; each step
   ends at rest (the input states the criterion) with a LEVEL line.
3. DIR/oedometer.csv, one row per step, and DIR/stress_strain.png. The strain is
   eps_zz = (H0 - z_p) / H0, z_p the piston's height at rest above the ground and H0 its
   height under the first (smallest) load; the constrained modulus of a step is
   M = (sigma_p - sigma_p,prev) / (eps_zz - eps_zz,prev) with the piston's stress sigma_p (the
   weight adds the same stress before and after, so the increment of sigma_zz is the piston's
   everywhere); K0 = (sigma_xx + sigma_yy) / (2 sigma_zz) of the slab, as in.deposit's
   packing.dat.
"""
import argparse
import csv
import os
import re
import shlex
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _paths  # noqa: E402,F401  (tools/_paths.py: the topic folders on sys.path)
import deposit_run  # noqa: E402

INPUT = os.path.join(deposit_run.ROOT, "examples", "oedometer", "in.oedometer")
LOADS = [0.5, 1, 2, 4, 2, 1, 0.5]
LEVEL = re.compile(r"^LEVEL (\d+) (.*)$")
COLUMNS = ["N", "eta", "zeta", "delta_r", "seed", "level", "phase", "load", "at_rest", "step",
           "piston", "eps_zz", "sigma_piston", "sigma_xx", "sigma_yy", "sigma_zz", "K0", "M",
           "phi_slab", "phi_mean", "sigma_w", "gain", "gamma"]


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--N", type=int, default=1000, help="particles (default 1000)")
    ap.add_argument("--eta", type=float, default=1.0, help="a/b (default 1)")
    ap.add_argument("--zeta", type=float, default=1.0, help="b/c (default 1)")
    ap.add_argument("--dr", type=float, default=0.0, help="size polydispersity (default 0)")
    ap.add_argument("--seed", type=int, default=4928, help="the pour's seed (default 4928)")
    ap.add_argument("--np", type=int, default=2, help="MPI ranks (default 2)")
    ap.add_argument("--out", required=True, help="run folder")
    ap.add_argument("--loads", type=float, nargs="+", default=LOADS,
                    help="the piston's stress at each step in units of the deposit's weight "
                         "stress (default %s)" % " ".join("%g" % x for x in LOADS))
    ap.add_argument("--var", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                    help="another variable of in.oedometer (gfrac, vmax, chunk, ftol, ...)")
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    if any(x <= 0 for x in args.loads):
        ap.error("--loads: every stress must be > 0 (the piston pushes)")
    for option, value in (("--N", args.N), ("--np", args.np)):
        if value < 1:
            sys.exit("oedometer_run: %s %d: must be >= 1" % (option, value))
    return args


def deposit_mismatch(args, settings):
    """None, or how the deposit's stored settings differ from this run's request"""
    if settings is None:
        return "it has no settings.json: not a deposit of tools/deposit/deposit_run.py"
    asked = {"N": args.N, "eta": args.eta, "zeta": args.zeta, "dr": args.dr, "seed": args.seed,
             "normal": "hertz"}
    stored = dict(settings, normal=deposit_run.normal_words(settings)[0])
    differ = ["%s %s (asked %s)" % (k, stored.get(k), v) for k, v in asked.items()
              if stored.get(k) != v]
    return "it was made with " + ", ".join(differ) if differ else None


def make_deposit(args, folder):
    """deposit.restart of in.deposit's protocol in folder (reused when it is of the same
    N, shape, size spread and seed; another deposit there is refused)"""
    restart = os.path.join(folder, "deposit.restart")
    if os.path.exists(restart):
        why = deposit_mismatch(args, deposit_run.read_settings(folder))
        if why:
            sys.exit("oedometer_run: the deposit in %s is not the one asked for: %s (in.oedometer "
                     "loads hertz deposits); give another --out or remove it" % (folder, why))
    else:
        deposit_run.main(["--N", str(args.N), "--eta", str(args.eta), "--zeta", str(args.zeta),
                          "--dr", str(args.dr), "--seed", str(args.seed), "--np", str(args.np),
                          "--out", folder, "--var", "save", "1", "--no-image", "--no-plots",
                          "--quiet"])
    if not os.path.exists(restart):
        sys.exit("oedometer_run: the deposit in %s wrote no deposit.restart" % folder)
    return restart, deposit_run.read_settings(folder)


def run_oedometer(args, restart, settings, out):
    """in.oedometer on the deposit; its LEVEL lines as dicts"""
    cmd = [] if args.np <= 1 else ["mpirun", "-np", str(args.np)]
    cmd += [deposit_run.lmp_binary(), "-in", INPUT, "-log", os.path.join(out, "log.lammps"),
            "-nocite", "-var", "restart", restart, "-var", "tangential", settings["tangential"],
            "-var", "loads"] + ["%g" % x for x in args.loads]
    for name in ("kn", "K"):
        if name in settings["vars"]:
            cmd += ["-var", name, str(settings["vars"][name])]
    for name, value in args.var:
        cmd += ["-var", name, value]
    env = deposit_run.mpi_env()
    print("oedometer_run: " + " ".join(shlex.quote(w) for w in cmd), flush=True)
    levels = []
    with open(os.path.join(out, "screen.txt"), "w") as screen:
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                cwd=out, env=env, bufsize=1)
        for line in proc.stdout:
            screen.write(line)
            m = LEVEL.match(line)
            if m:
                words = m.group(2).split()
                level = {k: float(v) for k, v in zip(words[::2], words[1::2])}
                level["level"] = int(m.group(1))
                levels.append(level)
            if (m or line.startswith(("PROGRESS", "ERROR", "WARNING"))) and not args.quiet:
                print("  " + line.rstrip(), flush=True)
        proc.wait()
    if proc.returncode != 0 or len(levels) != len(args.loads):
        sys.exit("oedometer_run: in.oedometer failed (exit %d, %d of %d steps); see %s"
                 % (proc.returncode, len(levels), len(args.loads),
                    os.path.join(out, "screen.txt")))
    return levels


def k0(level):
    """the slab's horizontal over vertical stress, the horizontal the mean of x and y"""
    return (level["sigma_xx"] + level["sigma_yy"]) / (2 * level["sigma_zz"])


def table(args, levels):
    """the rows of oedometer.csv: strain, K0 and the modulus of each step"""
    h0 = levels[0]["piston"]
    top = max(range(len(levels)), key=lambda i: levels[i]["target"])
    rows = []
    for i, lv in enumerate(levels):
        eps = (h0 - lv["piston"]) / h0
        row = {"N": args.N, "eta": args.eta, "zeta": args.zeta, "delta_r": args.dr,
               "seed": args.seed, "level": lv["level"], "load": lv["load"],
               "phase": "load" if i <= top else "unload", "at_rest": int(lv["at_rest"]),
               "step": int(lv["step"]), "piston": lv["piston"], "eps_zz": eps,
               "sigma_piston": lv["sigma_piston"], "sigma_xx": lv["sigma_xx"],
               "sigma_yy": lv["sigma_yy"], "sigma_zz": lv["sigma_zz"],
               "K0": k0(lv), "M": "",
               "phi_slab": lv["phi"], "phi_mean": lv["sigma_w"] / lv["piston"],
               "sigma_w": lv["sigma_w"], "gain": lv["gain"], "gamma": lv["gamma"]}
        if rows:
            deps = eps - rows[-1]["eps_zz"]
            row["M"] = (lv["sigma_piston"] - rows[-1]["sigma_piston"]) / deps if deps else ""
        rows.append(row)
    return rows


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.8g" % v if isinstance(v, float) else v) for k, v in r.items()})


def plot(path, rows, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sw = rows[0]["sigma_w"]
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(9, 3.8))
    for phase, mark in (("load", "o-"), ("unload", "s--")):
        # the unloading branch starts at the largest load
        sel = [r for r in rows if r["phase"] == phase]
        if phase == "unload":
            sel = [max((r for r in rows if r["phase"] == "load"), key=lambda r: r["load"])] + sel
        ax.plot([100 * r["eps_zz"] for r in sel], [r["sigma_piston"] / sw for r in sel], mark,
                label=phase + "ing")
        bx.plot([r["sigma_piston"] / sw for r in sel], [r["K0"] for r in sel], mark,
                label=phase + "ing")
    ax.set_xlabel(r"$\varepsilon_{zz}$ (%)")
    ax.set_ylabel(r"$\sigma_{zz}$ on the piston / $\sigma_w$")
    bx.set_xlabel(r"$\sigma_{zz}$ on the piston / $\sigma_w$")
    bx.set_ylabel(r"$K_0 = (\sigma_{xx}+\sigma_{yy})/2\sigma_{zz}$ (slab)")
    for a in (ax, bx):
        a.legend()
        a.grid(alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None):
    args = parse_args(argv)
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    restart, settings = make_deposit(args, os.path.join(out, "deposit"))
    levels = run_oedometer(args, restart, settings, out)
    rows = table(args, levels)
    write_csv(os.path.join(out, "oedometer.csv"), rows)
    title = r"$\eta$=%g $\zeta$=%g $\delta_r$=%g N=%d seed %d" % (
        args.eta, args.zeta, args.dr, args.N, args.seed)
    plot(os.path.join(out, "stress_strain.png"), rows, title)
    print("oedometer_run: sigma_w %.4g; wrote %s/oedometer.csv and stress_strain.png"
          % (rows[0]["sigma_w"], out))
    for r in rows:
        print("  %-6s load %4g sigma_w  eps_zz %.3e  sigma_p %.4g  K0 %.3f  M %s  at_rest %d"
              % (r["phase"], r["load"], r["eps_zz"], r["sigma_piston"], r["K0"],
                 "%.4g" % r["M"] if r["M"] != "" else "-", r["at_rest"]))
    return rows


if __name__ == "__main__":
    main()
