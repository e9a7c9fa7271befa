#!/usr/bin/env python3
"""Charts of what accuracy costs in time, from the CSV of deformable_sim_bench.

    scripts/plot_accuracy.py accuracy.csv OUTPUT_DIR

writes into OUTPUT_DIR:
  accuracy_<case>.png   error vs ms/step per case (log-log), the Pareto front marked, every point
                        labelled with its setting
  error_vs_dt.png       period error, numerical damping and trajectory error vs the implicit step h
  error_vs_tolerance.png  error vs CG tolerance and vs CG iteration cap
  advice.md             the budget table for the README, read off the measured Pareto fronts
Needs only Debian's python3-matplotlib (Agg backend: no display).
"""
import argparse
import csv
import math
import re
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

CASES = {
    "A_static": "A: linear static cantilever, P = 0.025 N\n"
                "error = |uz/uz_3D - 1| (converged 3D); time = whole static solve",
    "B_alpha1": "B: large deflection, alpha = 1 (tip turns 26 deg)\n"
                "error = |u - u_3D| / |u_3D| of tip (ux, uz); time = whole static solve",
    "B_alpha2": "B: large deflection, alpha = 2 (tip turns 45 deg)\n"
                "error = |u - u_3D| / |u_3D| of tip (ux, uz); time = whole static solve",
    "C2_period": "C2: free vibration, first bending period\n"
                 "error = |T/T_3D - 1| (converged 3D f1); time per tick",
    "C2_damping": "C2: free vibration, numerical damping\n"
                  "error = amplitude lost per cycle (the beam has none); time per tick",
    "T_trajectory": "T: tip path after a sudden alpha = 1 load, 1 s\n"
                    "error = RMS |u - u_conv| / max |u_conv| (converged run, same mesh); time per tick",
}
MESHES = ["tetU_L1", "tetU_L2", "tetU_L3", "tetU_L4", "tetS_L1", "tetS_L2", "tetS_L3", "tetS_L4",
          "hex_L1", "hex_L2", "hex_L3", "hex_L4"]
ERROR_FLOOR = 1e-9  # errors below this are drawn at it (a log axis has no zero)



