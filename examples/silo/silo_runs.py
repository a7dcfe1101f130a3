"""The silo study's runs (README.md): two radii, three shapes, three seeds, each one run_silo.py
process; finished runs (their run.json in results/) are skipped, so it resumes.

    nice -n 10 ./ellipsoid-dep python examples/silo/silo_runs.py [--only R5]

The results (wall.dat, stages.dat, run.json: small tables) go to results/R<R>/<shape>/seed<k>;
LAMMPS's logs to runs/silo/ (not committed). Several of these processes share the matrix: a
run being made is claimed (runs/silo/<run>.claim holds the process id; a dead one's claim is
taken over).
"""
import argparse
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
RESULTS = os.path.join(HERE, "results")
SHAPES = {"spheres": (1.0, 1.0), "eta1.4_zeta1.8": (1.4, 1.8), "eta2_zeta2": (2.0, 2.0)}
# radius: stages x particles per stage (a stage about 3.4 d of fill): H about 8 R and 2.7 R
SILOS = {2.5: (6, 70), 5.0: (4, 300)}
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


def claim(path):
    """True if this process now makes the run of the claim file `path` (no other live one
    does)"""
    try:
        fd = os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
    except FileExistsError:
        try:
            os.kill(int(open(path).read() or 0), 0)
            return False
        except (ProcessLookupError, ValueError):
            os.remove(path)    # its process died: take the run over
            return claim(path)
    with os.fdopen(fd, "w") as f:
        f.write(str(os.getpid()))
    return True


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--only", help="R2.5 or R5: one silo")
    a = p.parse_args()
    logs = os.path.join(ROOT, "runs", "silo")
    os.makedirs(logs, exist_ok=True)
    for radius, shape, seed, args in matrix():
        if a.only and a.only != "R%g" % radius:
            continue
        name = os.path.join(logs, "R%g_%s_seed%d" % (radius, shape, seed))
        if os.path.isfile(os.path.join(run_dir(radius, shape, seed), "run.json")) \
                or not claim(name + ".claim"):
            continue
        print("run: R %g %s seed %d" % (radius, shape, seed), flush=True)
        subprocess.run([sys.executable, os.path.join(HERE, "run_silo.py"), "--log",
                        name + ".log"] + args, check=True)
        os.remove(name + ".claim")


if __name__ == "__main__":
    main()
