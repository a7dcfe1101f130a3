"""The permeability of a deposit from flow solves (tools/pores/pore_flow.py) at several voxel sizes,
extrapolated to a vanishing voxel (tools/pores/pore_flow_fit.py); doc/howto_pores.md.

    flow_permeability(particles, box, zlo, zhi) -> {"xx", "yy", "zz" (k0 in d^2), errors,
                                                    "resolutions": [...], "domain", ...}

The flow domain is the slab [zlo, zhi] of the deposit, or a box cut out of it: side L in x and
y (at the slab's centre unless told where), the slab's height cut to L about its middle. The
slab is periodic in x and y; a cut box is not, so it is treated in x and y as the slab is in
z: mirrored for the flow along the axis, symmetry planes for the flow across it.
"""
import copy
import json
import os

import numpy as np

import pore_flow
from pore_flow_fit import extrapolate
from pore_surface import box_part, kozeny_carman
from pore_voxels import Grid, check_memory, periodic_labels, voxelize

# the default voxels, fractions of the smallest semi-axis: d/13, d/16, d/20 for spheres (a
# geometric progression; at d/10 a lattice's contacts are still 12 to 18 % off after the
# offsets' mean, finer costs too much: howto)
FLOW_VOXEL_FRACTIONS = (1.0 / 6.5, 0.125, 0.1)
MAX_FLOW_VOXEL_FRACTION = 1.0  # the flow needs at least 2 voxels across the thinnest particle
# each voxel's k is the mean over offsets of the grid (fractions of a voxel in x and y; the
# first: the grid on the domain's corner): a lattice's k at one voxel changes with where its
# contacts fall between the voxel centres by up to 55 % (howto, "Voxels, offsets and the
# extrapolation"), the mean far less. Two offsets, and all FLOW_OFFSET_COUNT of them unless
# the two agree: each direction's standard error of the mean within OFFSET_PRECISION of it.
# The mean of two that agree is known to OFFSET_PRECISION, not to their standard error (one
# degree of freedom, and 0 where the two images coincide): that is its error.
OFFSETS = ((0.0, 0.0), (0.5, 0.5), (0.0, 0.5), (0.5, 0.0))
FLOW_OFFSET_COUNT = 4
OFFSET_PRECISION = 0.01
FLOW_BOX = 5.0    # side of the cut box in d (the slab itself when the deposit is not wider)
# the flow's voxel image and its labels, before OpenFOAM's mesh (a lower bound of its memory)
FLOW_IMAGE_BYTES = 16


def volume_diameter(particles):
    """d: the mean volume-equivalent diameter, the length unit of the permeabilities"""
    return float(np.mean(2.0 * np.cbrt(np.prod(particles.semi, axis=1))))


class Domain:
    """the flow domain: x, y, z ranges and which of x, y are periodic (z never is)"""

    def __init__(self, x, y, z, periodic_xy):
        self.ranges = (tuple(map(float, x)), tuple(map(float, y)), tuple(map(float, z)))
        self.periodic = tuple(periodic_xy) + (False,)

    def shifted(self, dx, dy):
        """the same domain moved by (dx, dy) horizontally"""
        (x0, x1), (y0, y1), z = self.ranges
        return Domain((x0 + dx, x1 + dx), (y0 + dy, y1 + dy), z, self.periodic[:2])

    @classmethod
    def described(cls, desc):
        """the domain of describe()'s dict (a solve's json)"""
        return cls(desc["x"], desc["y"], desc["z"], desc["periodic"][:2])

    def describe(self, d):
        sides = [r[1] - r[0] for r in self.ranges]
        return {"kind": "slab" if all(self.periodic[:2]) else "box",
                "x": list(self.ranges[0]), "y": list(self.ranges[1]), "z": list(self.ranges[2]),
                "sides_d": [s / d for s in sides], "periodic": list(self.periodic)}


