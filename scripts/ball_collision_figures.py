#!/usr/bin/python3
"""Draw the colliding-ball figures 2.16 and 2.17 of the reference text from the runs of parameter_files/ball_collision*.prm.

Figure 2.16: kinetic, potential and total energy against time for energy-stepping (penalty
contact, h = 1e3) and explicit Newmark (dt = 3e-5), and the time steps energy-stepping took
(smallest and largest step between two history rows). Figure 2.17: the centre-of-mass
velocity V and Omega = angular momentum / mass of each ball and of the system. A run of the
exact-impenetrability variant, if present, is drawn beside them. The table of the summaries
(steps, drifts, restitution, contact duration, Hertz estimate) is printed and written to
ball_collision_table.md.

Usage (from the source directory, after the runs):
  estep parameter_files/ball_collision.prm
  estep parameter_files/ball_collision_newmark.prm
  estep parameter_files/ball_collision_impenetrable.prm      (optional)
  scripts/ball_collision_figures.py [--output output]
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from run_output import fail, read_history

RUNS = [("ball_collision", "energy-stepping, penalty, h = 1e3", "tab:blue", "-"),
        ("ball_collision_newmark", "Newmark, penalty, dt = 3e-5", "black", "--"),
        ("ball_collision_impenetrable", "energy-stepping, impenetrable", "tab:green", ":")]


# The columns the figures draw: energies, steps, and V and Omega of each ball and of the system.
COLUMNS = ["time", "total_energy", "kinetic_energy", "potential_energy", "min_step", "max_step"]
COLUMNS += [f"{q}{owner}_{c}" for q in ("V", "Omega") for owner in ("1", "2", "") for c in "xyz"]


def load(root, run):
    """(history as {column: list of floats}, summary dict), or None if the run is missing."""
    directory = os.path.join(root, run)
    history_path = os.path.join(directory, "history.csv")
    summary_path = os.path.join(directory, "summary.json")
    if not (os.path.exists(history_path) and os.path.exists(summary_path)):
        return None
    history = read_history(history_path, COLUMNS)
    try:
        with open(summary_path) as f:
            return history, json.load(f)
    except ValueError as error:
        fail(f"<{summary_path}> is not JSON: {error}")


def energies(root, runs, figure):
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5))
    for (history, summary), label, colour, style in runs:
        t = history["time"]
        # Steps from the second row on: the first precedes every step (its steps are 0).
        t_steps = t[1:]
        min_step, max_step = history["min_step"][1:], history["max_step"][1:]
        for key, name in (("total_energy", "T + V"), ("kinetic_energy", "T"),
                          ("potential_energy", "V")):
            left.plot(t, history[key], color=colour, ls=style, lw=0.9,
                      label=f"{name}, {label}" if key == "total_energy" else None)
        if summary["method"] != "energy stepping":
            right.plot(t_steps, max_step, color=colour, ls=style, lw=0.9, label=label)
        else:
            right.fill_between(t_steps, min_step, max_step, color=colour, alpha=0.35, lw=0)
            right.plot(t_steps, min_step, color=colour, lw=0.6, label=label + " (range per row)")
    left.set_xlabel("t")
    left.set_ylabel("energy")
    left.set_title("total (top), kinetic and potential energy")
    left.legend(fontsize=7)
    right.set_yscale("log")
    right.set_xlabel("t")
    right.set_ylabel("time step")
    right.set_title("time steps")
    right.legend(fontsize=7)
    fig.suptitle("colliding balls: energies and time steps (figure 2.16)")
    fig.tight_layout()
    fig.savefig(os.path.join(root, figure), dpi=110)
    print(f"{figure}: written")


def velocities(root, runs, figure):
    owners = [("1", "ball 1"), ("2", "ball 2"), ("", "system")]
    components = (("x", "tab:red"), ("y", "tab:green"), ("z", "tab:blue"))
    fig, axes = plt.subplots(2, 3, figsize=(15, 8), sharex=True)
    for (history, _), label, _, style in runs:
        for row, quantity in enumerate(("V", "Omega")):
            for column, (suffix, owner) in enumerate(owners):
                axis = axes[row][column]
                for component, colour in components:
                    axis.plot(history["time"], history[f"{quantity}{suffix}_{component}"],
                              color=colour, ls=style, lw=0.9)
                axis.set_title(f"{quantity} of {owner}")
    for axis in axes[1]:
        axis.set_xlabel("t")
    legend = [plt.Line2D([], [], color=colour, label=component) for component, colour in components]
    legend += [plt.Line2D([], [], color="grey", ls=style, label=label) for _, label, _, style in runs]
    axes[0][0].legend(handles=legend, fontsize=7)
    fig.suptitle("colliding balls: centre-of-mass velocity V and Omega = L / m (figure 2.17)")
    fig.tight_layout()
    fig.savefig(os.path.join(root, figure), dpi=110)
    print(f"{figure}: written")


def table(root, runs):
    lines = ["| run | steps | wall s | energy drift | linear momentum drift | angular momentum drift "
             "| restitution | contact duration | largest intersecting pairs |",
             "|---|---|---|---|---|---|---|---|---|"]
    hertz = None
    for (_, summary), label, _, _ in runs:
        energies = summary["energies"]
        drift = energies.get("terraced energy drift", energies["total energy drift"])
        contact = summary.get("contact", {})
        hertz = summary["problem"].get("Hertz contact duration estimate", hertz)
        lines.append(
            f"| {label} | {summary['counters']['steps']:,} | {summary['wall seconds']:.3g} "
            f"| {drift:.2g} | {summary['linear momentum drift']:.2g} "
            f"| {summary['angular momentum drift']:.2g} "
            f"| {contact.get('coefficient of restitution', float('nan')):.3f} "
            f"| {contact.get('contact duration', float('nan')):.4f} "
            f"| {contact.get('largest number of intersecting face pairs', 0)} |")
    lines.append("")
    lines.append("Reference text: restitution 0.964, contact duration 0.0476; Hertz estimate "
                 + (f"{hertz:.4f}" if hertz is not None else "not available") + ".")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    with open(os.path.join(root, "ball_collision_table.md"), "w") as f:
        f.write(text)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default="output",
                        help="the directory holding the runs' output directories")
    root = parser.parse_args().output
    runs = []
    for run, label, colour, style in RUNS:
        data = load(root, run)
        if data is None:
            print(f"{run}: no history.csv and summary.json in {os.path.join(root, run)}, left out")
        else:
            runs.append((data, label, colour, style))
    if not runs:
        print("no runs found: run the parameter files first (see --help)", file=sys.stderr)
        return 1
    energies(root, runs, "figure_2_16.png")
    velocities(root, runs, "figure_2_17.png")
    table(root, runs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