def log_axes(ax, title):
    """Log-log axes with a small title, a grid and a legend."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=7)


def save(fig, path, machine):
    """Writes the figure with the machine it was measured on in its corner."""
    fig.text(0.99, 0.005, machine, ha="right", va="bottom", fontsize=6, color="gray")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)

def read_rows(path):
    rows = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            for key in ("error", "error_same_mesh", "ms_per_step_median", "value", "theory_value",
                        "same_mesh_value", "reference_value", "dt", "tolerance", "iterations_mean",
                        "ms_per_30hz_tick"):
                row[key] = float(row[key]) if row.get(key) else math.nan
            for key in ("elements", "substeps", "max_iterations", "memory_bytes", "warping", "converged"):
                row[key] = int(row[key]) if row.get(key) else 0
            row["h"] = row["dt"] / row["substeps"] if row["substeps"] else math.nan
            # Static: the whole solve. Dynamic: per 1/30 s simulated, so that every dt compares.
            row["cost"] = row["ms_per_30hz_tick"] if row["substeps"] else row["ms_per_step_median"]
            rows.append(row)
    return rows


def rate(dt):
    return f"1/{round(1 / dt)}"


def label(row, with_mesh=True):
    """A setting in a few characters: mesh, linear FEM, tick and substeps, solver."""
    parts = [row["mesh"].replace("_L", "")] if with_mesh else []
    if not row["warping"]:
        parts.append("linear")
    if row["substeps"]:
        parts.append(rate(row["dt"]) + (f"x{row['substeps']}" if row["substeps"] > 1 else ""))
    if row["solver"] == "direct":
        parts.append("LDLT")
    else:
        cg = f"cg{row['tolerance']:.0e}".replace("e-0", "e-")
        if row["max_iterations"] <= 1000:
            cg += f"/{row['max_iterations']}it"
        parts.append(cg)
    return " ".join(parts)


def pareto_front(rows):
    """Rows no other row beats in both time and error, fastest first."""
    front, best = [], math.inf
    for row in sorted(rows, key=lambda r: (r["cost"], r["error"])):
        if row["error"] < best:
            front.append(row)
            best = row["error"]
    return front


def surface_id(mesh):
    """(turn in degrees, cells) of a beam voxelized from its surface ("surface30_c24"), or None."""
    match = re.fullmatch(r"surface([0-9.]+)_c([0-9]+)", mesh)
    return (float(match[1]), int(match[2])) if match else None


def meshes_of(rows):
    """The shipped meshes, then the surface beams by turn and cell count, that rows hold."""
    present = {r["mesh"] for r in rows}
    surfaces = sorted((m for m in present if surface_id(m)), key=surface_id)
    return [m for m in MESHES if m in present] + surfaces


def mesh_style(mesh):
    surface = surface_id(mesh)
    if surface:  # aligned in purples, turned in oranges, darker for finer grids
        turn, cells = surface
        shade = 0.35 + 0.6 * min(1.0, math.log(cells / 12) / math.log(4))
        return plt.get_cmap("Purples" if turn == 0 else "Oranges")(shade)
    colours = plt.get_cmap("tab20")
    return colours(MESHES.index(mesh) if mesh in MESHES else 19)


def marker(row):
    return {("direct", 1): "o", ("direct", 0): "s", ("cg", 1): "^", ("cg", 0): "v"}[
        (row["solver"], row["warping"])]


def plot_case(case, rows, out_dir, machine):
    fig, ax = plt.subplots(figsize=(13, 8.5))
    front = pareto_front(rows)
    front_ids = {id(r) for r in front}
    for row in rows:
        y = max(row["error"], ERROR_FLOOR)
        on_front = id(row) in front_ids
        ax.scatter(row["cost"], y, color=mesh_style(row["mesh"]), marker=marker(row),
                   s=60 if on_front else 28, edgecolors="black" if on_front else "none",
                   linewidths=1.2, zorder=3)
        ax.annotate(label(row), (row["cost"], y), xytext=(4, 2),
                    textcoords="offset points", fontsize=6.5 if on_front else 5,
                    fontweight="bold" if on_front else "normal",
                    color="black" if on_front else "dimgray", zorder=4)
    xs = [r["cost"] for r in front]
    ys = [max(r["error"], ERROR_FLOOR) for r in front]
    ax.step(xs + [max(r["cost"] for r in rows) * 1.5], ys + ys[-1:], where="post", color="black",
            linewidth=1, zorder=2)
    dynamic = bool(rows[0]["substeps"])
    if dynamic:
        ax.axvline(1000 / 30, color="red", linestyle=":", linewidth=1)
        ax.text(1000 / 30, 0.98, "real time on one core ", transform=ax.get_xaxis_transform(),
                rotation=90, va="top", ha="right", fontsize=7, color="red")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("ms per 1/30 s simulated = per tick of a 30 Hz node (median tick time x (1/30) / dt;"
                  " one thread)" if dynamic else "wall time of the whole static solve, ms (one thread)")
    ax.set_ylabel("error")
    ax.set_title(CASES.get(case, case), fontsize=10)
    ax.grid(True, which="both", alpha=0.25)
    handles = [plt.Line2D([], [], color=mesh_style(m), marker="o", linestyle="", label=m)
               for m in meshes_of(rows)]
    handles += [plt.Line2D([], [], color="gray", marker=mk, linestyle="", label=text)
                for mk, text in (("o", "warped, LDLT"), ("s", "linear FEM, LDLT"),
                                 ("^", "warped, CG"), ("v", "linear FEM, CG"))]
    handles.append(plt.Line2D([], [], color="black", label="Pareto front (circled)"))
    ax.legend(handles=handles, fontsize=7, loc="best")
    save(fig, out_dir / f"accuracy_{case}.png", machine)


def sweep(rows, case, key, **fixed):
    """Rows of one case, grouped by mesh, for the curve of `key`; `fixed` filters."""
    curves = defaultdict(list)
    for row in rows:
        if row["case"] != case or any(row[k] != v for k, v in fixed.items()):
            continue
        curves[row["mesh"]].append(row)
    return {m: sorted(rs, key=lambda r: r[key]) for m, rs in curves.items()}


def plot_dt(rows, out_dir, machine):
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.2))
    panels = (("C2_period", "error_same_mesh", "period error |T/T_mesh - 1|\n"
               "(vs the same mesh's eigenperiod; dashed: implicit Euler theory)"),
              ("C2_damping", "error", "amplitude lost per cycle\n(dashed: implicit Euler theory)"),
              ("T_trajectory", "error", "trajectory error RMS |u - u_conv| / max |u_conv|\n"
               "(converged run, same mesh)"))
    for ax, (case, key, title) in zip(axes, panels):
        for mesh, curve in sweep(rows, case, "h", solver="direct", warping=1).items():
            single = [r for r in curve if r["substeps"] == 1]
            sub = [r for r in curve if r["substeps"] > 1]
            colour = mesh_style(mesh)
            ax.plot([r["h"] for r in single], [max(r[key], ERROR_FLOOR) for r in single], "o-",
                    color=colour, label=mesh)
            ax.plot([r["h"] for r in sub], [max(r[key], ERROR_FLOOR) for r in sub], "D",
                    color=colour, markerfacecolor="none")
            if case == "C2_period":
                ax.plot([r["h"] for r in single],
                        [r["theory_value"] / r["same_mesh_value"] - 1 for r in single], "--",
                        color=colour, linewidth=0.8)
            if case == "C2_damping":
                ax.plot([r["h"] for r in single], [1 - r["theory_value"] for r in single], "--",
                        color=colour, linewidth=0.8)
        ax.set_xlabel("implicit Euler step h = dt / substeps, s\n(hollow diamonds: substeps of 1/30 s)")
        log_axes(ax, title)
    save(fig, out_dir / "error_vs_dt.png", machine)


def plot_tolerance(rows, out_dir, machine):
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.2))
    uncapped = 100000
    panels = (("A_static", "error_same_mesh", "tolerance", dict(solver="cg", max_iterations=uncapped),
               "A static: |uz/uz_CalculiX - 1| on the same mesh\nvs CG tolerance (dotted: direct solver)"),
              ("T_trajectory", "error", "tolerance", dict(solver="cg", max_iterations=uncapped),
               "T trajectory at dt = 1/60 s: error vs CG tolerance\n(dotted: direct solver, same dt)"),
              (None, None, "max_iterations", None,
               "error vs CG iteration cap (tolerance 1e-10 static, 1e-8 trajectory)"))
    for ax, (case, key, knob, fixed, title) in zip(axes, panels):
        if case is None:
            for case_name, key_name, tol, style in (("A_static", "error_same_mesh", 1e-10, "o-"),
                                                    ("T_trajectory", "error", 1e-8, "s--")):
                for mesh, curve in sweep(rows, case_name, knob, solver="cg").items():
                    curve = [r for r in curve if r["tolerance"] == tol and r["max_iterations"] < uncapped]
                    if curve:
                        ax.plot([r[knob] for r in curve], [max(r[key_name], ERROR_FLOOR) for r in curve],
                                style, color=mesh_style(mesh), label=f"{case_name.split('_')[0]} {mesh}")
            ax.set_xlabel("CG iteration cap")
        else:
            for mesh, curve in sweep(rows, case, knob, **fixed).items():
                colour = mesh_style(mesh)
                ax.plot([r[knob] for r in curve], [max(r[key], ERROR_FLOOR) for r in curve], "o-",
                        color=colour, label=mesh)
                direct = [r for r in rows if r["case"] == case and r["mesh"] == mesh and
                          r["solver"] == "direct" and r["warping"] == curve[0]["warping"] and
                          (not r["substeps"] or (r["dt"] == curve[0]["dt"] and r["substeps"] == 1))]
                if direct:
                    ax.axhline(max(direct[0][key], ERROR_FLOOR), color=colour, linestyle=":",
                               linewidth=0.9)
            ax.set_xlabel("CG tolerance (relative residual)")
            ax.invert_xaxis()
        log_axes(ax, title)
    save(fig, out_dir / "error_vs_tolerance.png", machine)


def advice(rows, budgets=(0.05, 0.1, 0.3, 1, 3, 10, 30, 100)):
    """For each mesh of the trajectory case and each budget, the most accurate setting in budget."""
    mesh_error = {r["mesh"]: r["error"] for r in rows
                  if r["case"] == "B_alpha1" and r["warping"] and r["solver"] == "direct"}
    lines = ["| mesh (elements) | budget, ms per 30 Hz tick | pick | measured ms per 30 Hz tick | "
             "trajectory error (vs converged run, same mesh) | the mesh's own error (case B, alpha = 1, "
             "vs converged 3D) |",
             "|---|---|---|---|---|---|"]
    for mesh in MESHES:
        mine = [r for r in rows if r["case"] == "T_trajectory" and r["mesh"] == mesh]
        if not mine:
            continue
        front = pareto_front(mine)
        previous = None
        for budget in budgets:
            affordable = [r for r in front if r["cost"] <= budget]
            if not affordable:
                continue
            pick = min(affordable, key=lambda r: r["error"])
            if pick is previous:
                continue
            previous = pick
            own = mesh_error.get(mesh, math.nan)
            lines.append(f"| {mesh} ({pick['elements']} elements) | {budget:g} | {label(pick, False)} | "
                         f"{pick['cost']:.3g} | {100 * pick['error']:.2g} % | "
                         f"{100 * own:.2g} % |")
    return "\n".join(lines) + "\n"


def pareto_tables(rows):
    """Every case's Pareto front as a markdown table (for the README and the record)."""
    text = []
    for case in CASES:
        mine = [r for r in rows if r["case"] == case]
        if not mine:
            continue
        unit = "ms per 30 Hz tick" if mine[0]["substeps"] else "ms per solve"
        text.append(f"\n**{case}** Pareto front\n\n| setting | {unit} | error | CG it/solve | memory, MB |\n"
                    "|---|---|---|---|---|")
        for r in pareto_front(mine):
            text.append(f"| {label(r)} | {r['cost']:.3g} | {r['error']:.3g} | "
                        f"{r['iterations_mean']:.0f} | {r['memory_bytes'] / 1e6:.2f} |")
    return "\n".join(text) + "\n"


