"""Table 4, the sphere path: this package's styles on spheres against LAMMPS's own."""
from .lmp_runs import NWARM, fmt_table, med, parse_log, run_lmp


def bench_spheres(out, nsteps, repeats):
    """The sphere path: 1024 unit spheres settled on a wall by LAMMPS's styles, then the same
    steps through LAMMPS's pair granular + fix wall/gran + nve/sphere and through this
    package's styles (with nve/ellipsoid, and with nve/asphere), alternating, 1 rank."""
    scene = {"L": 10, "zt": 20}
    run_lmp(out, "in.settle_sphere_wall", "log.settle_sphere_wall",
            dict(scene, nfall=5000, out="spheres_wall.dump"))
    codes = [("LAMMPS: granular, wall/gran, nve/sphere", "in.run_sphere_wall", {}),
             ("ours: granular/ellipsoid, wall/gran/ellipsoid, nve/ellipsoid",
              "in.run_sphere_wall_ours", {"integrator": "nve/ellipsoid"}),
             ("ours with nve/asphere", "in.run_sphere_wall_ours", {"integrator": "nve/asphere"})]
    loops = {name: [] for name, _, _ in codes}
    for r in range(repeats):
        for k, (name, inp, extra) in enumerate(codes):
            log = run_lmp(out, inp, f"log.spheres_{k}_{r}",
                          dict(scene, **extra, dump="spheres_wall.dump", nwarm=NWARM,
                               nsteps=nsteps))
            res = parse_log(log)
            loops[name].append(res["loop"])
            atoms = res["atoms"]
        print(f"  repeat {r + 1}/{repeats} done", flush=True)
    base = med(loops[codes[0][0]])
    return [{"code": name, "atoms": atoms, "steps": nsteps, "loop_s": med(loops[name]),
             "spread": (min(loops[name]), max(loops[name])), "repeats": repeats,
             "ratio": med(loops[name]) / base} for name, _, _ in codes]


def spheres_markdown(rows):
    return fmt_table(["code", "spheres", "steps", "loop time (s, median)", "min-max",
                      "time / LAMMPS"],
                     [[r["code"], r["atoms"], r["steps"], f"{r['loop_s']:.3f}",
                       f"{r['spread'][0]:.3f}-{r['spread'][1]:.3f}", f"{r['ratio']:.2f}"]
                      for r in rows])
