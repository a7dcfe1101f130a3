#!/usr/bin/python3
"""The deposit protocol's speed against the accuracy of its results (phi and Z).

    ./ellipsoid-dep python tools/deposit/protocol_trade.py [--N 400] [--seeds 101 202 303]
                               [--jobs 2] [--only NAME ...] [--by-config] [--table-only]

Runs the default deposit (examples/deposit/in.deposit through deposit_run.py, one rank,
`nice -n 10`) for a stiff, slow reference and for variants that change ONE knob of it (normal
stiffness kn, damping K, time step, drop height zpour, insertion volume fraction fins), each
for every seed, and today's and the new defaults. A run whose log already reached its rest
criterion, or that another driver is running (its running.pid), is not run again, so the
driver resumes where it stopped and several drivers can share a grid. The rest criterion ketol
costs no runs: a log has phi and Z (thermo) and KE per particle (PROGRESS) after every chunk,
so a looser ketol is read off a run at the first chunk end where a run with that ketol would
stop. Cost: steps, and CPU seconds from LAMMPS's loop time x its "% CPU use".

Writes results/protocol_trade/protocol_trade_N<N>.csv (one row per run and ketol), prints the
table (mean +- standard error over seeds, the difference from the reference against the
reference's seed-to-seed standard deviation) as markdown and plots phi and Z against the cost
(steps) into results/protocol_trade/protocol_trade_N<N>.png. Runs go to
runs/protocol_trade/N<N>/<config>/s<seed>/. The N = 400 results and their reading:
doc/CHANGELOG.md, 2026-12-01, "Protocol".
"""
import argparse
import concurrent.futures
import csv
import math
import os
import re
import statistics
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
OUT = os.path.join(ROOT, "results", "protocol_trade")    # the CSV and the plot
RUNNER = os.path.join(ROOT, "tools", "deposit", "deposit_run.py")

# The reference: stiff (overlaps at rest ~0.6x today's), slow (dt ~1/50 of the shortest
# contact time), strict rest criterion; the pour as today.
REFERENCE = {"kn": 2.0e4, "K": 200.0, "dt": 1.5e-4, "zpour": 0.0, "fins": 0.2, "ketol": 1e-5}
# One knob off the reference per variant. kn variants keep the reference's dt / contact time
# (t_c ~ kn^(-2/5) for Hertz), so a softer spring buys larger steps. The variants stop at
# today's rest criterion 1e-4 (the ketol rows, read off the reference, show what that costs
# in accuracy): the criterion to 1e-5 is most of a run's settling time.
VARIANT_KETOL = 1e-4
VARIANTS = [
    ("dt 3e-4", {"dt": 3.0e-4}),
    ("dt 6e-4", {"dt": 6.0e-4}),
    ("fins 0.4", {"fins": 0.4}),
    ("kn 1e4", {"kn": 1.0e4, "dt": 1.5e-4 * 2.0 ** 0.4}),
    ("zpour 1", {"zpour": 1.0}),    # the cloud starts 1 d above the ground: a lower drop
    ("K 400", {"K": 400.0}),
]
# looser rest criteria read off the reference's runs
KETOLS = [3e-5, 1e-4, 3e-4, 1e-3]

PROGRESS = re.compile(r"^PROGRESS step (\d+) inserted (\S+) of (\d+) KE/particle (\S+) target")
LOOP = re.compile(r"^Loop time of (\S+) on \d+ procs for (\d+) steps")
CPU_USE = re.compile(r"^(\S+)% CPU use with")


