"""The cost curve's tables on made-up rows and logs whose answers are known.
bench/cost_curve/cost_table.py: the medians, the time and contacts per particle-step, the memory
per particle, the communication's share summed over a log's runs, the first checks at which
each rest condition held, and the exponents in N; bench/cost_curve/cost_extrapolation.py: the
extrapolation to more particles and ranks. bench/cost_curve/run_replicate.py: the last
run's loop time, CPU use, section shares and contacts (the difference of cumulative counters)."""
import csv
import math
import os
import subprocess
import sys

import pytest

from conftest import root_dir, subprocess_env

sys.path.insert(0, os.path.join(root_dir(), "bench", "cost_curve"))
import cachegrind_replicate    # noqa: E402
import cost_extrapolation    # noqa: E402
import cost_table    # noqa: E402
import run_replicate    # noqa: E402

LOG = """Created orthogonal box = (0 0 0) to (4.5 4.5 20)
  {procs} by 1 by 1 MPI processor grid
Per MPI rank memory allocation (min/avg/max) = 10 | 11 | {mem} Mbytes
PROGRESS step 1000 inserted 10 of {n} KE/particle 1e-2 target 1e-3 flight 0.5 target 1
PROGRESS step 2000 inserted {n} of {n} KE/particle 1e-2 target 1e-3 flight 3 target 1
PROGRESS step 3000 inserted {n} of {n} KE/particle 5e-4 target 1e-3 flight 2 target 1
PROGRESS step 4000 inserted {n} of {n} KE/particle 2e-3 target 1e-3 flight 0.5 target 1
Loop time of {loop1} on {procs} procs for 1000 steps with {n} atoms

50.0% CPU use with 1 MPI tasks x no OpenMP threads
Comm    | 0.1        | {comm1}      | 0.3        |   0.0 |  5.00
Per MPI rank memory allocation (min/avg/max) = 10 | 11 | 1.5 Mbytes
Loop time of {loop2} on {procs} procs for 1000 steps with {n} atoms
Comm    | 0.1        | {comm2}      | 0.3        |   0.0 |  5.00
Nlocal:           {n} ave        {n} max        {n} min
Nghost:           {ghosts} ave        {ghosts} max        {ghosts} min
"""


