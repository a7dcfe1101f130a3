"""The cost curve's extrapolation to a deposit of 10^6 particles (cost_table.py's last line):
from the largest N measured, the CPU time per particle-step with its communication share scaled
by the ghosts per owned atom of the new subdomains, and the steps to rest from their fitted
exponent in N."""
import math


def ghost_width(ratio, a, b):
    """the ghost shell's width w from the ghosts per owned atom of an a x b subdomain with
    ghosts on its four sides in x and y (none in z): (a + 2w)(b + 2w) = (1 + ratio) a b"""
    return (-(a + b) + math.sqrt((a + b) ** 2 + 4 * ratio * a * b)) / 4


def ghost_ratio(w, a, b):
    """the ghosts per owned atom of an a x b subdomain with a ghost shell of width w"""
    return ((a + 2 * w) * (b + 2 * w) - a * b) / (a * b)


def rank_grid(p):
    """processors * * 1 on a square box: the ranks along x and y, as near a square as p has"""
    py = max(d for d in range(1, int(math.isqrt(p)) + 1) if p % d == 0)
    return p // py, py


def base_size(sizes):
    """the (N, ranks) the extrapolation starts from: the largest N measured on several ranks,
    else on one"""
    return max(sizes, key=lambda s: (s[1] > 1, s[0]), default=None)


def extrapolate(sizes, steps_exponent, n=10 ** 6, cores=(2, 64)):
    """a deposit of n particles on each number of cores, from the largest N measured on
    several ranks (else on one): the CPU time per particle-step with its communication share
    scaled by the ghosts per owned atom of the new subdomains (the ghost shell's width from the
    measured ratio), the steps to rest from the fitted exponent. None without a box and grid;
    else {"base": (N, ranks), "width", "steps", "cores": {p: (grid, ghost ratio, us per
    particle-step, hours)}}"""
    base = base_size(sizes)
    if base is None or sizes[base]["box"] is None or sizes[base]["grid"] is None:
        return None
    v = sizes[base]
    (lx, ly), (px, py) = v["box"], v["grid"]
    w = ghost_width(v["ghost_ratio"], lx / px, ly / py)
    steps = v["steps"] * (n / base[0]) ** (steps_exponent or 0.0)
    scale = math.sqrt(n / base[0])    # the box's edge grows as sqrt(N)
    out = {"base": base, "width": w, "steps": steps, "cores": {}}
    for p in cores:
        grid = rank_grid(p)
        g = ghost_ratio(w, scale * lx / grid[0], scale * ly / grid[1])
        t = v["us_per_particle_step"] * (1 - v["comm_share"] +
                                          v["comm_share"] * g / v["ghost_ratio"])
        out["cores"][p] = (grid, g, t, t * 1e-6 * n * steps / p / 3600)
    return out


def extrapolation(sizes, steps_exponent, n=10 ** 6):
    """extrapolate()'s answer in words"""
    e = extrapolate(sizes, steps_exponent, n)
    if e is None:
        return ""
    v = sizes[e["base"]]
    parts = ["on %d cores (%d x %d ranks, %.2f ghosts per owned particle) %.2f us per "
             "particle-step, %.1f hours" % (p, grid[0], grid[1], g, t, hours)
             for p, (grid, g, t, hours) in e["cores"].items()]
    if steps_exponent is None:
        steps = "%.0f steps to rest (one size at its rank count: no exponent fitted, the " \
                "steps held at the measured)" % e["steps"]
    else:
        steps = "%.0f steps to rest (%.0f steps times (%.0e / %d)^%.3f, the fitted exponent)" \
                % (e["steps"], v["steps"], n, e["base"][0], steps_exponent)
    return ("A deposit of %.0e particles, from N = %d on %d rank%s (%.2f us per particle-step, "
            "communication %.3f of the loop at %.2f ghosts per owned particle: a ghost shell "
            "%.2f d wide) and %s: %s; LAMMPS's memory estimate %.1f GB in all (%.1f kB per "
            "particle). The communication's time is taken as proportional to the ghosts (no "
            "latency, no load imbalance): a lower bound on the time."
            % (n, e["base"][0], e["base"][1], "s" if e["base"][1] > 1 else "",
               v["us_per_particle_step"], v["comm_share"], v["ghost_ratio"], e["width"],
               steps, "; ".join(parts), v["kb_per_particle"] * n / 1024 ** 2,
               v["kb_per_particle"]))