def surface_table(rows):
    """The beam voxelized from its surface beside the shipped meshes: static errors and times."""
    def cell(case, mesh):
        warped = case != "A_static"  # a linear static solve needs no rotations
        mine = [r for r in rows if r["case"] == case and r["mesh"] == mesh
                and bool(r["warping"]) == warped and r["solver"] == "direct"]
        return f"{100 * mine[0]['error']:.2g} % in {mine[0]['cost']:.3g} ms" if mine else "-"
    lines = ["\n**Surface beams** (case A linear static, linear FEM, and B at alpha = 1, warped; "
             "LDLT; error against the converged 3D reference; ms of the whole solve)\n",
             "| mesh | elements | A | B |", "|---|---|---|---|"]
    for mesh in meshes_of([r for r in rows if r["case"].startswith("A")]):
        elements = next(r["elements"] for r in rows if r["mesh"] == mesh)
        lines.append(f"| {mesh} | {elements} | {cell('A_static', mesh)} | "
                     f"{cell('B_alpha1', mesh)} |")
    return "\n".join(lines) + "\n"


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="plot_accuracy.py", formatter_class=argparse.RawDescriptionHelpFormatter,
        description=__doc__)
    parser.add_argument("csv", help="the CSV deformable_sim_bench wrote")
    parser.add_argument("output_dir", help="where the charts and advice.md go")
    return parser.parse_args(argv)


def main():
    arguments = parse_arguments(sys.argv[1:])
    rows = read_rows(arguments.csv)
    out_dir = Path(arguments.output_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    machine_file = Path(arguments.csv).with_name("machine.txt")
    machine = machine_file.read_text().strip().splitlines()[0] if machine_file.exists() else ""
    for case in CASES:
        mine = [r for r in rows if r["case"] == case]
        if mine:
            plot_case(case, mine, out_dir, machine)
    plot_dt(rows, out_dir, machine)
    plot_tolerance(rows, out_dir, machine)
    (out_dir / "advice.md").write_text(advice(rows) + pareto_tables(rows) + surface_table(rows))
    print(f"wrote {len(list(out_dir.glob('*.png')))} charts and advice.md to {out_dir}")


if __name__ == "__main__":
    main()