def flow_domain(box, zlo, zhi, d, side=FLOW_BOX, at=None):
    """the box of side side * d centred at at = (x, y) (default: the box's centre) and at the
    slab's mid-height, its height at most the slab's; the whole width of an axis whose box
    edge is not longer than the side (side 0 or None: the slab)"""
    length = (side or 0.0) * d
    centre = [0.5 * (box[a, 0] + box[a, 1]) for a in (0, 1)] if at is None else list(at)
    ranges, periodic = [], []
    for a in (0, 1):
        edge = box[a, 1] - box[a, 0]
        whole = not 0 < length < edge
        periodic.append(whole)
        ranges.append((box[a, 0], box[a, 1]) if whole
                      else (centre[a] - 0.5 * length, centre[a] + 0.5 * length))
    z = (zlo, zhi)
    if not all(periodic) and length < zhi - zlo:
        mid = 0.5 * (zlo + zhi)
        z = (mid - 0.5 * length, mid + 0.5 * length)
    return Domain(ranges[0], ranges[1], z, periodic)


def domain_medium(particles, box, domain, d):
    """the flow domain's own porous medium: its porosity, specific surface (per length) and
    Kozeny-Carman k in d^2, from the exact parts of the particles (and their periodic images)
    inside it (pore_surface.box_part), so that k / k_KC compares one volume with itself"""
    inside = images_in(particles, box, domain)
    fractions, areas, change = box_part(inside, domain.ranges)
    volume = float(np.prod([r[1] - r[0] for r in domain.ranges]))
    porosity = 1.0 - float(fractions @ inside.volumes) / volume
    s_v = float(areas.sum()) / volume
    return {"porosity": porosity, "specific_surface": s_v,
            "kozeny_carman": kozeny_carman(porosity, s_v) / d ** 2,
            "quadrature_relative_change": change}


def images_in(particles, box, domain):
    """the particles and their periodic images in x and y that reach into the domain"""
    keep, shifts = [], []
    lengths = box[:2, 1] - box[:2, 0]
    for i in (-1, 0, 1):
        for j in (-1, 0, 1):
            shift = np.array([i * lengths[0], j * lengths[1], 0.0])
            c = particles.centres + shift
            inside = np.ones(len(particles), bool)
            for a in (0, 1):
                lo, hi = domain.ranges[a]
                inside &= (c[:, a] + particles.half_extent[:, a] > lo) & (
                    c[:, a] - particles.half_extent[:, a] < hi)
            keep.append(np.flatnonzero(inside))
            shifts.append(np.tile(shift, (inside.sum(), 1)))
    index = np.concatenate(keep)
    out = copy.copy(particles)
    for name in ("semi", "rotations", "inverse_form", "form", "half_extent"):
        setattr(out, name, getattr(particles, name)[index])
    out.centres = particles.centres[index] + np.concatenate(shifts)
    return out


def domain_grid(box, domain, voxel):
    """the voxel grid of the domain; a ValueError when its image would not fit in memory"""
    x, y, z = domain.ranges
    grid = Grid(np.array([x, y, box[2]]), z[0], z[1], voxel, margin=0.0)
    check_memory(grid, voxel, FLOW_IMAGE_BYTES, "--flow-voxel")
    return grid


def flow_image(particles, box, domain, voxel, progress, offset=(0.0, 0.0)):
    """the domain's voxel image at voxel, its grid moved by offset (fractions of a voxel in x
    and y; pore voxels off the largest pore cluster joining the bottom to the top filled)
    -> (solid, spacing, filled fraction of the pore voxels)"""
    grid = domain_grid(box, domain, voxel)
    if any(offset):
        domain = domain.shifted(offset[0] * grid.hx, offset[1] * grid.hy)
        grid = domain_grid(box, domain, voxel)
    if all(domain.periodic[:2]):
        solid = voxelize(particles, grid, progress)
    else:
        solid = voxelize(images_in(particles, box, domain), grid, progress, periodic=False)
    solid = solid[:, :, grid.slab]
    labels, _ = periodic_labels(~solid, domain.periodic[:2])
    spanning = np.intersect1d(labels[:, :, 0][labels[:, :, 0] > 0],
                              labels[:, :, -1][labels[:, :, -1] > 0])
    if not spanning.size:
        raise ValueError("no connected pore path from the bottom to the top of the flow domain "
                         "at the flow voxel %.4g: no flow along z (a smaller --flow-voxel may "
                         "open one)" % voxel)
    # pores off the largest cluster joining bottom and top carry no flow or, as a separate
    # cluster, have no pressure reference and would stop the solver: they are filled
    sizes = np.bincount(labels.ravel())
    connected = labels == spanning[np.argmax(sizes[spanning])]
    filled = float((~solid & ~connected).sum() / max((~solid).sum(), 1))
    return ~connected, grid.spacing, filled


