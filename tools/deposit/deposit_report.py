"""The default deposit's report (tools/deposit/deposit_run.py): the summary it prints and its plots,
PNGs with matplotlib (Agg) from the run's data, which deposit_run reads from its files
(read_histo, read_packing).

    contact_histo.png   P(Omega(theta)) of the contact normals, geometric and weighted by the
                        normal force, and the mean normal force per angle bin over <f>
    orient_histo.png    P(Omega(theta)) of the long axes
    force_histo.png     P(f/<f>) of the normal contact forces
    profile.png         phi(z) with the slab
"""
import math
import os

ISOTROPIC = 1.0 / (4.0 * math.pi)


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _theta_axis(ax, xlabel):
    ax.set_xlim(0, math.pi)
    ax.set_xticks([0, math.pi / 4, math.pi / 2, 3 * math.pi / 4, math.pi])
    ax.set_xticklabels(["0", r"$\pi/4$", r"$\pi/2$", r"$3\pi/4$", r"$\pi$"])
    ax.set_xlabel(xlabel)


def _save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    _pyplot().close(fig)
    return path


def plot_orientations(path, title, histo):
    """histo: (theta, P, fraction) of the long axes"""
    plt = _pyplot()
    theta, p = histo[0], histo[1]
    fig, ax = plt.subplots(figsize=(5.0, 3.6))
    ax.plot(theta, p, "o-", label="deposit")
    ax.axhline(ISOTROPIC, color="gray", ls="--", label=r"isotropic $1/4\pi$")
    _theta_axis(ax, r"$\theta$ (long axis a vs +z)")
    ax.set_ylabel(r"$P(\Omega(\theta))$")
    ax.set_title("long axes: %s" % title, fontsize=9)
    ax.legend(fontsize=8)
    return _save(fig, path)


def plot_contacts(path, title, geometric, weighted=None):
    """geometric: (theta, P, fraction) of contact/histo; weighted: (theta, P_f, fraction,
    mean |f_n| per bin) of contact/histo weight force, or None (a run without forces)"""
    plt = _pyplot()
    ncols = 1 if weighted is None else 2
    fig, axes = plt.subplots(1, ncols, figsize=(5.0 * ncols, 3.6), squeeze=False)
    ax = axes[0][0]
    ax.plot(geometric[0], geometric[1], "o-", label="contact normals")
    if weighted is not None:
        ax.plot(weighted[0], weighted[1], "s-", label="weighted by the normal force")
    ax.axhline(ISOTROPIC, color="gray", ls="--", label=r"isotropic $1/4\pi$")
    _theta_axis(ax, r"$\theta$ (contact normal vs +z)")
    ax.set_ylabel(r"$P(\Omega(\theta))$")
    ax.set_title("contact normals: %s" % title, fontsize=9)
    ax.legend(fontsize=8)
    if weighted is not None:
        # the mean force per bin over the mean of all samples: P_f / P (bins without contacts
        # are left out)
        theta, fraction, mean_f = weighted[0], geometric[2], weighted[3]
        total = sum(f * m for f, m in zip(fraction, mean_f))
        ax = axes[0][1]
        kept = [(t, m / total) for t, f, m in zip(theta, fraction, mean_f) if f > 0 and total > 0]
        ax.plot([t for t, _ in kept], [r for _, r in kept], "s-", color="C1")
        ax.axhline(1.0, color="gray", ls="--")
        _theta_axis(ax, r"$\theta$ (contact normal vs +z)")
        ax.set_ylabel(r"mean $|f_n|$ in the bin / $\langle f_n \rangle$")
        ax.set_title("normal force by direction", fontsize=9)
    return _save(fig, path)


def plot_force_distribution(path, title, histo):
    """histo: (f/<f>, P, fraction) of force/histo"""
    plt = _pyplot()
    x, p = histo[0], histo[1]
    fig, ax = plt.subplots(figsize=(5.0, 3.6))
    shown = [(a, b) for a, b in zip(x, p) if b > 0]
    if shown:
        ax.semilogy([a for a, _ in shown], [b for _, b in shown], "o-", label="deposit")
        top = x[-1] + (x[1] - x[0]) / 2 if len(x) > 1 else 1.0
        grid = [top * k / 100 for k in range(101)]
        ax.semilogy(grid, [math.exp(-g) for g in grid], color="gray", ls="--",
                    label=r"$e^{-f/\langle f\rangle}$ (for reference)")
        ax.legend(fontsize=8)
    ax.set_xlabel(r"$f_n / \langle f_n \rangle$")
    ax.set_ylabel(r"$P(f_n/\langle f_n\rangle)$")
    ax.set_title("normal contact forces: %s" % title, fontsize=9)
    return _save(fig, path)


