"""The default deposit's time step is a stated fraction of the Hertz contact time or of the
damping time, whichever is shorter.

examples/deposit/in.deposit lets the pair find the contact time and the damping time of the
lightest pair the pour can make (a probe of the smallest size r = 0.5 (1 - dr)) at the largest
impact speed, that of the pour region's top falling to the ground, sqrt(vdrop^2 + 2 g z_top),
and sets dt = min(dtfrac x the contact time, dtdamp x the damping time):

* dt is that minimum of the times the pair reports (its log lines and compute pair's entries);
* they are the closed-form Hertz time of two of the smallest particles at that speed and
  m*/(K sqrt(xi_max)) at its deepest overlap xi_max = (5 m* v^2 / (4 kn))^(2/5), and no poured
  particle is lighter (the pair's later reports are not shorter);
* the default (delta_r 0.6) is bound by the damping, a stiffer pour with delta_r 0.3
  by the contact time;
* no contact-time or damping WARNING (nor any other) appears; an explicit dt is used as given,
  with a WARNING when it exceeds the rule.
"""
import math
import re

import pytest
from scipy.special import beta

import ed_helpers_pour as h
REPORT = re.compile(r"^Pair granular/ellipsoid: Hertz contact time (\S+) \(types 1 1, impact "
                    r"speed (\S+)\)", re.M)
DAMPING = re.compile(r"^Pair granular/ellipsoid: damping number \S+ \(types 1 1, impact speed "
                     r"\S+\): the time step over the damping time m\*/gamma (\S+) ", re.M)


def short_deposit(tmp_path, name, variables):
    """in.deposit with 100 particles for one chunk of 200 steps: (dt, (dtfrac, dtdamp), (tc,
    tdamp), log, lightest mass poured, out, z_top)."""
    out = tmp_path / name
    out.mkdir()
    args = {"N": "100", "maxchunks": "1", "chunk": "200", "image": "0", "out": str(out),
            **variables}
    lmp = h.deposit_lammps(out, args)
    dt = lmp.extract_global("dt")
    fractions = (float(lmp.extract_variable("dtfrac")), float(lmp.extract_variable("dtdamp")))
    times = ((lmp.extract_variable("tc"), lmp.extract_variable("tdamp"))
             if "dt" not in variables else None)
    ztop = lmp.extract_variable("pz1")
    masses = lmp.numpy.extract_atom("rmass")[:lmp.extract_global("nlocal")]
    lightest = float(masses.min())
    lmp.close()
    with open(out / "log.lammps") as f:
        return dt, fractions, times, f.read(), lightest, out, ztop


def hertz_time(stiffness, m_eff, speed):
    return 2 * 0.4 * beta(0.4, 0.5) * (5 * m_eff * speed**2 / (4 * stiffness))**0.4 / speed


