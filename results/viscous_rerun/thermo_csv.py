"""step, time (LAMMPS units), KE per particle, phi and Z of the slab every 1000 steps from a viscous re-run's LAMMPS
logs (log.lammps and the resumed runs' log.resume-*.lammps) into RUN/thermo.csv: how the
bed creeps while it settles (doc/study.md)

    python3 thermo_csv.py RUN_DIR OUT_DIR"""
import csv
import glob
import os
import sys

run, out = sys.argv[1], sys.argv[2]
rows = {}
for log in [os.path.join(run, "log.lammps")] + sorted(glob.glob(os.path.join(run, "log.resume-*.lammps")),
                                                      key=lambda p: int(p.split("-")[-1].split(".")[0])):
    header = None
    for line in open(log):
        words = line.split()
        if words[:2] == ["Step", "Elaplong"]:
            header = words
            continue
        if header and len(words) == len(header) and words[0].isdigit():
            r = dict(zip(header, words))
            step = int(r["Step"])
            if step % 1000 == 0 and step > 0:
                rows[step] = (r["Time"], r["v_kep"], r["c_pack[1]"], r["c_pack[3]"])
        elif header and words and not words[0].lstrip("-").replace(".", "").isdigit():
            header = None
os.makedirs(out, exist_ok=True)
with open(os.path.join(out, "thermo.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["step", "time", "ke_per_particle", "phi", "Z"])
    for step in sorted(rows):
        w.writerow([step, *rows[step]])
print(out, len(rows), "rows")
