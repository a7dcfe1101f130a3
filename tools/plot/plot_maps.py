"""The maps over (eta, zeta) of tools/plot/plot_figures.py (the paper's Figs. 5a and 6).

Left: the measured means interpolated (cubic, scipy griddata; nearest at the hull's edge) on
a fine grid, with contours, every measured point marked and the 8 x 8 grid's values written
beside it; the highest point is a star, the points within 2 standard errors of it are ringed.
Right: each point's standard error (its group's pooled seed SD / sqrt(its seeds)), each
point's cell its own (nearest), with the groups' SDs and degrees of freedom.
"""
import math

import matplotlib.patheffects as pe
import matplotlib.pyplot as plt
import numpy as np
from scipy.interpolate import griddata

GRID = (1.0, 1.2, 1.4, 1.6, 1.8, 2.0, 2.5, 3.0)    # the map's labelled grid


def interpolate(points, values, method):
    """values at the measured points on a 241 x 241 grid over their bounding box"""
    lo, hi = points.min(axis=0), points.max(axis=0)
    e, z = np.meshgrid(np.linspace(lo[0], hi[0], 241), np.linspace(lo[1], hi[1], 241))
    grid = griddata(points, values, (e, z), method=method)
    holes = np.isnan(grid)
    if holes.any():    # the hull's edge, by round-off
        grid[holes] = griddata(points, values, (e[holes], z[holes]), method="nearest")
    return e, z, grid


def groups_text(pooled, fmt, sep="; "):
    """the groups' pooled SDs; fmt: that of the values (the SD gets one digit more)"""
    digits = int(fmt.strip("%f").split(".")[1]) + 1
    return sep.join("%s: s = %.*f (%d dof, %d shapes)" % (g, digits, v["sd"], v["dof"],
                                                          v["shapes"])
                    for g, v in sorted(pooled.groups.items()) if v["sd"] is not None)


def value_panel(ax, fig, pooled, shapes, fmt, label):
    pts = np.array(shapes)
    vals = np.array([pooled.mean(s) for s in shapes])
    e, z, grid = interpolate(pts, vals, "cubic")
    m = ax.contourf(e, z, grid, levels=40, cmap="viridis")
    cs = ax.contour(e, z, grid, levels=10, colors="k", linewidths=0.4, alpha=0.6)
    ax.clabel(cs, fontsize=6, fmt=fmt)
    ax.plot(pts[:, 0], pts[:, 1], "o", ms=2.5, color="w", mec="k", mew=0.4)
    k = int(np.argmax(vals))
    top, se_top = shapes[k], pooled.se(shapes[k])
    near = [s for s in shapes if s != top and se_top is not None and pooled.se(s) is not None
            and pooled.mean(top) - pooled.mean(s) < 2 * math.hypot(se_top, pooled.se(s))]
    ax.plot(*top, marker="*", ms=13, color="crimson", mec="w", mew=0.6, ls="none",
            label="highest: %s at (%g, %g)" % (fmt % pooled.mean(top), *top))
    if near:
        ax.plot(*np.array(near).T, "o", ms=9, mfc="none", mec="crimson", mew=1.0, ls="none",
                label="within 2 standard errors of it")
    stroke = [pe.withStroke(linewidth=1.8, foreground="w")]
    top_row = pts[:, 1].max()
    for s in shapes:
        if s[0] in GRID and s[1] in GRID:    # above the point, below it on the top row
            below = s[1] == top_row
            ax.text(s[0], s[1] + (-0.045 if below else 0.045), fmt % pooled.mean(s),
                    ha="center", va="top" if below else "bottom", fontsize=5.5,
                    path_effects=stroke)
    ax.plot([1, 3], [1, 3], "w--", lw=0.7)
    fig.colorbar(m, ax=ax, label=label)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)


def error_panel(ax, fig, pooled, shapes, fmt, label):
    pts = np.array(shapes)
    se = np.array([pooled.se(s) for s in shapes], float)
    e, z, grid = interpolate(pts, se, "nearest")    # each point's own: no smoothing
    m = ax.pcolormesh(e, z, grid, shading="auto", cmap="magma_r")
    ax.scatter(pts[:, 0], pts[:, 1], c=se, cmap="magma_r", vmin=grid.min(), vmax=grid.max(),
               s=[12 * len(pooled.values[s]) for s in shapes], edgecolors="k", linewidths=0.4)
    fig.colorbar(m, ax=ax, label="standard error of " + label)
    ax.set_title("standard error: the group's pooled seed SD / sqrt(seeds) (marker size: seeds)",
                 fontsize=8)
    ax.text(0.5, -0.13, groups_text(pooled, fmt, "\n"), transform=ax.transAxes, ha="center",
            va="top", fontsize=7)


def on_map(shapes):
    """the shapes inside the square the off-diagonal shapes span: the diagonal's points
    beyond it (the fall-back's a/c 12 and 16) would stretch the interpolation over a plane
    with no points (they are on the line figures)"""
    reach = max((max(s) for s in shapes if s[0] != s[1]), default=math.inf)
    return [s for s in sorted(shapes) if max(s) <= reach]


def map_figure(pooled, path, label, title, fmt):
    """pooled: study_stats.Pooled of one quantity at one selection; path: the PNG"""
    shapes = on_map(pooled.values)
    pts = np.array(shapes, float)
    if len(pts) < 4 or np.linalg.matrix_rank(pts - pts.mean(axis=0)) < 2:
        print("  %s: skipped (needs shapes that span the plane, not a line)" % path)
        return None
    fig, axs = plt.subplots(1, 2, figsize=(12.5, 6.0))
    value_panel(axs[0], fig, pooled, shapes, fmt, label)
    axs[0].set_title(title, fontsize=9)
    if all(pooled.se(s) is not None for s in shapes):
        error_panel(axs[1], fig, pooled, shapes, fmt, label)
    else:
        axs[1].set_axis_off()
    for ax in axs:
        ax.set_xlabel(r"$\eta = a/b$")
        ax.set_ylabel(r"$\zeta = b/c$")
        ax.set_aspect("equal")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