# The defaults before and after this trade, side by side with the reference (dt 0: in.deposit
# derives it, dtfrac x the Hertz contact time of its lightest pair at the drop's speed).
DEFAULTS = [
    ("before: dt 3e-4, ketol 1e-4",
     {"kn": 1.0e4, "K": 200.0, "dt": 3.0e-4, "zpour": 0.0, "fins": 0.2, "ketol": 1e-4}),
    ("after: dtfrac 0.03, ketol 1e-3",
     {"kn": 1.0e4, "K": 200.0, "dt": 0, "dtfrac": 0.03, "zpour": 0.0, "fins": 0.2,
      "ketol": 1e-3}),
    ("after: dtfrac 0.075, ketol 1e-3",
     {"kn": 1.0e4, "K": 200.0, "dt": 0, "dtfrac": 0.075, "zpour": 0.0, "fins": 0.2,
      "ketol": 1e-3}),
]


# looser rest criteria read off runs: the reference's, and today's default at the new one
READ_OFF = {"reference": KETOLS, DEFAULTS[0][0]: [1e-3]}


def configs():
    out = [("reference", dict(REFERENCE))]
    for name, change in VARIANTS:
        c = dict(REFERENCE, ketol=VARIANT_KETOL)
        c.update(change)
        out.append((name, c))
    return out + DEFAULTS


def folder_name(name):
    return re.sub(r"[^A-Za-z0-9.+-]+", "_", name)


def run_folder(runs, name, seed):
    return os.path.join(runs, folder_name(name), "s%d" % seed)


def finished(out, ketol):
    """The run is at rest by ketol: its log has a chunk end with every particle in and the
    kinetic energy per particle below ketol (a run stopped later still counts)."""
    if not os.path.exists(os.path.join(out, "log.lammps")):
        return False
    return any(inserted and ke < ketol for _, ke, inserted, _, _, _ in chunk_ends(out))


def running(out):
    """A run another driver started and is still running (its folder's pid file)."""
    try:
        os.kill(int(open(os.path.join(out, "running.pid")).read()), 0)
        return True
    except (OSError, ValueError):
        return False


def run_one(out, n, seed, config):
    """One deposit; returns its CPU seconds (None: another driver did or does it)."""
    if running(out) or finished(out, config["ketol"]):
        return None
    os.makedirs(out, exist_ok=True)
    cmd = ["nice", "-n", "10", sys.executable, RUNNER, "--np", "1", "--N", str(n),
           "--seed", str(seed), "--out", out, "--no-image", "--no-plots", "--quiet",
           "--ketol", repr(config["ketol"])]
    for name in ("kn", "K", "dt", "dtfrac", "zpour", "fins"):
        if name in config:
            cmd += ["--var", name, repr(config[name])]
    with open(os.path.join(out, "driver.txt"), "w") as log:
        proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT)
        with open(os.path.join(out, "running.pid"), "w") as f:
            f.write(str(proc.pid))
        status = proc.wait()
    os.remove(os.path.join(out, "running.pid"))
    if status != 0:
        raise RuntimeError("run failed (status %d): see %s/driver.txt" % (status, out))
    return chunk_ends(out)[-1][5]


def read_packing(out):
    d = {}
    for line in open(os.path.join(out, "packing.dat")):
        w = line.split()
        if len(w) == 2 and not line.startswith("#"):
            try:
                d[w[0]] = float(w[1])
            except ValueError:
                pass
    return d


def chunk_ends(out):
    """Per chunk end: (step, KE per particle, all inserted, phi, Z, CPU seconds so far). The
    CPU time is LAMMPS's: loop time x its "% CPU use" (the machine is shared, wall time is not
    the cost)."""
    thermo, rows, cpu, loop = {}, [], 0.0, 0.0
    header = None
    for line in open(os.path.join(out, "log.lammps")):
        w = line.split()
        if w[:1] == ["Step"]:
            header = w if "c_pack[1]" in w else None    # not the time-step probe's run
            continue
        m = LOOP.match(line)
        if m:
            loop = float(m.group(1))
            header = None
            continue
        m = CPU_USE.match(line)
        if m:
            cpu += loop * float(m.group(1)) / 100.0
            continue
        if header and len(w) == len(header) and w[0].isdigit():
            thermo[int(w[0])] = (float(w[header.index("c_pack[1]")]),
                                 float(w[header.index("c_pack[3]")]))
            continue
        m = PROGRESS.match(line)
        if m:
            step = int(m.group(1))
            phi, z = thermo[step]
            rows.append((step, float(m.group(4)), float(m.group(2)) >= int(m.group(3)), phi, z,
                         cpu))
    return rows


