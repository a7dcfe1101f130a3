"""The clump-against-ellipsoid table of run_clumps.py: per run group (ellipsoids e, clumps k3,
k7, k15) the median CPU time (the cost; the wall time on a shared machine is mostly the other
jobs' share), wall time and steps, phi and Z (mean and seed SD), the contact-normal
histogram's rms difference from the ellipsoids' against its seed noise, and the verdict.

Agreement "within the seed spread": a clump group agrees with the ellipsoids in a measure when
the difference of the means is at most twice its standard error from the seed scatter,
sqrt(SD_k^2/n_k + SD_e^2/n_e); for the histogram, when the rms over the bins of the difference
of the mean P is at most twice the rms over the bins of that standard error. The clump
agrees when phi, Z and the histogram all agree.
"""
import csv
import math
import os

import numpy as np

BINS = 18
ORDER = ["e", "k3", "k7", "k15"]


def groups(rows):
    out = {}
    for r in rows:
        out.setdefault(r["run"], []).append(r)
    return out


def stats(rows):
    f = lambda key: np.array([float(r[key]) for r in rows])
    P = np.array([[float(r["P%d" % k]) for k in range(BINS)] for r in rows])
    sd = lambda a: float(a.std(ddof=1)) if len(a) > 1 else float("nan")
    return {"n": len(rows), "wall": float(np.median(f("wall_seconds"))),
            "cpu": float(np.median(f("cpu_seconds"))),
            "steps": float(np.median(f("steps"))), "at_rest": int(f("at_rest").min()),
            "phi": float(f("phi").mean()), "phi_sd": sd(f("phi")),
            "Z": float(f("Z").mean()), "Z_sd": sd(f("Z")),
            "P": P.mean(axis=0), "P_sd": P.std(axis=0, ddof=1) if len(rows) > 1
            else np.full(BINS, np.nan)}


def compare(c, e):
    """Differences to the ellipsoids with their standard errors; None when a side has < 2."""
    if c["n"] < 2 or e["n"] < 2:
        return None
    se = lambda key: math.sqrt(c[key + "_sd"] ** 2 / c["n"] + e[key + "_sd"] ** 2 / e["n"])
    d_phi, d_Z = c["phi"] - e["phi"], c["Z"] - e["Z"]
    rms = float(np.sqrt(np.mean((c["P"] - e["P"]) ** 2)))
    noise = float(np.sqrt(np.mean(c["P_sd"] ** 2 / c["n"] + e["P_sd"] ** 2 / e["n"])))
    res = {"d_phi": d_phi, "se_phi": se("phi"), "d_Z": d_Z, "se_Z": se("Z"),
           "P_rms": rms, "P_noise": noise}
    res["agree_phi"] = abs(d_phi) <= 2 * res["se_phi"]
    res["agree_Z"] = abs(d_Z) <= 2 * res["se_Z"]
    res["agree_P"] = rms <= 2 * noise
    res["agree"] = res["agree_phi"] and res["agree_Z"] and res["agree_P"]
    return res


