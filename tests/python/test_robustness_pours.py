"""Robustness of small pours at the extremes of shape and size: needles, disks and triaxial
bodies of aspect ratio 20, near-spheres (eta = zeta = 1 + 1e-9), spheres, a 10:1 size ratio and
delta_r = 0.9, poured onto the floor wall under gravity.

Each case asserts the five checks of robust_helpers.assert_robust (finite state, no lost atom,
bounded kinetic energy, largest overlap below a stated fraction of the smaller body's smallest
semi-axis, non-convergence at most 1e-6 of the contact evaluations). With ELLIPSOID_DEP_LONG=1
the pours use more particles and steps. `pytest -s` prints the measured numbers
(doc/robustness.md).
"""
import math

import pytest

import ed_helpers_pour as h
import robust_helpers as rb

# small pours (lj units, g = 1, density 1, mean size r = (abc)^(1/3) = 1 unless stated)

E_MAT = 2.0e6       # hertz/material: peak overlap ~2 % of r for a sphere hitting at v ~ 3.5
E_STIFF = 1.2e7     # for a/c = 20: rims and tips have small curvature radii (softer contacts)
POURS = {
    # name: (pour keywords, N, smallest semi-axis the pour can make)
    "needle20": ("size 1 1 shape 20 1", 1.0 / 20 ** (1 / 3)),
    "disk20": ("size 1 1 shape 1 20", 1.0 / 400 ** (1 / 3)),
    "tri20": (f"size 1 1 shape {20 ** 0.5:.17g} {20 ** 0.5:.17g}", 1.0 / 20 ** 0.5),
    "nearsphere": (f"size 1 1 shape {rb.NEAR:.17g} {rb.NEAR:.17g}", 1.0 / rb.NEAR),
    "sphere": ("size 1 1 shape 1 1", 1.0),
    "ratio10": ("size 0.2 2 shape 1.4 1.2", 0.2 / (1.4 * 1.44) ** (1 / 3)),
    "delta_r0.9": ("size mean 1 delta_r 0.9 shape 1.4 1.2", 0.1 / (1.4 * 1.44) ** (1 / 3)),
}


def pour_case(tmp_path, name, n, extra_steps):
    words, cmin = POURS[name]
    big = 2.0 * (2.0 if name == "ratio10" else 1.9 if name == "delta_r0.9" else 1.0) * \
        (20 ** (2 / 3) if "20" in name else 1.5)        # largest diameter, roughly
    width = max(12.0, 2.2 * big)
    # the pour keeps each bounding sphere inside the region in z: make it tall enough
    bottom = 0.5
    top = bottom + 6.0 + big
    vmax = math.sqrt(2.0 * top)
    young = E_STIFF if "20" in name else E_MAT
    peak = 0.03 * (young / E_MAT) ** -0.4       # design peak overlap / c_min
    # 20 steps per contact of the thinnest body at the largest speed (tc ~ 3 x peak / v)
    dt = min(2e-3, 3.0 * peak * cmin / vmax / 20.0)
    steps = int(math.sqrt(2.0 * top) / dt) + extra_steps
    work = str(tmp_path)
    lmp = h.new_lammps(work, name)
    law = f"hertz/material {young:g} 0.3 0.5 tangential history 1e4 0.5 rolling constant 0.02"
    for c in [
        "units lj", "atom_style ellipsoid", "atom_modify map array", "boundary p p f",
        "comm_modify vel yes", f"region box block 0 {width} 0 {width} 0 {top + 2 * big}",
        "create_box 1 box", f"region ins block 0 {width} 0 {width} {bottom} {top}",
        "pair_style granular/ellipsoid", f"pair_coeff * * {law}",
        f"fix p all pour/ellipsoid {n} 1 7151 region ins {words} density 1 vol 0.3 400 "
        f"every {steps // 4}",
        "fix g all gravity 1.0 vector 0 0 -1", "fix i all nve/asphere",
        f"fix w all wall/gran/ellipsoid {law} zplane 0 NULL",
        f"timestep {dt:.6g}",
    ]:
        lmp.command(c)
    rb.instrument(lmp, work, max(1, steps // 200))
    lmp.command(f"run {steps}")
    res = rb.analyse(lmp, work, wall_z=0.0)
    inserted = lmp.extract_fix("p", 0, 1, 0)
    lmp.close()
    masses = [rb.mass_of(0.5 * row[17:20]) for row in res["frames"][-1][1]]
    res["ke_bound"] = sum(masses) * 1.0 * top   # the potential energy of the region top
    res["inserted"] = inserted
    res["steps"], res["dt"] = steps, dt
    return res


POUR_N = 100 if rb.LONG else 50


@pytest.mark.parametrize("name", list(POURS))
def test_small_pour(tmp_path, name):
    """50 particles (100 with ELLIPSOID_DEP_LONG) poured onto the floor wall (the region
    holds them all in the first batch; the run lasts the fall time from the region top):
    every inserted particle is kept, the kinetic energy never exceeds the potential energy
    of the region top, overlaps stay below 10 % of the smaller body's smallest semi-axis."""
    res = pour_case(tmp_path, name, POUR_N, 2000 if rb.LONG else 0)
    rb.report(f"pour {name} n {res['inserted']:.0f} steps {res['steps']} dt {res['dt']:.3g} "
           f"ke bound {res['ke_bound']:.4g}", res)
    n = int(res["inserted"])
    assert n >= POUR_N // 2
    rb.assert_robust(res, n, res["ke_bound"], 0.10, min_contacts=10, label=f"pour {name}")
