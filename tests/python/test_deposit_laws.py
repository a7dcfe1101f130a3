"""Every documented force law pours the default scene without losing an atom, at delta_r 0 and
0.6, at the time step in.deposit's rule gives it.

The paper's viscous tangential law F_t = -mu F_n v_t is a dashpot whose coefficient mu F_n
peaks with the impact's normal force; velocity Verlet integrates a dashpot stably only below
two damping times. The rule's damping time is therefore the shorter of the normal m*/gamma at
the deepest overlap and the tangential m_t/(mu F_peak) at the peak force (m_t: the mass for
sliding, rotation included); for the history spring's dashpot xt, m_t/(xt gamma_n). Without
the tangential part the rule's dt was several times the tangential damping time and the first
impacts threw atoms out of the box.

The scene is examples/deposit/in.deposit at N 100 with the particles released at vdrop 8, so
that they hit the ground at the speed of the N 600 default (about 9.8 against 9.1) after a
short fall; the run covers the landing of the whole batch.
"""
import math
import re

import pytest

import ed_helpers_pour as h

LAWS = {
    "coulomb": "history 2.0e3 0.5",    # the default
    "coulomb_dashpot": "history 2.0e3 0.5 xt 1",    # the spring with its dashpot
    "viscous": "viscous 0.5",          # the paper's
    "frictionless": "none",
    "rolling": "history 2.0e3 0.5 rolling constant 0.1",
    "rolling_sds": "history 2.0e3 0.5 rolling sds 1.0e3 2.0 0.3",
}
RULE = re.compile(r"^time step rule (\S+) = the shorter of \S+ x the Hertz contact time (\S+) "
                  r"and \S+ x the damping time (\S+) of the lightest pair at impact speed (\S+)",
                  re.M)


@pytest.mark.parametrize("dr", ["0", "0.6"])
@pytest.mark.parametrize("law", sorted(LAWS))
def test_every_law_pours_the_default_scene_without_loss(tmp_path, law, dr):
    out = tmp_path / f"{law}_{dr}"
    out.mkdir()
    # the batch lands within t = (sqrt(vdrop^2 + 2 g z_top) - vdrop) / g < 2.2 (z_top < 20)
    lmp = h.deposit_lammps(out, {"N": "100", "dr": dr, "vdrop": "8", "tangential": LAWS[law],
                                 "image": "0", "out": str(out), "chunk": "1000",
                                 "maxchunks": "1000", "ketol": "1e9", "flytol": "1e9",
                                 "unbtol": "1e9"})
    # (ketol, flytol and unbtol so large that the run stops after its first chunk: run on to
    # t = 3; 100 particles make no measuring slab, which is not the point here: its WARNING is expected)
    dt = lmp.extract_global("dt")
    ztop = lmp.extract_variable("pz1")
    steps = math.ceil(3.0 / dt) - lmp.extract_global("ntimestep")
    lmp.command(f"run {max(steps, 0)}")    # (the stress window may have run past t = 3)
    assert (math.sqrt(64 + 2 * ztop) - 8) < 2.2
    natoms = lmp.get_natoms()
    zmax = max(lmp.numpy.extract_atom("x")[:lmp.extract_global("nlocal"), 2])
    lmp.command("run 0 post no")
    kep = lmp.extract_variable("kep")    # translation and rotation, per particle, in m g d
    lmp.close()
    log = (out / "log.lammps").read_text()
    assert natoms == 100, f"{100 - natoms} atoms lost"
    # the batch has landed: nobody above the top of the pour region, and the energy of the
    # fall, over m g z_top per particle, is dissipated, not gained
    print(law, dr, "zmax", zmax, "ztop", ztop, "KE per particle", kep)
    assert zmax < ztop
    assert kep < 0.1 * ztop
    rule, contact, damping, _ = (float(x) for x in RULE.search(log).groups())
    assert dt == pytest.approx(rule, rel=1e-5)
    # the viscous law and the spring's dashpot are bound by their tangential damping time,
    # and the report says so
    tangential = re.search(r"^Pair granular/ellipsoid: damping number \S+ \(types 1 1, impact "
                           r"speed \S+\): the time step over the damping time m_t/gamma_t "
                           r"(\S+) at the peak force \(tangential\)", log, re.M)
    assert bool(tangential) == (law in ("viscous", "coulomb_dashpot"))
    if tangential:
        assert float(tangential.group(1)) == pytest.approx(damping, rel=1e-5)
        assert 0.9 * damping < 0.06 * contact
    warnings = [w for w in re.findall(r"^WARNING.*", log, re.M) if "measuring slab" not in w]
    assert not warnings, warnings
