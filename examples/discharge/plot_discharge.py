"""The discharge study's table and figure (README.md): the steady rates, Beverloo's C and k
fitted per shape (tools/containers/discharge.py), the stiffness check.

    ./ellipsoid-dep python examples/discharge/plot_discharge.py --table --figure \
        examples/discharge/discharge.png
"""
import argparse
import glob
import json
import os

import numpy as np

import discharge

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = os.path.join(HERE, "results")
LABELS = {"spheres": "spheres", "eta1.4_zeta1.8": "eta 1.4 zeta 1.8",
          "hopper30_spheres": "spheres, hopper 30 deg",
          "eta1.4_zeta1.8_long": "eta 1.4 zeta 1.8, long window"}
STIFF = "spheres_stiff"    # the stiffness check: spheres at hertz 1e4 200, its own fill


def runs():
    """{name: {"fill": fill.json, "orifices": [D<D0>.json, each with its series' path, sorted
    by D0]}} of the committed results"""
    out = {}
    for name in list(LABELS) + [STIFF]:
        folder = os.path.join(RESULTS, name)
        if not os.path.isfile(os.path.join(folder, "fill.json")):
            continue
        out[name] = {"fill": json.load(open(os.path.join(folder, "fill.json"))),
                     "orifices": sorted((dict(json.load(open(path)), series=path[:-5] + ".dat")
                                         for path in glob.glob(os.path.join(folder, "D*.json"))),
                                        key=lambda r: r["D0"])}
    return out


def steady(e):
    """the orifices whose rate is steady over the window (no trend in its time blocks)"""
    return [r for r in e["orifices"] if discharge.block_trend(r["blocks"])["steady"]]


def fits(data):
    """Beverloo's fit per shape with >= 3 steady orifices in the flat floor"""
    return {name: discharge.fit_beverloo([r["D0"] for r in steady(e)],
                                         [r["rate"] for r in steady(e)],
                                         [r["se"] for r in steady(e)], e["fill"]["rho_b"])
            for name, e in data.items()
            if name in LABELS and len(steady(e)) >= 3 and e["fill"].get("angle", 0) == 0}


def trend_text(blocks):
    t = discharge.block_trend(blocks)
    if t["rise"] is None:
        return "no flow, not steady"
    return f"{100 * t['rise']:+.0f} % (p {t['p']:.2g}){'' if t['steady'] else ', not steady'}"