def grid_offsets(count):
    """at most the first count of OFFSETS; a ValueError for another count"""
    if count not in (1, 2, 4):
        raise ValueError("--flow-offsets %s: needs 1, 2 or 4" % count)
    return OFFSETS[:count]


def check_voxels(voxels, smallest):
    for voxel in voxels:
        if not 0 < voxel <= MAX_FLOW_VOXEL_FRACTION * smallest:
            raise ValueError("flow voxel %.4g: needs 0 < voxel <= %g x the smallest semi-axis "
                             "(%.4g)" % (voxel, MAX_FLOW_VOXEL_FRACTION,
                                         MAX_FLOW_VOXEL_FRACTION * smallest))


def offsets_agree(solves, directions):
    """whether the offsets solved so far fix the mean: each direction's standard error of
    the mean within OFFSET_PRECISION of it"""
    return all(standard_error([s[key] for s in solves])
               <= OFFSET_PRECISION * np.mean([s[key] for s in solves]) for key in directions)


def offsets_taken(solves, directions):
    """the solves the rule takes out of offsets solved in order: the first two when they
    agree, all otherwise"""
    return solves[:2] if offsets_agree(solves[:2], directions) else solves


def offset_error(values, agreed):
    """the error of the mean over the offsets' values: their standard error, at least
    OFFSET_PRECISION of the mean where the rule stopped at two that agree"""
    se = standard_error(values)
    return max(se, OFFSET_PRECISION * abs(float(np.mean(values)))) if agreed else se


def resolution(particles, box, domain, voxel, d, offsets, directions, progress, workdir,
               solved=None):
    """k / d^2 at one voxel: the mean over the grid's offsets (the first two, the others
    while they disagree), its standard error, and each offset's solve; solved: a folder that
    keeps each solve (a rerun takes them from there instead of solving again)"""
    solves = []
    for n, offset in enumerate(offsets):
        if n >= 2 and offsets_agree(solves, directions):
            break
        kept = solved and os.path.join(solved, "d%.6g_offset%d_%s.json" % (
            d / voxel, n + 1, "_".join(directions)))
        if kept and os.path.exists(kept):
            with open(kept) as f:
                solves.append(json.load(f))
            continue
        solid, spacing, filled = flow_image(particles, box, domain, voxel, progress, offset)
        label = "d/%.3g" % (d / voxel) + (" offset %d" % (n + 1) if len(offsets) > 1 else "")
        k = pore_flow.permeability(solid, spacing, directions, progress, workdir,
                                   domain.periodic, label=label)
        s = {key: k[key] / d ** 2 for key in directions}
        s.update({"offset": list(map(float, offset)), "porosity_voxel": float(1 - solid.mean()),
                  "filled_pore_fraction": filled})
        for key in ("cells", "iterations", "residuals", "seconds", "solver_cpu_seconds",
                    "ranks", "image_xyz"):
            s[key] = k[key]
        s["anisotropy_xx_zz"] = anisotropy(s)
        solves.append(s)
        if kept:
            os.makedirs(solved, exist_ok=True)
            with open(kept, "w") as f:
                json.dump(s, f)
    r = {"voxel": voxel, "voxels_per_d": d / voxel, "image_xyz": solves[0]["image_xyz"],
         "offsets": solves}
    for key in list(directions) + ["porosity_voxel", "filled_pore_fraction"]:
        r[key] = float(np.mean([s[key] for s in solves]))
    agreed = len(solves) == 2 and offsets_agree(solves, directions)
    for key in directions:
        r[key + "_offset_error"] = offset_error([s[key] for s in solves], agreed)
    r["anisotropy_xx_zz"] = anisotropy(r)
    r["anisotropy_xx_zz_offset_error"] = (None if r["anisotropy_xx_zz"] is None else
                                          offset_error([s["anisotropy_xx_zz"] for s in solves],
                                                       agreed))
    r["cells"] = solves[0]["cells"]    # the others differ by the voxels an offset moves
    r["ranks"] = solves[0]["ranks"]
    r["iterations"] = {key: max(s["iterations"][key] for s in solves) for key in directions}
    r["residuals"] = {key: {c: max(s["residuals"][key][c] for s in solves)
                            for c in solves[0]["residuals"][key]} for key in directions}
    for key in ("seconds", "solver_cpu_seconds"):
        r[key] = {k: sum(s[key][k] for s in solves) for k in directions}
    return r