@pytest.mark.parametrize("name,variables,bound_by", [
    ("default", {}, "damping"),
    ("stiff_low_drop", {"kn": "4.0e4", "zpour": "3.0", "vdrop": "2.0", "dr": "0.3",
                        "eta": "2.0"}, "contact"),
    ("undamped", {"K": "0"}, "contact"),
])
def test_deposit_dt_is_the_stated_fraction_of_the_shorter_time(tmp_path, name, variables,
                                                               bound_by):
    dt, (dtfrac, dtdamp), (tc, tdamp), log, lightest, out, ztop = short_deposit(
        tmp_path, name, variables)
    reports = [(float(t), float(v)) for t, v in REPORT.findall(log)]
    damping_reports = [float(t) for t in DAMPING.findall(log)]
    undamped = float(variables.get("K", "200.0")) == 0
    assert reports, "the pair reported no contact time"
    assert bool(damping_reports) != undamped, "a damping time, and only for a damped law"
    probe_time, speed = reports[0]
    # the pair's reports are the times the input used, and dt the stated fraction of the shorter
    assert tc == pytest.approx(probe_time, rel=1e-5)
    if undamped:    # no damping time: compute pair's entry is 0, dt the contact time's fraction
        assert tdamp == 0 and dt == pytest.approx(dtfrac * tc, rel=1e-12)
    else:
        assert tdamp == pytest.approx(damping_reports[0], rel=1e-5)
        assert dt == pytest.approx(min(dtfrac * tc, dtdamp * tdamp), rel=1e-12)
        assert (dtdamp * tdamp < dtfrac * tc) == (bound_by == "damping")
    assert 0 < dtfrac < 0.1 and 0 < dtdamp < 1    # below the pair's warning thresholds
    # the lightest pair the pour can make, meeting at the speed of the drop
    kn = float(variables.get("kn", "1.0e4"))
    rmin = 0.5 * (1 - float(variables.get("dr", "0.6")))
    mmin = 4.0 / 3.0 * math.pi * rmin**3
    # the region's top from its stated geometry (doc/fix_pour_ellipsoid.rst, "Protocol")
    n, fins = 100, float(variables.get("fins", "0.2"))
    eta, zeta = float(variables.get("eta", "1.4")), float(variables.get("zeta", "1.8"))
    dr = float(variables.get("dr", "0.6"))
    # at least 5 d and two neighbour cutoffs (skin 0.2) of the longest particles
    a_max = 0.5 * (1 + dr) * (eta**2 * zeta)**(1 / 3)
    side = max(5.0, 0.3 * math.sqrt(n), 4 * a_max + 2 * 0.2)
    bottom = float(variables.get("zpour", "0")) or 1 + n * math.pi / 6 / (0.6 * side**2)
    top = bottom + n * math.pi / 6 / (fins * side**2) + (1 + dr) * (eta**2 * zeta)**(1 / 3)
    assert ztop == pytest.approx(top, rel=1e-12)
    vimpact = math.sqrt(float(variables.get("vdrop", "1.0"))**2 + 2 * top)
    assert speed == pytest.approx(vimpact, rel=1e-5)
    assert tc == pytest.approx(hertz_time(kn, mmin / 2, vimpact), rel=1e-10)
    K = float(variables.get("K", "200.0"))
    xi_max = (5 * (mmin / 2) * vimpact**2 / (4 * kn))**0.4
    if not undamped:
        assert tdamp == pytest.approx((mmin / 2) / (K * math.sqrt(xi_max)), rel=1e-10)
    # the poured particles are no lighter, so no later contact is shorter
    assert lightest >= mmin * (1 - 1e-12)
    assert all(t >= probe_time * (1 - 1e-5) for t, _ in reports)
    assert all(t >= damping_reports[0] * (1 - 1e-5) for t in damping_reports[1:])
    assert re.search(r"^time step rule \S+ = the shorter of \S+ x the Hertz contact time \S+ and "
                     r"\S+ x the damping time", log, re.M)
    assert "ELLIPSOID_DEP deposit: N 100" in log
    # one chunk of 200 steps cannot bring the pour to rest: the only WARNING says so, and
    # packing.dat records it
    warnings = re.findall(r"^WARNING.*", log, re.M)
    assert len(warnings) == 1 and "NOT at rest after 200 steps" in warnings[0], warnings
    packing = dict(line.split(None, 1) for line in open(out / "packing.dat")
                   if line.strip() and not line.startswith("#"))
    assert packing["at_rest"].strip() == "0"


@pytest.mark.parametrize("given,above", [("2.5e-4", False), ("6.0e-4", True)])
def test_explicit_dt_is_used_as_given_and_warned_above_the_rule(tmp_path, given, above):
    """a given dt is used as given; the rule is still computed, and a dt above it (as a
    study's fixed dt in a taller box) is a WARNING that names both"""
    dt, _, _, log, _, _, _ = short_deposit(tmp_path, "explicit", {"dt": given})
    assert dt == float(given)
    rule = float(re.search(r"^time step rule (\S+) = the shorter of", log, re.M).group(1))
    assert (dt > rule) == above, (dt, rule)
    warnings = re.findall(r"^WARNING.*", log, re.M)
    ours = [w for w in warnings if w.startswith("WARNING: the given dt")]
    assert any("NOT at rest" in w for w in warnings), warnings
    if above:    # (the pair and the pour warn too, of the damping number above 1)
        assert len(ours) == 1 and ours[0].startswith(
            "WARNING: the given dt %g exceeds the time step rule %g" % (dt, rule)), warnings
    else:
        assert len(warnings) == 1, warnings


def test_deposit_writes_a_data_file_that_reads_back(tmp_path):
    """The probe that finds the time step leaves no ellipsoid behind: write_data after the
    deposit counts its N ellipsoids, and read_data accepts the file (LAMMPS's "delete_atoms
    group all" kept the probe's, and read_data refused the header of N + 1)."""
    out = tmp_path / "data"
    out.mkdir()
    lmp = h.deposit_lammps(out, {"N": "30", "maxchunks": "1", "chunk": "10", "image": "0",
                                 "out": str(out)})
    data = out / "deposit.data"
    lmp.command(f"write_data {data}")
    lmp.close()
    with open(data) as f:
        header = f.read(2000)
    assert re.search(r"^30 atoms$", header, re.M) and re.search(r"^30 ellipsoids$", header, re.M)
    reread = h.new_lammps(tmp_path, "reread")
    reread.command("atom_style ellipsoid")
    reread.command(f"read_data {data}")
    assert reread.get_natoms() == 30
    reread.close()
