"""The Hertz contact time and the damping time in every LAMMPS unit style.

Two glass spheres of radius 1 mm (E 6.3e10 Pa, nu 0.23, e 0.9, 2500 kg/m^3), meeting at
1 m/s, and one of them against a wall (pair and wall impact_velocity 1 m/s), at a time step of
1.25e-7 s, are set up in each unit style with the same physical values; lj with a length unit
of 1 mm, a mass unit of 1 mg and a time unit of 1 ms. Checks:

* the contact times of pair and wall, converted to seconds, equal the si ones (6.26122e-6 s
  for the pair, 50 time steps) in every style; before the fix real and metal were off (units
  real: 2.8e-7 s with a false WARNING, metal: 2.5e-4 s);
* with the paper's law (hertz kn K, converted) the damping times equal the si ones too;
* with hertz/material's restitution coefficient e the damping is that of LAMMPS's pair
  granular (damping coeff_restitution), from the mass in the style's mass unit: in styles
  whose force->ftm2v is not 1 (real, metal, electron) it acts as Tsuji's beta(e) sqrt(ftm2v)
  (doc/pair_granular_ellipsoid.rst). The damping time reported is that of the force applied,
  the si one over sqrt(ftm2v); a head-on collision in units real rebounds exactly as one in si
  with the e' of that beta, and one in units metal (beta' < -1) does not rebound;
* no contact-time or damping WARNING in any style (dt is 1/50 of the contact time).
"""
import math
import re

import pytest

import ed_helpers_pour as h

NA = 6.02214076e23
BOHR, HARTREE, AMU = 5.29177210903e-11, 4.3597447222071e-18, 1.66053906660e-27
# SI value of one unit of length, mass, time and force (LAMMPS's doc/src/units.rst; velocity is
# length / time, in electron Bohr/fs as LAMMPS's ftm2v and mvv2e have it)
UNITS = {
    "lj": (1.0e-3, 1.0e-6, 1.0e-3, 1.0e-6 * 1.0e-3 / 1.0e-6),
    "real": (1.0e-10, 1.0e-3 / NA, 1.0e-15, 4184.0 / NA / 1.0e-10),
    "metal": (1.0e-10, 1.0e-3 / NA, 1.0e-12, 1.602176634e-19 / 1.0e-10),
    "si": (1.0, 1.0, 1.0, 1.0),
    "cgs": (1.0e-2, 1.0e-3, 1.0, 1.0e-5),
    "electron": (BOHR, AMU, 1.0e-15, HARTREE / BOHR),
    "micro": (1.0e-6, 1.0e-15, 1.0e-6, 1.0e-9),
    "nano": (1.0e-9, 1.0e-21, 1.0e-9, 1.0e-12),
}
GLASS = (6.3e10, 0.23, 0.9)    # potentials/ellipsoid_dep.materials
RADIUS, DENSITY, SPEED, DT = 1.0e-3, 2500.0, 1.0, 1.25e-7
KN, K = 7.0e8, 50.0    # hertz kn K in SI: N/m^1.5, N s/m^1.5
WALL = re.compile(r"^Fix wall/gran/ellipsoid: Hertz contact time (\S+) ", re.M)
WALL_DAMPING = re.compile(r"^Fix wall/gran/ellipsoid: damping number .* damping time "
                          r"m\*/gamma (\S+) ", re.M)


def ftm2v(units):
    """force / mass * time in velocity units, from the table (LAMMPS's force->ftm2v)."""
    length, mass, time, force = UNITS[units]
    return force * time * time / (mass * length)


def law(units, kind):
    """pair_coeff words of the law in `units`: glass (numbers in lj, which has no SI
    equivalent) or the paper's hertz kn K."""
    length, mass, time, force = UNITS[units]
    if kind == "kn_K":
        return f"hertz {KN / (force / length**1.5)!r} {K / (force * time / length**1.5)!r}"
    if units == "lj":
        return "hertz/material {!r} {} {}".format(GLASS[0] / (force / length**2), *GLASS[1:])
    return "hertz/material glass"


def two_spheres(units, words, gap, speed, wall=True):
    """Input of two spheres of radius RADIUS along x, `gap` apart, at +-speed/2 (SI values)."""
    length, mass, time, force = UNITS[units]
    r, v = RADIUS / length, SPEED / (length / time)
    m = DENSITY * 4.0 / 3.0 * math.pi * RADIUS**3 / mass
    x = r + 0.5 * gap / length
    lines = [f"units {units}", "atom_style ellipsoid", "atom_modify map array",
             "boundary f f f", "comm_modify vel yes",
             f"region box block {-6 * r!r} {6 * r!r} {-3 * r!r} {3 * r!r} {-3 * r!r} {3 * r!r}",
             "create_box 1 box", f"create_atoms 1 single {-x!r} 0 0",
             f"create_atoms 1 single {x!r} 0 0", f"set type 1 shape {2 * r!r} {2 * r!r} {2 * r!r}",
             f"set type 1 mass {m!r}", f"set atom 1 vx {0.5 * speed * v!r}",
             f"set atom 2 vx {-0.5 * speed * v!r}",
             f"pair_style granular/ellipsoid impact_velocity {v!r}", f"pair_coeff * * {words}",
             f"timestep {DT / time!r}", "fix i all nve/ellipsoid"]
    if wall:
        lines.append(f"fix w all wall/gran/ellipsoid {words} zplane {-2 * r!r} NULL "
                     f"impact_velocity {v!r}")
    return lines


