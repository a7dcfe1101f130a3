"""Input fuzzing of every style's command lines (engine and outcomes: fuzz_inputs.py).

A fixed seed and a small count by default. Long mode: ELLIPSOID_DEP_FUZZ_COUNT=N (and
optionally ELLIPSOID_DEP_FUZZ_SEED, ELLIPSOID_DEP_FUZZ_JOBS, ELLIPSOID_DEP_FUZZ_TIMEOUT),
`pytest -s` prints the tally and every finding.

A mutant passes when LAMMPS either runs it to a finite state or stops with an ERROR; a crash,
a sanitizer report, a hang or a non-finite state fails the test.
"""
import os
import subprocess
from concurrent.futures import ThreadPoolExecutor

import pytest

import fuzz_inputs as fz
from conftest import subprocess_env

SEED = int(os.environ.get("ELLIPSOID_DEP_FUZZ_SEED", "20261201"))
COUNT = int(os.environ.get("ELLIPSOID_DEP_FUZZ_COUNT", "48"))
JOBS = int(os.environ.get("ELLIPSOID_DEP_FUZZ_JOBS", "2"))
TIMEOUT = float(os.environ.get("ELLIPSOID_DEP_FUZZ_TIMEOUT", "60"))

# Mutants that fail through a bug in a file being restructured elsewhere: key -> the bug.
# Each must still fail (one that passes fails the test, so it is taken off this list once
# its bug is fixed). Crashes of LAMMPS itself are fuzz_inputs.HOST_CRASH instead.
KNOWN_FAILURES = {
}

# Mutants of the long runs that must keep passing: a bug fixed, or a finding that was not
# the package's fault but must stay classified right.
ROLLING_HUGE = ("lj:19: pair_coeff * * hertz 1e4 50 tangential history 1e3 0.5 "
                "rolling constant 2e+301")
REGRESSIONS = [
    # was nonfinite: orient/histo printed nan (a torque ~1e300 left the orientation NaN);
    # mu_r is now refused above 1
    ROLLING_HUGE,
    # LAMMPS's thermo ke overflows (si units, k_B = 1.38e-23); state and computes finite
    "si:21: fix p all pour/ellipsoid 4 2 977 region ins size 0.0015 0.0025 shape 1.3 1.1 "
    "density 2.5000000000000002e+303 vol 0.05 40",
]


def lmp_binary():
    return os.environ["ELLIPSOID_DEP_LMP"]


def run_all(cases):
    env = subprocess_env()

    def one(case):
        name, k, line = case[:3]
        return case, fz.run_mutant(lmp_binary(), name, k, line, TIMEOUT, env)

    with ThreadPoolExecutor(max_workers=JOBS) as pool:
        return list(pool.map(one, cases))


def check(results):
    tally, bad, fixed = {}, [], []
    for case, (outcome, detail) in results:
        name, k, line = case[:3]
        tally[outcome] = tally.get(outcome, 0) + 1
        known = fz.key(name, k, line) in KNOWN_FAILURES
        if outcome in fz.BAD and not known:
            bad.append(f"{outcome}: {fz.key(name, k, line)}\n    {detail}")
        elif known and outcome not in fz.BAD:
            fixed.append(fz.key(name, k, line))
        if outcome in fz.BAD + fz.NOTED:
            print(f"FINDING {outcome}{' (known)' if known else ''}: {fz.key(name, k, line)}\n"
                  f"    {detail}")
    print(f"fuzz: {len(results)} mutants, " +
          ", ".join(f"{n} {o}" for o, n in sorted(tally.items())))
    assert not bad, "\n".join(bad)
    assert not fixed, "known failures that now pass (remove them from KNOWN_FAILURES): " + \
        "; ".join(fixed)
    return tally


@pytest.mark.parametrize("name", sorted(fz.BASES))
def test_base_inputs_run_clean(name):
    """The unmutated inputs run to a finite state: every mutant differs from a clean run."""
    k = fz.targets(fz.BASES[name])[0]
    line = fz.base_lines(fz.BASES[name])[k]
    outcome, detail = fz.run_mutant(lmp_binary(), name, k, line, TIMEOUT, subprocess_env())
    assert outcome == "ok", detail


def test_mutants():
    cases = list(fz.mutants(SEED, COUNT))
    assert len(cases) == COUNT
    tally = check(run_all(cases))
    # the mix is meaningful: some mutants are refused and some still run
    assert tally.get("error", 0) > 0 and tally.get("ok", 0) > 0, tally


def test_known_failures_and_regressions():
    cases = [fz.parse_key(entry) for entry in list(KNOWN_FAILURES) + REGRESSIONS]
    if not cases:
        pytest.skip("no known failures or regressions listed")
    check(run_all(cases))


def test_rolling_resistance_bounded():
    """mu_r above 1 (a torque arm longer than the contact radius) is an ERROR naming mu_r;
    mu_r = 1 still runs to a finite state and finite orientations."""
    name, k, line = fz.parse_key(ROLLING_HUGE)
    outcome, detail = fz.run_mutant(lmp_binary(), name, k, line, TIMEOUT, subprocess_env())
    assert outcome == "error" and "rolling constant mu_r must be in [0, 1]" in detail, detail
    at_limit = line.replace("2e+301", "1")
    assert fz.run_mutant(lmp_binary(), name, k, at_limit, TIMEOUT, subprocess_env())[0] == "ok"


STOL_MUTANT = ("lj:19: pair_coeff * 9223372036854775808 * hertz 1e4 50 tangential history 1e3 "
               "0.5 rolling constant 0.02")


def test_lammps_own_crash_is_host(tmp_path):
    """A type range beyond long crashes LAMMPS's utils::bounds for any pair style (here
    lj/cut, no package involved); the fuzzer names that outcome 'host'."""
    inp = tmp_path / "in.stol"
    inp.write_text("units lj\natom_style atomic\nregion box block 0 4 0 4 0 4\n"
                   "create_box 2 box\npair_style lj/cut 2.5\n"
                   "pair_coeff * 9223372036854775808 1 1\n")
    proc = subprocess.run([lmp_binary(), "-in", str(inp), "-log", "none", "-nocite"],
                          capture_output=True, text=True, env=subprocess_env())
    out = proc.stdout + proc.stderr
    assert fz.HOST_CRASH.search(out), out
    name, k, line = fz.parse_key(STOL_MUTANT)
    assert fz.run_mutant(lmp_binary(), name, k, line, TIMEOUT, subprocess_env())[0] == "host"