def run_dt(out, config):
    """The run's time step: as printed by in.deposit (derived when dt is 0), else as given."""
    m = re.search(r"^ELLIPSOID_DEP deposit: .*; dt (\S+);", open(os.path.join(out, "log.lammps")).read(),
                  re.M)
    return float(m.group(1)) if m else config["dt"]


def results_of(out, config, ketols):
    """Rows (ketol, steps, CPU s, phi, Z) of one finished run: its own ketol from packing.dat,
    the looser ones from its chunk ends."""
    ends = chunk_ends(out)
    rows = []
    for ketol in [config["ketol"]] + ketols:
        stop = next(e for e in ends if e[2] and e[1] < ketol)
        rows.append((ketol, stop[0], stop[5], stop[3], stop[4]))
    # a run that ended there has its result in packing.dat: the two reads must agree
    packing = os.path.join(out, "packing.dat")
    if os.path.exists(packing):
        pk = read_packing(out)
        step, phi, z = rows[0][1], rows[0][3], rows[0][4]
        if int(pk["steps"]) == step and (abs(phi - pk["phi"]) > 1e-4 or abs(z - pk["Z"]) > 1e-3):
            raise RuntimeError("%s: log and packing.dat disagree (%s vs %s)" % (out, rows[0], pk))
    return rows


def mean_se(values):
    m = statistics.fmean(values)
    se = statistics.stdev(values) / math.sqrt(len(values)) if len(values) > 1 else float("nan")
    return m, se


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--N", type=int, default=400)
    ap.add_argument("--seeds", type=int, nargs="+", default=[101, 202, 303])
    ap.add_argument("--jobs", type=int, default=2, help="runs at once (default 2)")
    ap.add_argument("--only", nargs="+", help="run only these configurations")
    ap.add_argument("--by-config", action="store_true",
                    help="every seed of a configuration before the next one")
    ap.add_argument("--table-only", action="store_true", help="no runs; tabulate what is done")
    ap.add_argument("--runs", default=None, help="runs folder (default runs/protocol_trade/N<N>)")
    args = ap.parse_args()
    runs = args.runs or os.path.join(ROOT, "runs", "protocol_trade", "N%d" % args.N)
    grid = configs()

    if not args.table_only:
        todo = [(name, c, s) for name, c in grid for s in args.seeds
                if (not args.only or name in args.only)
                and not finished(run_folder(runs, name, s), c["ketol"])
                and not running(run_folder(runs, name, s))]
        if not args.by_config:    # seeds outermost: every configuration gets a first seed
            todo.sort(key=lambda t: args.seeds.index(t[2]))
        elif args.only:           # in the order of --only
            todo.sort(key=lambda t: args.only.index(t[0]))
        print("protocol_trade: %d runs to do in %s" % (len(todo), runs), flush=True)
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            futures = {pool.submit(run_one, run_folder(runs, name, s), args.N, s, c): (name, s)
                       for name, c, s in todo}
            for f in concurrent.futures.as_completed(futures):
                name, s = futures[f]
                cpu = f.result()
                if cpu is not None:
                    print("  done %-10s seed %d: %.0f CPU s" % (name, s, cpu), flush=True)

    table(args, runs, grid)


