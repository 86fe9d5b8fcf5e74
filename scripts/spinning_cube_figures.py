#!/usr/bin/python3
"""Draw the spinning-cube figures 2.11-2.14 of the reference text from the runs of scripts/spinning_cube_runs.sh.

Figures 2.11-2.13 compare energy-stepping with explicit Newmark at the mean step energy-stepping
selected: the tracked point X = (0.5, 1, 1) (x, y, z against t), the total, potential and
kinetic energies, and the angular momentum Lz. Figure 2.14 shows the histograms of the time
steps energy-stepping selected at h = 3e-5 and 6e-5.

Usage: scripts/spinning_cube_figures.py [--output output]   (reads and writes in that directory)
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from run_output import read_history


# The columns the comparison figures draw.
COLUMNS = ["time", "tracked_x", "tracked_y", "tracked_z", "total_energy", "potential_energy",
           "kinetic_energy", "angular_momentum_z"]


def history(root, run):
    path = os.path.join(root, run, "history.csv")
    if not os.path.exists(path):
        return None
    return read_history(path, COLUMNS)


def comparison(root, figure, runs, title):
    """runs: list of (directory, label, colour)."""
    data = [(history(root, d), label, colour) for d, label, colour in runs]
    missing = [d for (h, _, _), (d, _, _) in zip(data, runs) if h is None]
    if missing:
        print(f"{figure}: skipped, no history in {', '.join(missing)}")
        return
    fig, axes = plt.subplots(2, 3, figsize=(15, 8))
    for (h, label, colour) in data:
        for axis, c in zip(axes[0], "xyz"):
            axis.plot(h["time"], h[f"tracked_{c}"], color=colour, lw=0.8, label=label)
            axis.set_title(f"tracked point: {c}")
            axis.set_xlabel("t")
        axes[1][0].plot(h["time"], h["total_energy"], color=colour, lw=0.8, label=label)
        axes[1][1].plot(h["time"], h["potential_energy"], color=colour, lw=0.8, label=label)
        axes[1][1].plot(h["time"], h["kinetic_energy"], color=colour, lw=0.8, ls="--")
        axes[1][2].plot(h["time"], h["angular_momentum_z"], color=colour, lw=0.8, label=label)
    axes[1][0].set_title("total energy T + V")
    axes[1][1].set_title("potential (solid) and kinetic (dashed) energy")
    axes[1][2].set_title("angular momentum Lz")
    for axis in axes[1]:
        axis.set_xlabel("t")
    axes[0][0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(os.path.join(root, figure), dpi=110)
    print(f"{figure}: written")


def histograms(root, figure):
    runs = [("spinning_cube_h3e-5", "h = 3e-5"), ("spinning_cube_h6e-5", "h = 6e-5")]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for axis, (run, label) in zip(axes, runs):
        path = os.path.join(root, run, "step_histogram.csv")
        if not os.path.exists(path):
            print(f"{figure}: skipped, no {path}")
            return
        with open(path) as f:
            rows = list(csv.DictReader(f))
        lower = [float(r["lower"]) for r in rows]
        upper = [float(r["upper"]) for r in rows]
        count = [int(r["count"]) for r in rows]
        axis.bar(lower, count, width=[u - l for l, u in zip(lower, upper)], align="edge")
        axis.set_xscale("log")
        summary = json.load(open(os.path.join(root, run, "summary.json")))
        axis.set_title(f"{label}: {summary['counters']['steps']} steps, mean "
                       f"{summary['mean step']:.4f}")
        axis.set_xlabel("time step")
        axis.set_ylabel("count")
    fig.suptitle("spinning cube: time steps selected by energy-stepping (figure 2.14)")
    fig.tight_layout()
    fig.savefig(os.path.join(root, figure), dpi=110)
    print(f"{figure}: written")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default="output")
    root = parser.parse_args().output
    comparison(root, "figure_2_11.png",
               [("spinning_cube", "energy-stepping, h = 1e-5", "tab:blue"),
                ("spinning_cube_newmark_0.0082", "Newmark, dt = 0.0082", "black"),
                ("spinning_cube_newmark_converged", "Newmark, dt = 1e-4", "tab:red")],
               "spinning cube: energy-stepping h = 1e-5 against Newmark (figure 2.11)")
    comparison(root, "figure_2_12.png",
               [("spinning_cube_h3e-5", "energy-stepping, h = 3e-5", "tab:blue"),
                ("spinning_cube_newmark_0.0204", "Newmark, dt = 0.0204", "black")],
               "spinning cube: energy-stepping h = 3e-5 against Newmark (figure 2.12)")
    comparison(root, "figure_2_13.png",
               [("spinning_cube_h6e-5", "energy-stepping, h = 6e-5", "tab:blue"),
                ("spinning_cube_newmark_0.0381", "Newmark, dt = 0.0381", "black")],
               "spinning cube: energy-stepping h = 6e-5 against Newmark (figure 2.13)")
    histograms(root, "figure_2_14.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
