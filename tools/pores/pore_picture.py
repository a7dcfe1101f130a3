"""The picture of tools/pores/pores.py (pores.png): sections of the pore space coloured by local
thickness, the pore size distribution and the porosity profile, voxel layers against the exact
closed form."""
import numpy as np

from pore_surface import slab_fraction


def plot(result, particles, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    grid = result["_grid"]
    solid, thick = result["_solid_slab"], result["_thickness"]
    zlo, zhi = result["slab"]["zlo"], result["slab"]["zhi"]
    lx, ly = grid.nx * grid.hx, grid.ny * grid.hy
    fig, ax = plt.subplots(2, 2, figsize=(10, 8.5))
    fig.subplots_adjust(hspace=0.35)
    show = np.ma.masked_where(solid, thick)
    cmap = plt.get_cmap("viridis").copy()
    cmap.set_bad("0.75")
    vmax = max(float(thick.max()), 1e-12)
    im = ax[0, 0].imshow(show[:, grid.ny // 2, :].T, origin="lower", cmap=cmap, vmin=0,
                         vmax=vmax, extent=(0, lx, zlo, zhi), aspect="equal")
    ax[0, 0].set(xlabel="x", ylabel="z", title="vertical section y = Ly/2 (grey: solid)")
    ax[0, 1].imshow(show[:, :, grid.nslab // 2].T, origin="lower", cmap=cmap, vmin=0, vmax=vmax,
                    extent=(0, lx, 0, ly), aspect="equal")
    ax[0, 1].set(xlabel="x", ylabel="y", title="horizontal section, middle of the slab")
    fig.colorbar(im, ax=ax[0, :], label="local thickness (pore radius)", shrink=0.8)
    psd = result["pore_size_distribution"]
    ax[1, 0].bar(psd["radius"], psd["volume_fraction"], width=psd["bin_width"], color="C0")
    ax[1, 0].axvline(result["mean_pore_radius"], color="k", ls="--", label="mean")
    ax[1, 0].set(xlabel="pore radius (local thickness)", ylabel="fraction of pore volume",
                 title="pore size distribution (voxel %.3g)" % result["voxel_size"])
    ax[1, 0].legend(fontsize=8)
    # porosity profile: voxel layers and the exact closed form in the same layers
    z = zlo + (np.arange(grid.nslab) + 0.5) * grid.hz
    layers = 1 - solid.mean(axis=(0, 1))
    ax[1, 1].plot(layers, z, lw=0.8, label="voxel layers")
    edges = np.linspace(zlo, zhi, min(grid.nslab, 60) + 1)
    exact = [1 - (slab_fraction(particles, a, b) * particles.volumes).sum() / (lx * ly * (b - a))
             for a, b in zip(edges[:-1], edges[1:])]
    ax[1, 1].stairs(exact, edges, orientation="horizontal", color="k", baseline=None,
                    label="exact (closed form)")
    ax[1, 1].axvline(result["porosity"], color="gray", ls=":", label="slab porosity")
    lo, hi = min(min(exact), layers.min()), max(max(exact), layers.max())
    ax[1, 1].set_xlim(lo - 0.1 * (hi - lo + 0.01), hi + 0.1 * (hi - lo + 0.01))
    ax[1, 1].set(xlabel="porosity", ylabel="z", title="porosity profile inside the slab")
    ax[1, 1].legend(fontsize=8)
    fig.suptitle("%s  porosity %.4f  S_v %.4g  k_KC %.3g" % (
        title, result["porosity"], result["specific_surface"],
        result["kozeny_carman_permeability"]), fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)
