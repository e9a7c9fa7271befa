#!/usr/bin/env python3
"""Measured against simulated for every observation of a material fit, over time.

    scripts/plot_identify.py [--residuals] FIT.csv FIT.png

FIT.csv is the table deformable_sim_identify --plot FIT.png writes beside the PNG (columns
observation, component, time, measured, guess, fitted). One panel per observation: each
component's measured samples as dots, the simulation with the first guess dashed, with the fitted
values solid; with --residuals, simulated minus measured (first guess faint, fit solid), where a
step or an offset hides in the values. Needs only Debian's python3-matplotlib (Agg backend: no
display).
"""
import argparse
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)


def read_table(path):
    """{observation: {component: (times, measured, guess, fitted)}} in the file's order."""
    table = defaultdict(lambda: defaultdict(lambda: ([], [], [], [])))
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            columns = table[row["observation"]][row["component"]]
            for column, key in zip(columns, ("time", "measured", "guess", "fitted")):
                column.append(float(row[key]))
    return table


def plot(table, png, residuals=False):
    figure, axes = plt.subplots(len(table), 1, figsize=(10, 3.2 * len(table)), squeeze=False)
    for axis, (observation, components) in zip(axes[:, 0], table.items()):
        for k, (component, (t, measured, guess, fitted)) in enumerate(components.items()):
            colour = f"C{k}"
            if residuals:
                axis.plot(t, [g - m for g, m in zip(guess, measured)], ".", color=colour,
                          markersize=1, alpha=0.15)
                axis.plot(t, [f - m for f, m in zip(fitted, measured)], ".", color=colour,
                          markersize=2, alpha=0.6, label=component)
            else:
                axis.plot(t, measured, ".", color=colour, markersize=2, alpha=0.4)
                axis.plot(t, guess, "--", color=colour, linewidth=1)
                axis.plot(t, fitted, "-", color=colour, linewidth=1.2, label=component)
        title = ("simulated minus measured: faint first guess, solid fit" if residuals else
                 "dots measured, dashed first guess, solid fit")
        axis.set_title(f"{observation}: {title}", fontsize=9)
        axis.set_xlabel("time (s)")
        axis.legend(fontsize=7, loc="upper right", ncol=3)
        axis.grid(alpha=0.3)
    figure.tight_layout()
    figure.savefig(png, dpi=110)


def main():
    parser = argparse.ArgumentParser(prog="plot_identify.py", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", help="the table deformable_sim_identify --plot wrote")
    parser.add_argument("png", help="the chart to write")
    parser.add_argument("--residuals", action="store_true",
                        help="draw simulated minus measured instead of the values")
    arguments = parser.parse_args(sys.argv[1:])
    plot(read_table(arguments.csv), arguments.png, arguments.residuals)


if __name__ == "__main__":
    main()
