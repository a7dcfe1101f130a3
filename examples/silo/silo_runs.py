"""The silo study's runs (README.md): two radii, three shapes, three seeds, each one run_silo.py
process; finished runs (their run.json in results/) are skipped, so it resumes.

    nice -n 10 ./ellipsoid-dep python examples/silo/silo_runs.py [--part 1/2] [--only R5]

The results (wall.dat, stages.dat, run.json: small tables) go to results/R<R>/<shape>/seed<k>;
LAMMPS's logs to runs/silo/ (not committed). --part i/n runs every n-th run from the i-th (two
processes share the matrix).
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
RESULTS = os.path.join(HERE, "results")
SHAPES = {"spheres": (1.0, 1.0), "eta1.4_zeta1.8": (1.4, 1.8), "eta2_zeta2": (2.0, 2.0)}
# radius: stages x particles per stage (a stage about 3.3 d of fill)
SILOS = {2.5: (8, 70), 5.0: (5, 300)}
SEEDS = (101, 202, 303)


def run_dir(radius, shape, seed):
    return os.path.join(RESULTS, "R%g" % radius, shape, "seed%d" % seed)


def matrix():
    """(radius, shape, seed, run_silo.py's arguments), the narrow silo first"""
    for radius, (stages, per) in SILOS.items():
        for seed in SEEDS:
            for shape, (eta, zeta) in SHAPES.items():
                args = ["--R", "%g" % radius, "--eta", "%g" % eta, "--zeta", "%g" % zeta,
                        "--stages", str(stages), "--per", str(per), "--seed", str(seed),
                        "--out", run_dir(radius, shape, seed)]
                yield radius, shape, seed, args


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--part", default="1/1", help="i/n: every n-th run from the i-th")
    p.add_argument("--only", help="R2.5 or R5: one silo")
    a = p.parse_args()
    i, n = (int(v) for v in a.part.split("/"))
    if not 1 <= i <= n:
        p.error("--part i/n needs 1 <= i <= n")
    logs = os.path.join(ROOT, "runs", "silo")
    os.makedirs(logs, exist_ok=True)
    for k, (radius, shape, seed, args) in enumerate(matrix()):
        if k % n != i - 1 or (a.only and a.only != "R%g" % radius):
            continue
        if os.path.isfile(os.path.join(run_dir(radius, shape, seed), "run.json")):
            continue
        log = os.path.join(logs, "R%g_%s_seed%d.log" % (radius, shape, seed))
        print("run: R %g %s seed %d" % (radius, shape, seed), flush=True)
        subprocess.run([sys.executable, os.path.join(HERE, "run_silo.py"), "--log", log] + args,
                       check=True)


if __name__ == "__main__":
    main()
