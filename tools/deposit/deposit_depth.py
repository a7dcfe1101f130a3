"""Is a deposit deep enough for its measuring slab? tools/deposit/deposit_run.py asks before it runs
in.deposit (which checks the slab it measured after the run: slab_ok in packing.dat), so that a
deposit too shallow is refused with the smallest N for its shape, not measured as phi 0."""
import math

# in.deposit's slab leaves out 3 mean diameters (1 above the ground, 2 below the surface) and
# must be slabmin mean diameters thick (its check after the run: slab_ok in packing.dat)
SLAB_SKIP = 3.0
SLAB_MIN = 1.0
# no poured deposit is denser than the densest random packings of ellipsoids (Donev et al.
# 2004, phi ~ 0.74): a deposit is at least N <v> / (PHI_DENSE L^2) deep
PHI_DENSE = 0.74


def size_moments(dr, alpha=3.0, beta=3.0, radius=0.5, nodes=4000):
    """(mean volume, mean volume-equivalent diameter) of fix pour/ellipsoid's particles, size
    mean 0.5 delta_r dr: the volume distribution V(r) ~ (r - rmin)^(alpha-1) (rmax - r)^(beta-1)
    samples the number distribution n(r) ~ V(r) / r^3 (doc/fix_pour_ellipsoid.rst)"""
    if dr == 0:
        return 4.0 / 3.0 * math.pi * radius ** 3, 2.0 * radius
    rmin, rmax = radius * (1 - dr), radius * (1 + dr)
    w = r2 = r3 = 0.0
    for k in range(nodes):    # midpoint rule in t = (r - rmin) / (rmax - rmin)
        t = (k + 0.5) / nodes
        r = rmin + (rmax - rmin) * t
        v = t ** (alpha - 1) * (1 - t) ** (beta - 1)
        w, r2, r3 = w + v, r2 + v / r ** 2, r3 + v / r ** 3
    return 4.0 / 3.0 * math.pi * w / r3, 2.0 * r2 / r3


def number(st, name, default):
    """the input variable name of the settings' vars as a number (ValueError naming it)"""
    value = st["vars"].get(name, default)
    try:
        return float(value)
    except ValueError:
        raise ValueError("--var %s %s: not a number" % (name, value)) from None


def box_width(st):
    """in.deposit's lateral box edge (its geometry section): width, or 0.3 sqrt(N), at least
    5 d and two neighbour cutoffs of the longest particles (4 bmax + 2 skin)"""
    width = number(st, "width", 0)
    bmax = 0.5 * (1 + st["dr"]) * (st["eta"] ** 2 * st["zeta"]) ** (1.0 / 3.0)
    least = max(4 * bmax + 2 * 0.2, 5.0)
    return max(width if width > 0 else 0.3 * math.sqrt(st["N"]), least)


def too_shallow(st):
    """None, or why the deposit would be too shallow for its measuring slab and the smallest N
    that makes it deep enough at this shape (or the width to give when no N does)"""
    slabmin = number(st, "slabmin", SLAB_MIN)
    if slabmin <= 0:
        return None
    volume, d = size_moments(st["dr"])
    need = (SLAB_SKIP + slabmin) * d
    def depth(n):
        return n * volume / (PHI_DENSE * box_width(dict(st, N=n)) ** 2)
    if depth(st["N"]) >= need:
        return None
    why = ("--N %d is too few for eta %g zeta %g dr %g: the deposit may be only %.2f d deep in "
           "its %.3g d wide box, and the measuring slab needs %.2f d (%g + slabmin %g mean "
           "diameters %.3f)" % (st["N"], st["eta"], st["zeta"], st["dr"], depth(st["N"]),
                                box_width(st), need, SLAB_SKIP, slabmin, d))
    # at a fixed edge L the depth grows as N; the 0.3 sqrt(N) edge grows with N and keeps the
    # depth it has where it overtakes the least edge
    edge = box_width(dict(st, N=1))
    n = int(math.ceil(need * PHI_DENSE * edge ** 2 / volume))
    if number(st, "width", 0) > 0 or 0.3 * math.sqrt(n) <= edge:
        return why + "; give --N %d or more" % n
    return why + ("; the 0.3 sqrt(N) box keeps it that shallow at any N: give a narrower box, "
                  "--var width %.4g with --N %d or more" % (edge, n))