def plot_profile(path, title, profile, pk):
    """phi(z) of compute packing/profile (profile: z, phi, ...) with the slab of packing.dat"""
    plt = _pyplot()
    z, phi = profile[0], profile[1]
    fig, ax = plt.subplots(figsize=(4.2, 5.0))
    ax.plot(phi, z, "-", lw=1, label=r"$\phi(z)$")
    ax.axhspan(pk["zlo"], pk["zhi"], color="C1", alpha=0.15, label="slab of packing.dat")
    ax.axvline(pk["phi"], color="gray", ls="--", label=r"$\phi$ of the slab")
    ax.set_xlabel(r"solid fraction $\phi(z)$")
    ax.set_ylabel("z")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    return _save(fig, path)


def plot_run(out, title, pk, read_histo):
    """every plot of a run folder (read_histo(path, columns): deposit_run's reader of the fix
    ave/time files); the force plots when the run wrote their files"""
    def data(name, columns=3):
        path = os.path.join(out, name + ".dat")
        return read_histo(path, columns) if os.path.exists(path) else None

    written = [plot_orientations(os.path.join(out, "orient_histo.png"), title,
                                 data("orient_histo"))]
    written.append(plot_contacts(os.path.join(out, "contact_histo.png"), title,
                                 data("contact_histo"), data("contact_force_histo", 4)))
    forces = data("force_histo")
    if forces is not None:
        written.append(plot_force_distribution(os.path.join(out, "force_histo.png"), title,
                                               forces))
    written.append(plot_profile(os.path.join(out, "profile.png"), title, data("profile"), pk))
    return written


# what the summary says of each file of a run folder
FILE_NOTES = {
    "log.lammps": "LAMMPS log", "screen.txt": "LAMMPS screen output",
    "packing.dat": "phi, Z and more as 'key value'",
    "contact_histo.dat": "contact-normal histogram (theta, P(Omega), fraction)",
    "orient_histo.dat": "long-axis histogram (theta, P(Omega), fraction)",
    "contact_force_histo.dat": "the same weighted by the normal force (theta, P_f, force "
                               "fraction, mean |f_n| in the bin)",
    "force_histo.dat": "P(f/<f>) of the normal forces (f/<f>, P, fraction)",
    "contact_histo.png": "plot (geometric and force-weighted)",
    "orient_histo.png": "plot", "force_histo.png": "plot",
    "profile.dat": "solid fraction phi(z) per bin: z, phi, solid volume, centres",
    "profile.png": "plot of phi(z) with the slab",
    "deposit.dump": "OVITO dump: semi-axes (radii) and quaternion w,i,j,k",
    "deposit.png": "picture (dump image)",
    "deposit.restart": "the deposit at rest with its contacts' histories (-var save 1)"}


def print_summary(out, settings, pk, nprocs, wall, more_notes):
    """the run's numbers (packing.dat) and its files"""
    st = settings
    print("\ndeposit_run: N %d  eta %g  zeta %g  delta_r %g  (%d ranks, %.0f s, %d steps)"
          % (st["N"], st["eta"], st["zeta"], st["dr"], nprocs, wall, int(pk.get("steps", 0))))
    print("  volume fraction phi = %.4f   (slab z in [%.3f, %.3f], %d particles)"
          % (pk["phi"], pk["zlo"], pk["zhi"], int(pk["Nslab"])))
    print("  coordination number Z = %.3f   without rattlers %.3f (%d rattlers)"
          % (pk["Z"], pk["Z_no_rattlers"], int(pk["rattlers"])))
    if "K0" in pk:
        print("  stress of the slab (mean over %d steps at rest, +- standard error): sigma_zz = "
              "%.4g +- %.2g, K0 = (sigma_xx+sigma_yy)/(2 sigma_zz) = %.3f +- %.3f; anisotropy "
              "a_n = %.3f (normals), a_f = %.3f (forces); unbalanced force %.2g"
              % (pk.get("window_steps", 0), pk["sigma_zz"], pk.get("sigma_zz_se", 0.0), pk["K0"],
                 pk.get("K0_se", 0.0), pk["a_n"], pk["a_f"], pk.get("unbalanced_force", 0.0)))
    if pk.get("slab_ok", 1) == 0:
        print("  WARNING: the measuring slab is empty or thinner than slabmin (slab_ok 0): phi, "
              "Z and the forces are not results")
    if pk.get("at_rest", 1) == 0:
        print("  WARNING: the deposit is NOT at rest (maxchunks ran out): phi and Z are of a "
              "moving packing; run it again with a larger --var maxchunks (it starts anew)")
    print("  files in %s:" % out)
    notes = dict(FILE_NOTES, **more_notes)
    for name in sorted(os.listdir(out)):
        print("    %-24s %s" % (name, notes.get(name, "")))
