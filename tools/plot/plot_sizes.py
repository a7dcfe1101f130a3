#!/usr/bin/env python3
"""The paper's Fig. 3 (fig:vr-nr): the volume distribution V(r) and the size distribution n(r).

    ./ellipsoid-dep python tools/plot/plot_sizes.py --from-dump runs/<run>/deposit.dump \
        --out results/study/sizes_N1000_dr0.6.csv      # a deposit's sizes, once
    ./ellipsoid-dep python tools/plot/plot_sizes.py results/study/sizes_N1000_dr0.6.csv \
        --png results/study/figures/fig_sizes.png

V(r) = C (r - rmin)^(alpha-1) / (rmax - r)^(1-beta) on [rmin, rmax] is the total volume of the
particles of size r = (abc)^(1/3) (fix pour/ellipsoid's sampler, src/kernel/
ellipsoid_pour_sampler.h); the number distribution is n(r) ~ V(r) / r^3. Both are drawn here
from their formulas (normalised to 1 numerically) for several alpha, beta at the sizes'
rmin, rmax (size mean R delta_r D: rmin = R (1 - D), rmax = R (1 + D)), with the measured
sizes of a real deposit (alpha = beta = 3) over them and the Kolmogorov-Smirnov test of those
sizes against n(r).
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy import stats  # noqa: E402

SHAPES = ((3, 3, "-"), (1, 1, ":"), (2, 2, "--"), (2, 4, "-."), (4, 2, (0, (5, 1, 1, 1))),
          (1.5, 1.5, (0, (1, 2))))


def volume_density(r, rmin, rmax, alpha, beta):
    """V(r) normalised on [rmin, rmax] (a Beta(alpha, beta) density in r)"""
    return stats.beta.pdf(r, alpha, beta, loc=rmin, scale=rmax - rmin)


def number_density(r, rmin, rmax, alpha, beta):
    """n(r) ~ V(r) / r^3, normalised on [rmin, rmax]"""
    grid = np.linspace(rmin, rmax, 4001)
    norm = np.trapz(volume_density(grid, rmin, rmax, alpha, beta) / grid ** 3, grid)
    return volume_density(r, rmin, rmax, alpha, beta) / r ** 3 / norm


def number_cdf(r, rmin, rmax, alpha, beta):
    grid = np.linspace(rmin, rmax, 4001)
    cdf = np.concatenate([[0], np.cumsum(np.diff(grid) * 0.5 * (
        number_density(grid[1:], rmin, rmax, alpha, beta)
        + number_density(grid[:-1], rmin, rmax, alpha, beta)))])
    return np.interp(r, grid, cdf / cdf[-1])


def sizes_from_dump(dump):
    """r = (abc)^(1/3) of every particle of a deposit.dump (semi-axis columns semi_a_*)"""
    with open(dump) as f:
        lines = f.read().splitlines()
    head = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    cols = lines[head].split()[2:]
    k = [cols.index(c) for c in ("semi_a_x", "semi_a_y", "semi_a_z")]
    rows = [line.split() for line in lines[head + 1:] if line.strip()]
    return np.array([np.prod([float(w[j]) for j in k]) ** (1 / 3) for w in rows])


def write_sizes(dump, out, rmin, rmax, note):
    r = np.sort(sizes_from_dump(dump))
    with open(out, "w") as f:
        f.write("# sizes r = (abc)^(1/3) of the %d particles of a deposit: %s\n" % (len(r), note))
        f.write("# rmin %g rmax %g alpha 3 beta 3\nr\n" % (rmin, rmax))
        f.writelines("%.6f\n" % x for x in r)


def read_sizes(path):
    """(sizes, rmin, rmax) of a file written by write_sizes"""
    with open(path) as f:
        lines = f.read().splitlines()
    words = lines[1].split()
    r = np.array([float(x) for x in lines[3:] if x.strip()])
    return r, float(words[2]), float(words[4])


def figure(sizes_path, png):
    r, rmin, rmax = read_sizes(sizes_path)
    grid = np.linspace(rmin, rmax, 400)[1:-1]
    ks = stats.kstest(r, lambda x: number_cdf(x, rmin, rmax, 3, 3))
    fig, axs = plt.subplots(1, 2, figsize=(9.6, 3.9))
    edges = np.linspace(rmin, rmax, 16)
    axs[0].hist(r, bins=edges, weights=r ** 3 / np.sum(r ** 3) / np.diff(edges)[0],
                color="0.85", edgecolor="0.5", label="deposit, volume-weighted")
    counts, _ = np.histogram(r, bins=edges)
    centres = (edges[1:] + edges[:-1]) / 2
    density = counts / len(r) / np.diff(edges)
    axs[1].bar(centres, density, width=np.diff(edges), color="0.85", edgecolor="0.5",
               label="deposit: %d particles" % len(r))
    axs[1].errorbar(centres, density, yerr=np.sqrt(counts) / len(r) / np.diff(edges),
                    fmt="none", ecolor="0.3", capsize=2)
    for alpha, beta, style in SHAPES:
        label = r"$\alpha$ = %g, $\beta$ = %g" % (alpha, beta)
        lw = 2.0 if (alpha, beta) == (3, 3) else 1.2
        axs[0].plot(grid, volume_density(grid, rmin, rmax, alpha, beta), ls=style, lw=lw,
                    label=label)
        axs[1].plot(grid, number_density(grid, rmin, rmax, alpha, beta), ls=style, lw=lw)
    axs[0].set_ylabel(r"$V(r)$ (normalised)")
    axs[1].set_ylabel(r"$n(r) \propto V(r)/r^3$ (normalised)")
    axs[0].set_ylim(0, 2.6 / (rmax - rmin))
    axs[1].set_ylim(0, 1.25 * max(density.max(), number_density(grid, rmin, rmax, 3, 3).max()))
    dr = (rmax - rmin) / (rmax + rmin)
    for ax, title in zip(axs, ("volume distribution", "size distribution")):
        ax.set_xlabel(r"size $r = (abc)^{1/3}$ ($r_{min}$ = %g, $r_{max}$ = %g, "
                      r"$\delta_r$ = %g)" % (rmin, rmax, dr))
        ax.set_title(title, fontsize=9)
        ax.set_xlim(rmin, rmax)
    axs[0].legend(fontsize=7)
    axs[1].legend(fontsize=7, title="KS test vs n(r), 3, 3: D = %.3f, p = %.2f"
                  % (ks.statistic, ks.pvalue), title_fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)
    return png, ks


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("sizes", nargs="?", help="a sizes file (written by --from-dump)")
    ap.add_argument("--from-dump", help="a deposit.dump: write its sizes to --out")
    ap.add_argument("--out", help="the sizes file to write")
    ap.add_argument("--rmin", type=float, default=0.2, help="in.deposit's at delta_r 0.6")
    ap.add_argument("--rmax", type=float, default=0.8)
    ap.add_argument("--note", default="", help="the deposit's provenance, for the file's head")
    ap.add_argument("--png", help="the figure to write")
    args = ap.parse_args(argv)
    if args.from_dump:
        write_sizes(args.from_dump, args.out, args.rmin, args.rmax, args.note)
        print("plot_sizes: wrote %s" % args.out)
    if args.sizes and args.png:
        png, ks = figure(args.sizes, args.png)
        print("plot_sizes: wrote %s (KS D %.3f, p %.2f)" % (png, ks.statistic, ks.pvalue))
    elif not args.from_dump:
        ap.error("give a sizes file and --png, or --from-dump and --out")


if __name__ == "__main__":
    main()
