"""doc/study.md's figure list and the study's cost (tools/study/study_doc.py): each figure with the
paper's figure it answers (the numbers of the paper's LaTeX source), the command that draws
it and its sets in workflow/config/paper.yaml; the deposits and CPU hours per selection from
deposits.csv (wall_seconds x np, the runner's; a resumed deposit's earlier segments from their
logs, where they were kept)."""
import csv
import os

from study_doc_claims import table

FIGURES_CMD = "`./ellipsoid-dep python tools/plot/plot_figures.py results/study/table.csv`"
STUDY_CMD = "`./ellipsoid-dep study` (rule %s)"
# (file under results/, the paper's figure, what it shows, the command, the sets)
FIGURES = (
    ("-", "Fig. 1 (fig:contact): the contact vector", "not redrawn (src/kernel, "
     "doc/architecture.md)", "-", "-"),
    ("-", "Fig. 2 (fig:diagram): the contact algorithm's flow chart", "not redrawn", "-", "-"),
    ("study/figures/fig_sizes.png", "Fig. 3 (fig:vr-nr)", "V(r) and n(r) for several alpha, "
     "beta; a deposit's sizes over them", FIGURES_CMD + " (sizes: `tools/plot/plot_sizes.py "
     "--from-dump` of `./ellipsoid-dep run --N 1000 --dr 0.6`)", "none (one deposit)"),
    ("study/picture.png", "Fig. 4 (fig:deposit)", "the deposit, LAMMPS's rendering",
     STUDY_CMD % "picture", "`picture`"),
    ("study/figures/fig_density_map.png", "Fig. 5a (fig:density)", "phi over (eta, zeta) and "
     "its error map", FIGURES_CMD, "`map`, `diagonal`"),
    ("study/figures/fig_density_lines.png", "Fig. 5b (fig:density) and its inset", "phi on the "
     "three lines, the fits near the maxima, the diagonal per delta_r", FIGURES_CMD,
     "`map`, `diagonal`, `diagonal_forces`, `ridge`, `fall_back`, `polydisperse`"),
    ("study/figures/fig_z_map.png, fig_z_norattler_map.png", "Fig. 6 (fig:coordnum)",
     "Z over (eta, zeta), with and without rattlers", FIGURES_CMD, "`map`, `diagonal`"),
    ("study/figures/fig_contact_shapes.png", "Fig. 7a (fig:contact-hist)", "P(Omega(theta)) of "
     "the contact normals per shape", FIGURES_CMD, "`map`, `diagonal`"),
    ("study/figures/fig_contact_dr.png", "Fig. 7b (fig:contact-hist)", "the same for (1.6, 1.8) "
     "at each delta_r", FIGURES_CMD, "`map`, `polydisperse`"),
    ("study/figures/fig_orient_shapes.png", "Fig. 8 (fig:orient-hist)", "P(Omega(theta)) of "
     "the long axes per shape", FIGURES_CMD, "`map`, `diagonal`"),
    ("study/figures/fig_density_laws.png", "-", "phi on the diagonal per tangential law",
     FIGURES_CMD, "`diagonal`, `viscous_diagonal`"),
    ("study/figures/fig_forces.png", "- (the abstract's claim)", "a_n, a_f, a_n + a_f; K0; "
     "force by direction; P(f/<f>)", FIGURES_CMD, "`equilibrium`, `equilibrium_lines`"),
    ("study/pores.png", "-", "porosity, S_v, k_KC along the lines",
     STUDY_CMD % "pores_figure", "`map`, `diagonal`, `ridge` (the lines)"),
    ("oedometer/modulus_k0.png", "-", "the oedometer's modulus and K0",
     "`./ellipsoid-dep python tools/containers/oedometer_study.py report`",
     "results/oedometer (not paper.yaml)"))


def figures_block(data):
    return table(["file (results/)", "the paper's figure", "what", "command", "sets of "
                  "paper.yaml"], [list(f) for f in FIGURES])


def cost_block(data):
    """deposits, those with window means, and CPU hours per selection and in all"""
    with open(os.path.join(data.results, "deposits.csv")) as f:
        rows = list(csv.DictReader(f))
    groups = {}
    for r in rows:
        key = (int(r["N"]), r["width"] or "", float(r["delta_r"]), r["law"])
        groups.setdefault(key, []).append(r)

    def hours(v):
        return sum(float(r["wall_seconds"]) * float(r.get("np") or 1) for r in v) / 3600

    def window(v):
        return sum(1 for r in v if float(r.get("window_steps") or 0) > 0)

    out = [["%d" % n, "%s" % (w or "default"), "%g" % dr, law, "%d" % len(v), "%d" % window(v),
            "%.1f" % hours(v), "%.1f" % (60 * hours(v) / len(v))]
           for (n, w, dr, law), v in sorted(groups.items())]
    out.append(["all", "", "", "", "%d" % len(rows), "%d" % window(rows), "%.1f" % hours(rows),
                "%.1f" % (60 * hours(rows) / len(rows))])
    uncounted = [r for r in rows if r.get("resumed_from") and
                 r.get("earlier_segments_seconds", "") == ""]
    note = ("" if not uncounted else
            "\n\n%d deposit%s resumed from a checkpoint before the runner counted the earlier "
            "segments (their logs are gone): %s count only the last segment, a lower bound (%s)."
            % (len(uncounted), "s were" if len(uncounted) > 1 else " was",
               "they" if len(uncounted) > 1 else "it",
               ", ".join("%s s%s from step %s" % (r["point"], r["seed"], r["resumed_from"])
                         for r in uncounted)))
    return table(["N", "box edge (d)", "delta_r", "law", "deposits", "with window means",
                  "CPU hours", "CPU minutes per deposit"], out) + note
