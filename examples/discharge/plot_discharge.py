"""The discharge study's table and figure (README.md): the steady rates, Beverloo's C and k
fitted per shape (tools/containers/discharge.py), the stiffness check.

    ./ellipsoid-dep python examples/discharge/plot_discharge.py --table --figure \
        examples/discharge/discharge.png
"""
import argparse
import glob
import json
import os
import re

import numpy as np

import discharge

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = os.path.join(HERE, "results")
LABELS = {"spheres": "spheres", "eta1.4_zeta1.8": "eta 1.4 zeta 1.8",
          "hopper30_spheres": "spheres, hopper 30 deg"}


def runs():
    """{shape: {"fill": fill.json, "orifices": [D<D0>.json sorted by D0], "tagged": {tag:
    [json]}, "series": {json path: its .dat}}} of the committed results"""
    out = {}
    for name in LABELS:
        folder = os.path.join(RESULTS, name)
        if not os.path.isfile(os.path.join(folder, "fill.json")):
            continue
        entry = {"fill": json.load(open(os.path.join(folder, "fill.json"))), "orifices": [],
                 "tagged": {}}
        for path in sorted(glob.glob(os.path.join(folder, "D*.json"))):
            tag = re.match(r"D[0-9.]+(?:_(\w+))?\.json", os.path.basename(path)).group(1)
            run = dict(json.load(open(path)), series=path[:-5] + ".dat")
            (entry["tagged"].setdefault(tag, []) if tag else entry["orifices"]).append(run)
        entry["orifices"].sort(key=lambda r: r["D0"])
        out[name] = entry
    return out


def fits(data):
    """Beverloo's fit per shape with >= 3 orifices in the flat floor"""
    return {name: discharge.fit_beverloo([r["D0"] for r in e["orifices"]],
                                         [r["rate"] for r in e["orifices"]],
                                         [r["se"] for r in e["orifices"]], e["fill"]["rho_b"])
            for name, e in data.items()
            if len(e["orifices"]) >= 3 and e["fill"].get("angle", 0) == 0}


def table(data):
    """the README's tables: the rates per orifice, then the fits and the stiffness check"""
    rows = ["| shape | D0 / d | W (mass / time) | W / (rho_b sqrt(g) d^(5/2)) | particles "
            "counted | window (time) | minutes |", "|---|---|---|---|---|---|---|"]
    for name, e in data.items():
        rho = e["fill"]["rho_b"]
        for r in e["orifices"]:
            rows.append(f"| {LABELS[name]} | {r['D0']:g} | {r['rate']:.2f} +- {r['se']:.2f} | "
                        f"{r['rate'] / rho:.2f} | {r['count']} | {r['t0']:g}-{r['t1']:g} | "
                        f"{r['minutes']:.0f} |")
    rows += ["", "| shape | N | fill height H / d | rho_b | orifices | C | k | corr(C, k) | "
             "chi^2 / dof |", "|---|---|---|---|---|---|---|---|---|"]
    for name, f in fits(data).items():
        e = data[name]
        rows.append(f"| {LABELS[name]} | {e['fill']['N']} | {e['fill']['H']:.1f} | "
                    f"{e['fill']['rho_b']:.3f} | {len(e['orifices'])} | "
                    f"{f['C']:.3f} +- {f['dC']:.3f} | {f['k']:.2f} +- {f['dk']:.2f} | "
                    f"{f['corr']:.2f} | {f['chi2']:.1f} / {f['dof']} |")
    stiff = [(name, r) for name, e in data.items() for r in e["tagged"].get("stiff", [])]
    if stiff:
        rows += ["", "| shape | D0 / d | kn (K, dt) | W | kn 1e3 (K 63.2, dt 2e-3): W | "
                 "ratio |", "|---|---|---|---|---|---|"]
        for name, r in stiff:
            soft = next(o for o in data[name]["orifices"] if o["D0"] == r["D0"])
            ratio = r["rate"] / soft["rate"]
            dratio = ratio * np.hypot(r["se"] / r["rate"], soft["se"] / soft["rate"])
            rows.append(f"| {LABELS[name]} | {r['D0']:g} | {r['kn']:.0e} ({r['K']:g}, "
                        f"{r['dt']:g}) | {r['rate']:.2f} +- {r['se']:.2f} | "
                        f"{soft['rate']:.2f} +- {soft['se']:.2f} | {ratio:.3f} +- {dratio:.3f} |")
    return "\n".join(rows)


def figure(data, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    colours = {"spheres": "C0", "eta1.4_zeta1.8": "C3", "hopper30_spheres": "C2"}
    for name, e in data.items():
        for r in e["orifices"]:
            t, mass = np.loadtxt(r["series"], usecols=(0, 2), unpack=True)
            ax1.plot(t, mass, color=colours[name], lw=1)
            ax1.text(t[-1], mass[-1], f" {r['D0']:g}", color=colours[name], fontsize=8)
        ax1.axvline(e["orifices"][0]["t0"] if e["orifices"] else 0, color="grey", ls=":")
    ax1.set(xlabel="time since the orifice opened (sqrt(d/g))", ylabel="discharged mass",
            title="discharge (D0 / d at the ends; dotted: the window starts)")
    fitted = fits(data)
    for name, e in data.items():
        d0 = np.array([r["D0"] for r in e["orifices"]])
        w = np.array([r["rate"] for r in e["orifices"]])
        se = np.array([r["se"] for r in e["orifices"]])
        ax2.errorbar(d0, w ** 0.4, yerr=0.4 * w ** -0.6 * se, fmt="o", color=colours[name],
                     label=LABELS[name])
        if name in fitted:
            f = fitted[name]
            x = np.linspace(f["k"], d0.max() + 0.5, 50)
            ax2.plot(x, f["slope"] * x + f["intercept"], color=colours[name],
                     label=f"fit: C {f['C']:.2f} +- {f['dC']:.2f}, k {f['k']:.2f} +- "
                           f"{f['dk']:.2f}")
        if name == "spheres" and len(d0):
            x = np.linspace(1.5, d0.max() + 0.5, 50)
            ax2.plot(x, discharge.beverloo(x, 0.58, 1.5, e["fill"]["rho_b"]) ** 0.4, "k--",
                     lw=1, label="Beverloo: C 0.58, k 1.5 (spheres' rho_b)")
    ax2.set(xlabel="D0 / d", ylabel="W^(2/5)", xlim=(0, None), ylim=(0, None),
            title="Beverloo: W = C rho_b sqrt(g) (D0 - k d)^(5/2)")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--table", action="store_true")
    p.add_argument("--figure")
    a = p.parse_args()
    data = runs()
    if a.table:
        print(table(data))
    if a.figure:
        figure(data, a.figure)


if __name__ == "__main__":
    main()
