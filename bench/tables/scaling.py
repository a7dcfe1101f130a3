"""Table 3, scaling: granular/ellipsoid on k x k replicas of the settled deposit, against N
(1 rank) and against the ranks at the largest N."""
from .lmp_runs import NWARM, fmt_table, med, parse_log, replicate, run_lmp


def bench_scaling(out, g, ks, nsteps_for, repeats, nps):
    base_m = g["nmobile"]
    rows = []
    for k in ks:
        data_e, _ = replicate(out, g, k)
        nmob = base_m * k * k
        for np_ in nps:
            if np_ > 1 and k != ks[-1]:
                continue
            ms = nsteps_for(nmob)
            vals = []
            for r in range(repeats):
                x = parse_log(run_lmp(out, "in.run_ours", f"log.scale_x{k}_np{np_}_{r}",
                                      {"data": data_e, "knobs": "planes yes", "nsteps": ms,
                                       "nwarm": NWARM},
                                      np=np_))
                vals.append(nmob * x["steps"] / x["loop"])
            rows.append({"N": nmob, "np": np_, "steps": ms, "pss": med(vals),
                         "ns": 1e9 / med(vals)})
            print(f"  N={nmob} np={np_}: {med(vals):.3g} particle-steps/s", flush=True)
    return rows


def scaling_markdown(rows):
    n1 = [r for r in rows if r["np"] == 1]
    base = n1[0]["ns"]
    out = []
    for r in rows:
        same_n1 = next((x for x in n1 if x["N"] == r["N"]), None)
        speedup = r["pss"] / same_n1["pss"] if same_n1 else float("nan")
        out.append([r["N"], r["np"], r["steps"], f"{r['pss']:.3g}", f"{r['ns']:.0f}",
                    f"{r['ns'] / base:.2f}", f"{speedup:.2f}"])
    return fmt_table(["N (mobile)", "MPI ranks", "M", "particle-steps/s", "ns/particle-step",
                      "cost / smallest N", "speed-up vs 1 rank"], out)