def standard_error(values):
    """of the mean of values (0 for one value)"""
    n = len(values)
    return float(np.std(values, ddof=1) / np.sqrt(n)) if n > 1 else 0.0


def flow_permeability(particles, box, zlo, zhi, voxels=None, progress=None, workdir=None,
                      directions=("xx", "yy", "zz"), side=FLOW_BOX, at=None,
                      offset_count=FLOW_OFFSET_COUNT, solved=None):
    """k along directions in units of d^2: at each voxel (default FLOW_VOXEL_FRACTIONS of the
    smallest semi-axis) the mean over the grid's offsets (fractions of a voxel in x and y),
    and with three or more voxels extrapolated to a vanishing voxel"""
    progress = progress or (lambda msg: None)
    smallest = float(particles.semi.min())
    if voxels is None:
        voxels = [f * smallest for f in FLOW_VOXEL_FRACTIONS]
    voxels = sorted(map(float, voxels), reverse=True)    # the coarsest, quickest first
    check_voxels(voxels, smallest)
    offsets = grid_offsets(offset_count)
    d = volume_diameter(particles)
    domain = flow_domain(box, zlo, zhi, d, side, at)
    for voxel in voxels:    # before any solve: the finest may not fit
        domain_grid(box, domain, voxel)
    pore_flow.require_openfoam()
    progress("flow domain: %s, %s d; voxels d/%s" % (
        domain.describe(d)["kind"], " x ".join("%.3g" % s for s in domain.describe(d)["sides_d"]),
        ", d/".join("%.3g" % (d / v) for v in voxels)))
    resolutions = [resolution(particles, box, domain, voxel, d, offsets, directions, progress,
                              workdir, solved) for voxel in voxels]
    out = {"units": "d^2", "d": d, "domain": domain.describe(d), "resolutions": resolutions,
           "tolerance": pore_flow.TOLERANCE}
    if len(resolutions) >= 3:
        out["extrapolation"] = {}
        for key in directions:
            e = extrapolate(voxels, [r[key] for r in resolutions],
                            [r[key + "_offset_error"] for r in resolutions])
            out[key], out[key + "_error"] = e["k0"], e["error"]
            out["extrapolation"][key] = e
        if resolutions[0]["anisotropy_xx_zz"] is not None:
            e = extrapolate(voxels, [r["anisotropy_xx_zz"] for r in resolutions],
                            [r["anisotropy_xx_zz_offset_error"] for r in resolutions])
            out["anisotropy_xx_zz"], out["anisotropy_xx_zz_error"] = e["k0"], e["error"]
            out["extrapolation"]["anisotropy_xx_zz"] = e
    else:
        out.update({key: resolutions[-1][key] for key in directions})
        out["anisotropy_xx_zz"] = resolutions[-1]["anisotropy_xx_zz"]
    add_medium(out, particles, box)
    return out


def add_medium(k, particles, box):
    """k (flow_permeability's result, or one solved before it held them) gets its domain's
    own medium and k over that medium's Kozeny-Carman k per direction solved"""
    k["medium"] = domain_medium(particles, box, Domain.described(k["domain"]), k["d"])
    k["ratio_to_kozeny_carman"] = {key: k[key] / k["medium"]["kozeny_carman"]
                                   for key in ("xx", "yy", "zz") if key in k}


def anisotropy(k):
    """(k_xx + k_yy) / (2 k_zz), k_xx / k_zz without k_yy; None without k_zz or k_xx"""
    if "zz" not in k or "xx" not in k:
        return None
    horizontal = 0.5 * (k["xx"] + k["yy"]) if "yy" in k else k["xx"]
    return horizontal / k["zz"]