def make_runs(folder, ranks=1, power=1.0):
    """N = 1000, 4000, 16000 with CPU exactly linear in N (1 us per particle-step at 2000
    steps; as N^power with another power), two seeds each (CPU +-10 %), memory 2 kB per
    particle; the logs' two runs of 1000 steps take 3 and 1 ms of wall time per particle, the
    first at 50 % CPU use"""
    rows = []
    for n in (1000, 4000, 16000):
        for seed, f in ((1, 0.9), (2, 1.1)):
            rows.append({"setting": "default", "seed": seed, "N": n, "np": ranks,
                         "cpu_seconds": f * n * 2000 * 1e-6 * (n / 1000) ** (power - 1),
                         "steps": 2000,
                         "contacts": 2.5 * n * 2000,
                         "peak_rss_mb": "" if seed == 1 or n == 1000 else 0.004 * n})
            run = folder / ("default-N%d-s%d" % (n, seed))
            run.mkdir()
            (run / "log.lammps").write_text(LOG.format(mem=2 * n / 1024, n=n, ghosts=n // 2,
                                                       procs=ranks,
                                                       loop1=3e-3 * n,
                                                       loop2=1e-3 * n, comm1=4e-4 * n,
                                                       comm2=0))
    rows.append({"setting": "fast", "seed": 1, "N": 1000, "np": 1, "cpu_seconds": 1.0,
                 "steps": 1, "contacts": 1, "peak_rss_mb": 1})    # another setting: left out
    with open(folder / "rows.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def test_cost_table_by_hand(tmp_path):
    make_runs(tmp_path)
    at_rest = [{"np": 1, "N": n, "us_per_particle_step": 2.0} for n in (1000, 64000)]
    sizes, fits = cost_table.write(cost_table.load([str(tmp_path)]), str(tmp_path / "out"),
                                   at_rest)
    assert sorted(sizes) == [(1000, 1), (4000, 1), (16000, 1)]
    for (n, _), v in sizes.items():
        assert v["seeds"] == 2 and v["steps"] == 2000
        assert v["cpu_seconds"] == pytest.approx(n * 0.002)    # the median of 0.9 and 1.1
        assert v["us_per_particle_step"] == pytest.approx(1.0)
        assert v["kb_per_particle"] == pytest.approx(2.0)
        assert v["comm_share"] == pytest.approx(0.4 / 4.0)    # summed over the log's runs
        assert v["cpu_to_common"] == pytest.approx(2.5e-3 * n)    # 3 x 50 % + 1 ms
        if n == 1000:    # neither row has the column's value
            assert math.isnan(v["peak_rss_mb"])
        else:    # seed 1's row has none
            assert v["peak_rss_mb"] == pytest.approx(0.004 * n)
        assert v["contacts_per_particle_step"] == pytest.approx(2.5)
        # step 1000 had flight below flytol but not all particles in; KE held first at 3000
        assert (v["ke_met"], v["flight_met"]) == (3000, 4000)
    assert list(fits) == [1]    # one fit per rank count
    assert fits[1]["cpu_seconds"] == pytest.approx(1.0)
    assert fits[1]["us_per_particle_step"] == pytest.approx(0.0, abs=1e-9)
    assert fits[1]["contacts_per_particle_step"] == pytest.approx(0.0, abs=1e-9)
    assert fits[1]["cpu_to_common"] == pytest.approx(1.0)
    by_step = cost_table.read_log(str(tmp_path / "default-N1000-s1" / "log.lammps"))["cpu_by_step"]
    assert by_step == pytest.approx([(1000, 1.5), (2000, 2.5)])
    assert cost_table.cpu_to_step(by_step, 1500) == pytest.approx(2.0)    # linear within a run
    assert cost_table.cpu_to_step(by_step, 500) == pytest.approx(0.75)
    assert math.isnan(cost_table.cpu_to_step(by_step, 2001))    # beyond the log
    assert os.path.getsize(tmp_path / "out" / "cost_curve.png") > 5000
    table = (tmp_path / "out" / "table.md").read_text()
    assert "| 16000 | 1 | 2 | 32 | 2000 | 3000 | 4000 | 40 | 1.00 | 2.50 | 31.2 | 2.00 | 64 | 0.100 |" in table
    assert "| 1000 | 1 | 2 | 2 | 2000 | 3000 | 4000 | 2 | 1.00 | 2.50 | 2.0 | 2.00 | - | 0.100 |" in table
    assert math.isnan(cost_table.read_log(str(tmp_path / "rows.csv"))["comm_share"])    # no loop



def test_one_fit_per_rank_count(tmp_path):
    """1-rank runs linear in N, 2-rank runs (another invocation's folder) as N^1.5: each rank
    count has its own exponents, and the extrapolation starts from the 2-rank N = 16000"""
    (tmp_path / "one").mkdir()
    (tmp_path / "two").mkdir()
    make_runs(tmp_path / "one")
    make_runs(tmp_path / "two", ranks=2, power=1.5)
    rows = cost_table.load([str(tmp_path / "one"), str(tmp_path / "two")])
    sizes, fits = cost_table.write(rows, str(tmp_path / "out"))
    assert sorted(fits) == [1, 2]
    assert fits[1]["cpu_seconds"] == pytest.approx(1.0)
    assert fits[2]["cpu_seconds"] == pytest.approx(1.5)
    assert fits[2]["us_per_particle_step"] == pytest.approx(0.5)
    assert cost_extrapolation.base_size(sizes) == (16000, 2)
    table = (tmp_path / "out" / "table.md").read_text()
    assert "Exponents in N at 1 rank (log-log least squares over 3 sizes): CPU to deposit 1.000" \
        in table
    assert "Exponents in N at 2 ranks (log-log least squares over 3 sizes): CPU to deposit 1.500" \
        in table
    assert "from N = 16000 on 2 ranks (4.00 us per particle-step" in table


def work_row(n, chunks, scale=1.0):
    """a deposit's row with its runs' CPU and counters: chunks of 1000 steps, each (pairs tested,
    contacts per particle-step) or "none" (a run that printed no counters) or "reset" (the
    counters start anew), whose CPU per particle-step is 10 ns per pair + 200 ns per contact +
    500 ns, times scale; a 0-step run first"""
    cpu_by_step, work_by_step = [(0, 1e-6)], [(0, 0, 0)]
    steps, cpu, pairs, contacts, rate = 0, 1e-6, 0, 0, (0, 0)
    for c in chunks:
        steps += 1000
        if c == "reset":
            pairs, contacts = n * 5, 0
        elif c != "none":
            rate = c
        if c != "reset":
            pairs += rate[0] * n * 1000
            contacts += rate[1] * n * 1000
        cpu += scale * (10 * rate[0] + 200 * rate[1] + 500) * 1e-9 * n * 1000
        cpu_by_step.append((steps, cpu))
        work_by_step.append(None if c == "none" else (steps, pairs, contacts))
    return {"N": n, "np": 1, "cpu_by_step": cpu_by_step, "work_by_step": work_by_step}


def test_work_fit_by_hand():
    """N = 1000's chunks give the costs exactly; N = 4000 costs 1.2 times its work (a run
    whose counters start anew is left out), N = 16000 another mix of work at its cost (a run
    without counters joins the next)"""
    rows = [work_row(1000, [(100, 0), (50, 0), (30, 1), (10, 2)]),
            work_row(4000, [(100, 0), "reset", (30, 1)], scale=1.2),
            work_row(16000, [(20, 3), "none", (40, 1)])]
    assert [c[0] for c in cost_table.chunks(rows[1])] == [4000, 4000]
    fit = cost_table.work_fit(rows)
    assert fit["fitted_n"] == 1000
    assert (fit["ns_per_pair"], fit["ns_per_contact"], fit["ns_per_particle"]) == \
        (pytest.approx(10), pytest.approx(200), pytest.approx(500))
    assert fit["ratio"] == {1000: pytest.approx(1.0), 4000: pytest.approx(1.2),
                            16000: pytest.approx(1.0)}
    assert cost_table.work_fit(rows[:1]) is None    # one size: nothing to compare
    words = cost_table.work_words(2, fit)
    assert "at 2 ranks: the CPU per particle-step of N = 1000's chunks" in words
    assert "10.00 ns per pair tested + 200 ns per contact + 500 ns per particle" in words
    assert "N = 1000 1.00, N = 4000 1.20, N = 16000 1.00." in words


def test_read_log_counters_after_their_run(tmp_path):
    """each run's counters line belongs to the loop before it; a run without one has None"""
    log = tmp_path / "log.lammps"
    log.write_text("""Loop time of 1e-06 on 2 procs for 0 steps with 1 atoms
granular/ellipsoid counters: {"pairs": 0, "contacts": 0}
Loop time of 2.0 on 2 procs for 1000 steps with 10 atoms

50.0% CPU use with 2 MPI tasks x no OpenMP threads
granular/ellipsoid counters: {"pairs": 70, "contacts": 3}
Loop time of 1.0 on 2 procs for 1000 steps with 10 atoms
""")
    d = cost_table.read_log(str(log))
    assert d["work_by_step"] == [(0, 0, 0), (1000, 70, 3), None]
    assert [s for s, _ in d["cpu_by_step"]] == [0, 1000, 2000]
    assert [c for _, c in d["cpu_by_step"]] == pytest.approx([2e-6, 2.000002, 4.000002])


def test_extrapolation_by_hand(tmp_path):
    """the ghost shell from the measured ghosts per atom and back; a deposit of 16 x 16000
    particles from N = 16000 on 1 rank (box 4.5 x 4.5 in the logs, 0.5 ghosts per atom,
    communication 0.1 of the loop): its box 4 times as wide, so on 16 ranks (4 x 4) each rank's
    subdomain is the measured box, with the measured ghosts and time per particle-step"""
    for a, b, w in ((4.5, 4.5, 0.3), (10.0, 3.0, 1.7)):
        ratio = cost_extrapolation.ghost_ratio(w, a, b)
        assert cost_extrapolation.ghost_width(ratio, a, b) == pytest.approx(w)
    assert [cost_extrapolation.rank_grid(p) for p in (1, 2, 6, 16, 64)] == \
        [(1, 1), (2, 1), (3, 2), (4, 4), (8, 8)]
    make_runs(tmp_path)
    sizes = cost_table.per_size(cost_table.load([str(tmp_path)]), 2000)
    assert sizes[(16000, 1)]["ghost_ratio"] == 0.5 and sizes[(16000, 1)]["box"] == (4.5, 4.5)
    e = cost_extrapolation.extrapolate(sizes, 0.1, n=16 * 16000, cores=(1, 16))
    assert e["base"] == (16000, 1) and e["steps"] == pytest.approx(2000 * 16 ** 0.1)
    grid, g, t, hours = e["cores"][16]
    assert grid == (4, 4) and g == pytest.approx(0.5) and t == pytest.approx(1.0)
    assert hours == pytest.approx(1e-6 * 16 * 16000 * e["steps"] / 16 / 3600)
    w = e["width"]    # (4.5 + 2w)^2 = 1.5 x 4.5^2
    assert w == pytest.approx((math.sqrt(1.5) - 1) * 4.5 / 2)
    grid, g, t, _ = e["cores"][1]    # one rank holds the whole 18 x 18 box
    assert grid == (1, 1) and g == pytest.approx(((18 + 2 * w) ** 2 - 18 ** 2) / 18 ** 2)
    assert t == pytest.approx(0.9 + 0.1 * g / 0.5)


REPLICATE_LOG = """Per MPI rank memory allocation (min/avg/max) = 10 | 11 | 12.5 Mbytes
granular/ellipsoid counters: {{"pairs": 9, "contacts": 1000}}
Loop time of 9.0 on 2 procs for 1000 steps with {n} atoms
granular/ellipsoid counters: {{"pairs": 9, "contacts": 4000}}
Per MPI rank memory allocation (min/avg/max) = 10 | 11 | 25 Mbytes
Loop time of {loop} on 2 procs for 500 steps with {n} atoms

90.0% CPU use with 2 MPI tasks x no OpenMP threads
granular/ellipsoid counters: {{"pairs": 9, "contacts": {contacts}}}
Section |  min time  |  avg time  |  max time  |%varavg| %total
---------------------------------------------------------------
Pair    | 1.0        | 1.5        | 2.0        |   0.0 | 75.00
Neigh   | 0          | 0          | 0          |   0.0 |  0.00
Comm    | 0.1        | 0.2        | 0.3        |   0.0 | 10.00
Output  | 0.0001     | 0.0001     | 0.0001     |   0.0 |  0.00
Modify  | 0.1        | 0.2        | 0.3        |   0.0 | 14.50
Other   |            | 0.01       |            |       |  0.50
"""


def test_replicate_log_and_table(tmp_path):
    rows = []
    for k, loop in ((1, 1.0), (2, 8.0)):    # 4x the atoms, 8x the loop: exponent 0.5
        n = 1000 * k * k
        log = tmp_path / ("log%d" % k)
        log.write_text(REPLICATE_LOG.format(n=n, loop=loop, contacts=4000 + 1500 * n))
        run = run_replicate.read_log(str(log))
        assert (run["N"], run["np"], run["steps"], run["loop_seconds"]) == (n, 2, 500, loop)
        assert run["cpu_use"] == pytest.approx(0.9)
        assert run["contacts"] == 1500 * n    # the last counters minus the ones before
        assert run["memory_mb_per_rank"] == 25
        assert run["shares"] == pytest.approx({"Pair": 0.75, "Neigh": 0.0, "Comm": 0.10,
                                               "Output": 0.0, "Modify": 0.145, "Other": 0.005})
        cpu = loop * 0.9 * 2
        for repeat, f in enumerate((1.0, 1.2, 0.8)):    # the median is the first
            row = {"k": k, "N": n, "np": 2, "repeat": repeat,
                   "us_per_particle_step": f * 1e6 * cpu / (n * 500),
                   "contacts_per_particle_step": 3.0,
                   "ns_per_contact_step": f * 1e9 * cpu * 0.75 / (1500 * n),
                   "share_pair": 0.75, "share_neigh": 0, "share_comm": 0.1,
                   "share_modify": 0.145, "share_output": 0, "share_other": 0.005,
                   "kb_per_particle": 1024 * 25 * 2 / n}
            row.update({m: row.get(m, 0) for m in run_replicate.MEASURES})
            rows.append(row)
    table = run_replicate.write_table(rows, str(tmp_path))
    assert "| 1 x 1 | 1000 | 2 | 3 | 3.600 | 1.50 | 3.000 | 900 | 0.750 |" in table
    assert "at 2 ranks (log-log least squares over 2 sizes' medians): 0.500." in table
    with pytest.raises(ValueError):    # a log without a measured run
        (tmp_path / "empty").write_text("LAMMPS\n")
        run_replicate.read_log(str(tmp_path / "empty"))


def test_replicate_copies_a_saved_deposit(tmp_path):
    """in.replicate on a tiny in.deposit run saved with its contacts' histories (which
    LAMMPS's replicate refuses: hence the data file): the 2 x 2 copy holds 4 times the
    particles, and, each copy being the deposit shifted by a box edge, the same contacts per
    particle-step as the deposit itself"""
    env = subprocess_env()
    deposit = tmp_path / "deposit"
    deposit.mkdir()
    subprocess.run([env["ELLIPSOID_DEP_LMP"], "-in", os.path.join(root_dir(), "examples",
                    "deposit", "in.deposit"), "-log", str(deposit / "log.lammps"), "-screen",
                    "none", "-nocite", "-var", "N", "40", "-var", "chunk", "2000", "-var",
                    "maxchunks", "8", "-var", "image", "0", "-var", "save", "1", "-var", "out",
                    str(deposit)], check=True, env=env)
    rows = {k: run_replicate.measure(str(deposit / "deposit.restart"), k, 1, 20, 50,
                                     str(tmp_path / ("k%d" % k))) for k in (1, 2)}
    assert (rows[1]["N"], rows[2]["N"]) == (40, 160)
    assert rows[1]["steps"] == rows[2]["steps"] == 50
    assert rows[1]["contacts_per_particle_step"] > 0.5    # the particles lie on each other
    assert rows[2]["contacts_per_particle_step"] == rows[1]["contacts_per_particle_step"]


CACHEGRIND_OUT = """desc: I1 cache:         65536 B, 64 B, 4-way associative
desc: D1 cache:         49152 B, 64 B, 12-way associative
desc: LL cache:         {ll} B, 64 B, 16-way associative
cmd: lmp -in in.replicate
events: Ir I1mr ILmr Dr D1mr DLmr Dw D1mw DLmw
fl=a.cpp
fn=f
1 5 0 0 1 0 0 1 0 0
summary: {ir} 10 5 {dr} {d1mr} {dlmr} {dw} {d1mw} {dlmw}
"""


def test_cachegrind_counts_per_particle_step(tmp_path):
    """the totals and caches of a cachegrind file, and the per particle-step difference of a
    run of 2 x 50 steps and one of 50 (the set-up cancels)"""
    counts = {}
    for name, steps in (("short", 50), ("long", 100)):
        path = tmp_path / name
        # set-up: 1e6 instructions, 1000 D1 and 100 LL misses; each particle-step 2000
        # instructions, 30 + 10 D1 misses and 0.5 + 0.25 LL misses; 160 particles
        ps = 160 * steps
        path.write_text(CACHEGRIND_OUT.format(
            ll=2 ** 25, ir=10 ** 6 + 2000 * ps, dr=500, d1mr=1000 + 30 * ps,
            dlmr=100 + ps // 2, dw=400, d1mw=10 * ps, dlmw=ps // 4))
        counts[name], caches = cachegrind_replicate.read_counts(str(path))
    assert counts["short"]["Ir"] == 10 ** 6 + 2000 * 160 * 50 and counts["short"]["I1mr"] == 10
    assert caches[2] == "LL cache:         33554432 B, 64 B, 16-way associative"
    c = cachegrind_replicate.per_particle_step(counts["short"], counts["long"], 160, 50)
    assert c == pytest.approx({"instructions": 2000, "d1_misses": 40, "ll_data_misses": 0.75})
    (tmp_path / "none").write_text("events: Ir\n")
    with pytest.raises(ValueError):
        cachegrind_replicate.read_counts(str(tmp_path / "none"))