def times(tmp_path, units, kind):
    """(pair contact, pair damping, wall contact, wall damping) times in seconds and the log;
    the pair's from Pair::extract at full precision, the wall's from its log lines (6 digits)."""
    lmp = h.new_lammps(tmp_path, f"{units}_{kind}")
    lmp.commands_list(two_spheres(units, law(units, kind), 2 * RADIUS, 0.0) + ["run 0"])
    pair_tc, pair_td = lmp.extract_pair("contact_time"), lmp.extract_pair("damping_time")
    log = h.read_log(lmp)
    lmp.close()
    time = UNITS[units][2]
    return (pair_tc * time, pair_td * time, float(WALL.search(log).group(1)) * time,
            float(WALL_DAMPING.search(log).group(1)) * time, log)


@pytest.fixture(scope="module")
def si_times(tmp_path_factory):
    work = tmp_path_factory.mktemp("si")
    return {kind: times(work, "si", kind) for kind in ("glass", "kn_K")}


@pytest.mark.parametrize("units", sorted(UNITS))
def test_contact_and_damping_times_equal_si(tmp_path, si_times, units):
    glass, si_glass = times(tmp_path, units, "glass"), si_times["glass"]
    paper, si_paper = times(tmp_path, units, "kn_K"), si_times["kn_K"]
    print(units, "pair/wall contact", glass[0], glass[2], "damping (e)", glass[1], glass[3],
          "damping (K)", paper[1], paper[3])
    assert si_glass[0] == pytest.approx(6.26122e-6, rel=1e-5)    # the si value
    for k, rel in ((0, 1e-6), (2, 1e-5)):    # contact times of pair and wall (6 digits)
        assert glass[k] == pytest.approx(si_glass[k], rel=rel), (units, k)
        assert paper[k] == pytest.approx(si_paper[k], rel=rel), (units, k)
    for k, rel in ((1, 1e-6), (3, 1e-5)):    # damping times: the paper's law as in si, and
        assert paper[k] == pytest.approx(si_paper[k], rel=rel), (units, k)    # e's convention
        assert glass[k] == pytest.approx(si_glass[k] / math.sqrt(ftm2v(units)), rel=rel)
    for log in (glass[4], paper[4]):
        assert "WARNING" not in log, log


def beta(e):
    return math.log(e) / math.sqrt(math.log(e) ** 2 + math.pi**2)


def restitution(tmp_path, units, words):
    """Measured restitution of the two spheres meeting head-on at SPEED (no wall)."""
    length, mass, time, force = UNITS[units]
    lmp = h.new_lammps(tmp_path, f"bounce_{units}")
    lmp.commands_list(two_spheres(units, words, 0.0, SPEED, wall=False)
                      + ["run 150"])
    v = lmp.numpy.extract_atom("v")
    i1, i2 = lmp.map_atom(1), lmp.map_atom(2)
    rebound = (v[i2][0] - v[i1][0]) * length / time
    lmp.close()
    return rebound / SPEED


def test_restitution_in_units_real_is_that_of_beta_times_sqrt_ftm2v(tmp_path):
    """e = 0.9 in units real rebounds as e' in si, beta(e') = beta(0.9) sqrt(ftm2v_real)."""
    scaled = beta(GLASS[2]) * math.sqrt(ftm2v("real"))
    e_prime = math.exp(math.pi * scaled / math.sqrt(1.0 - scaled**2))
    si_words = "hertz/material {!r} {!r} {!r}".format(GLASS[0], GLASS[1], e_prime)
    e_si = restitution(tmp_path, "si", "hertz/material glass")
    e_real = restitution(tmp_path, "real", "hertz/material glass")
    e_si_prime = restitution(tmp_path, "si", si_words)
    e_metal = restitution(tmp_path, "metal", "hertz/material glass")
    print("measured restitution: si", e_si, "real", e_real, "(e'", e_prime, ", si with e'",
          e_si_prime, ") metal", e_metal)
    assert abs(e_si - GLASS[2]) < 0.02
    assert e_real == pytest.approx(e_si_prime, rel=1e-6)
    assert e_real > 0.99
    # beta(0.9) sqrt(ftm2v_metal) = -3.3: overdamped, the spheres stick
    assert beta(GLASS[2]) * math.sqrt(ftm2v("metal")) < -1.0 and abs(e_metal) < 0.01