def table(data):
    """the README's tables: the rates per orifice, then the fits and the stiffness check"""
    rows = ["| shape | D0 / d | W (mass / time) | W / (rho_b sqrt(g) d^(5/2)) | particles "
            "out (all) | window (time) | first, last block | trend across the window (p) | "
            "lift band | minutes |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for name, e in data.items():
        if name not in LABELS:
            continue
        rho = e["fill"]["rho_b"]
        for r in e["orifices"]:
            rows.append(f"| {LABELS[name]} | {r['D0']:g} | {r['rate']:.2f} +- {r['se']:.2f} | "
                        f"{r['rate'] / rho:.2f} | {r['count']} | {r['t0']:g}-{r['t1']:g} | "
                        f"{r['blocks'][0]:.1f}, {r['blocks'][-1]:.1f} | "
                        f"{trend_text(r['blocks'])} | "
                        f"1-{r.get('band', 3.0):g} | {r['minutes']:.0f} |")
    rows += ["", "| shape | N | fill height H / d | rho_b | steady orifices fitted (D0 / d) | C | "
             "k | corr(C, k) | "
             "chi^2 / dof |", "|---|---|---|---|---|---|---|---|---|"]
    fitted = fits(data)
    for name, f in fitted.items():
        e = data[name]
        rows.append(f"| {LABELS[name]} | {e['fill']['N']} | {e['fill']['H']:.1f} | "
                    f"{e['fill']['rho_b']:.3f} | "
                    f"{', '.join('%g' % r['D0'] for r in steady(e))} | "
                    f"{f['C']:.3f} +- {f['dC']:.3f} | {f['k']:.2f} +- {f['dk']:.2f} | "
                    f"{f['corr']:.2f} | {f['chi2']:.1f} / {f['dof']} |")
    if STIFF in data and "spheres" in fitted:
        # the rate does not follow the law's stiffness, the soft fill's density does: C with
        # the stiff fill's rho_b (nearer the rigid limit), k unchanged
        e, f = data["spheres"], fitted["spheres"]
        scale = e["fill"]["rho_b"] / data[STIFF]["fill"]["rho_b"]
        rows.append(f"| spheres, rho_b of the hertz 1e4 fill | {e['fill']['N']} | "
                    f"{data[STIFF]['fill']['H']:.1f} | {data[STIFF]['fill']['rho_b']:.3f} | "
                    f"{', '.join('%g' % r['D0'] for r in steady(e))} | "
                    f"{f['C'] * scale:.3f} +- {f['dC'] * scale:.3f} | "
                    f"{f['k']:.2f} +- {f['dk']:.2f} | {f['corr']:.2f} | {f['chi2']:.1f} / "
                    f"{f['dof']} |")
    if STIFF in data and "spheres" in data:
        rows += ["", "| spheres, D0 / d | law (time step) | rho_b | W | W / rho_b |",
                 "|---|---|---|---|---|"]
        ratios = []
        for name in ("spheres", STIFF):
            e = data[name]
            for r in e["orifices"]:
                if r["D0"] not in [s["D0"] for s in data[STIFF]["orifices"]]:
                    continue
                rho = e["fill"]["rho_b"]
                ratios.append((r["rate"], r["se"], rho))
                rows.append(f"| {r['D0']:g} | hertz {r['kn']:g} {r['K']:g} ({r['dt']:g}) | "
                            f"{rho:.3f} | {r['rate']:.2f} +- {r['se']:.2f} | "
                            f"{r['rate'] / rho:.2f} +- {r['se'] / rho:.2f} |")
        if len(ratios) == 2:
            (w1, s1, r1), (w2, s2, r2) = ratios
            q = (w2 / r2) / (w1 / r1)
            rows.append(f"| | stiff / soft | {r2 / r1:.3f} | {w2 / w1:.3f} +- "
                        f"{w2 / w1 * np.hypot(s1 / w1, s2 / w2):.3f} | {q:.3f} +- "
                        f"{q * np.hypot(s1 / w1, s2 / w2):.3f} |")
    return "\n".join(rows)


def figure(data, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    colours = {"spheres": "C0", "eta1.4_zeta1.8": "C3", "hopper30_spheres": "C2",
               "eta1.4_zeta1.8_long": "C1"}
    data = {name: e for name, e in data.items() if name in LABELS}
    for name, e in data.items():
        for r in e["orifices"]:
            t, mass = np.loadtxt(r["series"], usecols=(0, 2), unpack=True)
            ax1.plot(t, mass, color=colours[name], lw=1)
            ax1.text(t[-1], mass[-1], f" {r['D0']:g}", color=colours[name], fontsize=8)
    starts = {r["t0"] for e in data.values() for r in e["orifices"]}
    for t0 in starts:
        ax1.axvline(t0, color="grey", ls=":")
    ax1.set(xlabel="time since the orifice opened (sqrt(d/g))", ylabel="discharged mass",
            title="discharge (D0 / d at the ends; dotted: the window starts)")
    fitted = fits(data)
    for name, e in data.items():
        d0 = np.array([r["D0"] for r in e["orifices"]])
        w = np.array([r["rate"] for r in e["orifices"]])
        se = np.array([r["se"] for r in e["orifices"]])
        ok = np.array([discharge.block_trend(r["blocks"])["steady"] for r in e["orifices"]])
        for mask, face, label in ((ok, colours[name], LABELS[name]),
                                  (~ok, "none", LABELS[name] + ": not steady, not fitted")):
            if mask.any():
                ax2.errorbar(d0[mask], w[mask] ** 0.4, yerr=0.4 * w[mask] ** -0.6 * se[mask],
                             fmt="o", mfc=face, color=colours[name], label=label)
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
    ax2.legend(fontsize=7, loc="upper left")
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