def write(rows, clumps, out_dir):
    g = {name: stats(rs) for name, rs in groups(rows).items()}
    names = [n for n in ORDER if n in g]
    e = g.get("e")
    lines = ["| run | seeds | CPU time (s, median) | CPU time / ellipsoids | wall time (s, median) "
             "| steps (median) | CPU ms per step | phi at the ellipsoid's volume | phi "
             "(mean +- SD) | Z (mean +- SD) | d phi / SE | d Z / SE | histogram rms diff / "
             "seed noise | volume error | area error | agrees |",
             "|" + "---|" * 16]
    summary = []
    for name in names:
        s = g[name]
        cmp_ = compare(s, e) if (e and name != "e") else None
        fit = clumps.get(name)
        vol = ("%+.2f +- %.2f %%" % (100 * fit["volume_error"], 100 * fit["volume_error_se"])
               if fit else "0 (exact)")
        area = ("%+.2f +- %.2f %%" % (100 * fit["area_error"], 100 * fit["area_error_se"])
                if fit else "0 (exact)")
        ratio = s["cpu"] / e["cpu"] if e else float("nan")
        label = "ellipsoids (granular/ellipsoid)" if name == "e" else \
            "clumps k = %s (granular + rigid/small)" % name[1:]
        if cmp_:
            dp = "%+.4f / %.4f" % (cmp_["d_phi"], cmp_["se_phi"])
            dz = "%+.3f / %.3f" % (cmp_["d_Z"], cmp_["se_Z"])
            dh = "%.4f / %.4f" % (cmp_["P_rms"], cmp_["P_noise"])
            agree = "yes" if cmp_["agree"] else "no (%s)" % ", ".join(
                m for m in ("phi", "Z", "P") if not cmp_["agree_" + m])
        else:
            dp = dz = dh = agree = "" if name == "e" else "n/a (< 2 seeds)"
        # the clumps' number density times the ellipsoid's volume (the union's volume differs)
        phi_e = s["phi"] / (1 + fit["volume_error"]) if fit else s["phi"]
        lines.append("| %s | %d | %.0f | %.2f | %.0f | %.0f | %.2f | %.4f | %.4f +- %.4f "
                     "| %.3f +- %.3f | %s | %s | %s | %s | %s | %s |"
                     % (label, s["n"], s["cpu"], ratio, s["wall"], s["steps"],
                        1e3 * s["cpu"] / s["steps"], phi_e, s["phi"], s["phi_sd"], s["Z"],
                        s["Z_sd"], dp, dz, dh, vol, area, agree))
        row = {"run": name, "seeds": s["n"], "cpu_median": s["cpu"], "wall_median": s["wall"],
               "time_ratio": ratio,
               "steps_median": s["steps"], "cpu_ms_per_step": 1e3 * s["cpu"] / s["steps"],
               "phi_at_ellipsoid_volume": phi_e, "phi": s["phi"], "phi_sd": s["phi_sd"],
               "Z": s["Z"],
               "Z_sd": s["Z_sd"], "all_at_rest": s["at_rest"]}
        if cmp_:
            row.update({k: v for k, v in cmp_.items()})
        if fit:
            row.update({"volume_error": fit["volume_error"], "area_error": fit["area_error"],
                        "iou": fit["iou"]})
        summary.append(row)
    agreeing = [r for r in summary if r.get("agree")]
    if not e:
        verdict = "No ellipsoid rows yet: no verdict."
    elif agreeing:
        first = agreeing[0]
        verdict = ("The smallest k whose deposit agrees with the ellipsoids within the seed spread "
                   "is k = %s; there this package deposits %.1fx faster (median CPU time)."
                   % (first["run"][1:], first["time_ratio"]))
    else:
        done = [r for r in summary if r["run"] != "e" and "agree" in r]
        verdict = "No k measured agrees with the ellipsoids within the seed spread (%s)." % (
            "; ".join("k = %s: %s, %.1fx the CPU time" % (
                r["run"][1:], ", ".join(m for m in ("phi", "Z", "P") if not r["agree_" + m]) +
                " differ", r["time_ratio"]) for r in done) or "no clump group with 2 seeds")
    with open(os.path.join(out_dir, "table.md"), "w") as f:
        f.write("\n".join(lines) + "\n\n" + verdict + "\n")
    keys = sorted({k for r in summary for k in r}, key=lambda k: (k != "run", k))
    with open(os.path.join(out_dir, "summary.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in summary:
            w.writerow(r)
    plot(g, names, rows[0]["N"], os.path.join(out_dir, "histograms.png"))
    print("\n".join(lines) + "\n\n" + verdict)


def plot(g, names, n, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    theta = (np.arange(BINS) + 0.5) * 180.0 / BINS
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for name in names:
        s = g[name]
        label = "ellipsoids" if name == "e" else "clumps k = " + name[1:]
        ax.errorbar(theta, s["P"], yerr=s["P_sd"], marker="o", ms=3, capsize=2,
                    label="%s (%d seeds)" % (label, s["n"]))
    ax.axhline(1 / (4 * math.pi), color="grey", lw=0.8, ls=":")
    ax.set_xlabel(r"$\theta$ (degrees from vertical)")
    ax.set_ylabel(r"$P(\Omega(\theta))$")
    ax.set_title(r"contact normals, $\eta$ 1.4 $\zeta$ 1.8, N = %s (bars: seed SD)"
                 % n)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