def table(args, runs, grid):
    per_run = []    # (config, knob value, ketol, seed, dt, steps, cpu, phi, Z)
    for name, c in grid:
        for s in args.seeds:
            out = run_folder(runs, name, s)
            if not finished(out, c["ketol"]):
                continue
            for ketol, steps, cpu, phi, z in results_of(out, c, READ_OFF.get(name, [])):
                label = name if ketol == c["ketol"] else \
                    "ketol %g" % ketol if name == "reference" else "%s, read at ketol %g" % (
                        name, ketol)
                per_run.append((label, ketol, s, run_dt(out, c), c["kn"], c["K"], c["zpour"],
                                c["fins"], int(steps), cpu, phi, z))
    os.makedirs(OUT, exist_ok=True)
    csv_path = os.path.join(OUT, "protocol_trade_N%d.csv" % args.N)
    with open(csv_path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["config", "ketol", "seed", "dt", "kn", "K", "zpour", "fins", "steps",
                    "cpu_seconds", "phi", "Z"])
        for r in per_run:
            w.writerow(list(r[:9]) + ["%.1f" % r[9], "%.6f" % r[10], "%.6f" % r[11]])

    labels = list(dict.fromkeys(r[0] for r in per_run))
    ref = [r for r in per_run if r[0] == "reference"]
    if len(ref) < 2:
        print("protocol_trade: fewer than 2 reference seeds done; no table yet")
        return
    sd_phi = statistics.stdev(r[10] for r in ref)
    sd_z = statistics.stdev(r[11] for r in ref)
    phi_ref, z_ref = statistics.fmean(r[10] for r in ref), statistics.fmean(r[11] for r in ref)
    steps_ref = statistics.fmean(r[8] for r in ref)
    print("\nN = %d, seeds %s; reference seed-to-seed SD: phi %.4f, Z %.3f\n"
          % (args.N, " ".join(map(str, args.seeds)), sd_phi, sd_z))
    print("| configuration | dt | seeds | steps | steps / reference | CPU s | phi | Z "
          "| phi - ref | Z - ref | within ref SD |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    summary = []
    for label in labels:
        rows = [r for r in per_run if r[0] == label]
        steps = statistics.fmean(r[8] for r in rows)
        cpu = statistics.fmean(r[9] for r in rows)
        phi, phi_se = mean_se([r[10] for r in rows])
        z, z_se = mean_se([r[11] for r in rows])
        dphi, dz = phi - phi_ref, z - z_ref
        ok = abs(dphi) <= sd_phi and abs(dz) <= sd_z
        summary.append((label, steps, phi, phi_se, z, z_se))
        print("| %s | %.3g | %d | %.0f | %.2f | %.0f | %.4f +- %.4f | %.3f +- %.3f | %+.4f | %+.3f "
              "| %s |" % (label, rows[0][3], len(rows), steps, steps / steps_ref, cpu, phi,
                          phi_se, z, z_se, dphi, dz,
                          "-" if label == "reference" else ("yes" if ok else "**no**")))
    png_path = plot(args, summary, phi_ref, z_ref, sd_phi, sd_z)
    print("\nwrote %s and %s" % (os.path.relpath(csv_path, ROOT), os.path.relpath(png_path, ROOT)))


def plot(args, summary, phi_ref, z_ref, sd_phi, sd_z):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, (k, ref, sd, what) in zip(axes, ((2, phi_ref, sd_phi, r"$\phi$"),
                                             (4, z_ref, sd_z, "Z"))):
        ax.axhspan(ref - sd, ref + sd, color="0.85", label="reference +- seed SD")
        for row in summary:
            ax.errorbar(row[1], row[k], yerr=row[k + 1], fmt="o", capsize=3)
            ax.annotate(row[0], (row[1], row[k]), fontsize=7, xytext=(4, 3),
                        textcoords="offset points")
        ax.set_xscale("log")
        ax.set_xlabel("steps to rest (mean over seeds)")
        ax.set_ylabel(what + " (mean +- s.e. over seeds)")
        ax.set_title("%s against cost, N = %d" % (what, args.N), fontsize=10)
        ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    png_path = os.path.join(OUT, "protocol_trade_N%d.png" % args.N)
    fig.savefig(png_path, dpi=110)
    plt.close(fig)
    return png_path


if __name__ == "__main__":
    main()
