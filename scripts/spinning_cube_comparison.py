#!/usr/bin/python3
"""Compare every time integrator of estep on the spinning cube.

Runs energy-stepping (h = 1e-5), explicit Newmark (dt = 0.0082 and 0.0204), the four implicit
methods (ida bdf, arkode midpoint, arkode irk, energy momentum) and the converged Newmark run
(dt = 1e-4, the reference), all to the same end time, each into its own directory under the
output directory. Then writes one table, comparison.md and comparison.csv, with per run: steps,
mean step, energy drift, angular momentum drift, the error of the tracked point against the
reference, wall seconds and status; and two plots, energy.png (total energy against t) and
tracked_point_error.png (the tracked point's distance from the reference against t).

Drifts are max over the history samples (every 0.1) of |X(t) - X(0)| / |X(0)|; the "end"
columns are the drifts at the last step from summary.json. The samples between the steps of the
step-based methods come from a cubic Hermite interpolant, whose own error shows in the sampled
drifts; at the steps themselves see the "end" columns. For energy-stepping the conserved energy
is the terraced energy T + L h; its true energy T + V is reported as well.

Usage: scripts/spinning_cube_comparison.py [--estep PATH] [--end-time T] [--output DIR] [--reuse]
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (name of the run's directory, method, setting, parameter file)
RUNS = [
    ("energy_stepping", "energy stepping", "h = 1e-5", "spinning_cube.prm"),
    ("newmark_0.0082", "explicit newmark", "dt = 0.0082", "spinning_cube_newmark_0.0082.prm"),
    ("newmark_0.0204", "explicit newmark", "dt = 0.0204", "spinning_cube_newmark_0.0204.prm"),
    ("ida_bdf", "ida bdf", "adaptive, rtol 1e-6", "spinning_cube_ida_bdf.prm"),
    ("arkode_midpoint", "arkode midpoint", "dt = 0.0204", "spinning_cube_arkode_midpoint.prm"),
    ("arkode_irk", "arkode irk", "adaptive order 3, rtol 1e-6", "spinning_cube_arkode_irk.prm"),
    ("energy_momentum", "energy momentum", "dt = 0.0204", "spinning_cube_energy_momentum.prm"),
]
REFERENCE = ("newmark_converged", "explicit newmark (reference)", "dt = 1e-4",
             "spinning_cube_newmark_converged.prm")
HISTORY_INTERVAL = 0.1

# Columns of the table: (key, heading). The CSV has the keys as its header.
COLUMNS = [
    ("run", "run"),
    ("method", "method"),
    ("setting", "step or h"),
    ("steps", "steps"),
    ("mean_step", "mean step"),
    ("energy_drift", "energy drift (conserved)"),
    ("true_energy_drift", "T+V drift"),
    ("end_energy_drift", "T+V drift at end"),
    ("lz_drift", "Lz drift"),
    ("end_lz_drift", "Lz drift at end"),
    ("point_error", "tracked-point error"),
    ("wall_seconds", "wall s"),
    ("status", "status"),
]


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default_estep = os.environ.get("ESTEP", os.path.join(SOURCE_DIR, "build", "bin", "estep"))
    parser.add_argument("--estep", default=default_estep,
                        help="the estep executable (default: $ESTEP, else build/bin/estep)")
    parser.add_argument("--end-time", type=float, default=20.0,
                        help="common end time of all runs (default 20)")
    parser.add_argument("--output",
                        default=os.path.join(SOURCE_DIR, "output", "spinning_cube_comparison"),
                        help="output directory (default: output/spinning_cube_comparison of the "
                        "source tree)")
    parser.add_argument("--reuse", action="store_true",
                        help="skip runs whose summary.json exists with the same end time")
    return parser.parse_args()


def read_summary(directory):
    """summary.json of a run as a dict, or None if there is none."""
    path = os.path.join(directory, "summary.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def read_history(directory):
    """history.csv of a run as {column name: numpy array}, or None if there is none."""
    path = os.path.join(directory, "history.csv")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = [values for values in map(parsed_row, csv.DictReader(f)) if values is not None]
    if not rows:
        return None
    return {key: np.array([row[key] for row in rows]) for key in rows[0]}


def parsed_row(row):
    """A history row as floats, or None for a row cut short (by a run that crashed)."""
    try:
        return {key: float(value) for key, value in row.items()}
    except (TypeError, ValueError):
        return None


def can_reuse(directory, end_time):
    summary = read_summary(directory)
    return summary is not None and math.isclose(summary["end time"], end_time)


def run_estep(estep, parameter_file, directory, end_time):
    """Run one estep job into directory; return its exit code (negative: killed by a signal)."""
    os.makedirs(directory, exist_ok=True)
    for stale in ("summary.json", "history.csv"):
        if os.path.exists(os.path.join(directory, stale)):
            os.remove(os.path.join(directory, stale))
    command = [estep, os.path.join(SOURCE_DIR, "parameter_files", parameter_file),
               "-s", f"Time integration/End time={end_time:.17g}",
               "-s", f"Output directory={directory}",
               "-s", "Postprocessors/List=history, step histogram, progress",
               "-s", f"Output/History interval={HISTORY_INTERVAL}",
               "-s", "Postprocessors/List=history, step histogram"]
    with open(os.path.join(directory, "log.txt"), "w") as log:
        return subprocess.run(command, stdout=log, stderr=subprocess.STDOUT).returncode


def relative_drift(values):
    """max |x(t) - x(0)| / |x(0)| over the samples."""
    return float(np.max(np.abs(values - values[0])) / abs(values[0]))


def tracked_point_error(history, reference):
    """Times common to both histories and the distance of the tracked points there."""
    def keyed(h):
        return {round(t, 9): i for i, t in enumerate(h["time"])}
    mine, theirs = keyed(history), keyed(reference)
    times = sorted(set(mine) & set(theirs))
    i = [mine[t] for t in times]
    j = [theirs[t] for t in times]
    squared = sum((history[f"tracked_{c}"][i] - reference[f"tracked_{c}"][j]) ** 2 for c in "xyz")
    return np.array(times), np.sqrt(squared)


def status_of(summary, exit_code):
    if summary is None:
        return f"failed (exit code {exit_code}, no summary.json)"
    if summary["status"] == "completed":
        return "completed"
    return f"{summary['status']} at t = {summary['final time']:.4g}"


def evaluate(run, summary, history, reference, exit_code):
    """One row of the table for a run."""
    name, method, setting, _ = run
    row = {key: "" for key, _ in COLUMNS}
    row.update(run=name, method=method, setting=setting, status=status_of(summary, exit_code))
    if summary is None or history is None:
        return row
    conserved = ("terraced_total_energy" if summary["method"] == "energy stepping"
                 else "total_energy")
    lz0 = abs(summary["initial momenta"]["angular"][2])
    row.update(steps=summary["counters"]["steps"],
               mean_step=summary["mean step"],
               energy_drift=relative_drift(history[conserved]),
               true_energy_drift=relative_drift(history["total_energy"]),
               end_energy_drift=summary["energies"]["total energy drift"],
               lz_drift=relative_drift(history["angular_momentum_z"]),
               end_lz_drift=summary["angular momentum drift"] / lz0,
               wall_seconds=summary["wall seconds"])
    if reference is not None:
        _, errors = tracked_point_error(history, reference)
        row["point_error"] = float(np.max(errors)) if len(errors) else float("nan")
    return row


def formatted(key, value):
    if value == "" or isinstance(value, str):
        return value
    if key == "steps":
        return f"{value:,}"
    if key == "wall_seconds":
        return f"{value:.0f}" if value >= 100 else f"{value:.3g}"
    if key == "mean_step":
        return f"{value:.3g}"
    return f"{value:.1e}"


def write_markdown(rows, path):
    with open(path, "w") as f:
        f.write("| " + " | ".join(heading for _, heading in COLUMNS) + " |\n")
        f.write("|" + "---|" * len(COLUMNS) + "\n")
        for row in rows:
            f.write("| " + " | ".join(formatted(key, row[key]) for key, _ in COLUMNS) + " |\n")


def write_csv(rows, path):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=[key for key, _ in COLUMNS])
        writer.writeheader()
        for row in rows:
            writer.writerow({key: (repr(value) if isinstance(value, float) else value)
                             for key, value in row.items()})


def label(run):
    return f"{run[1]}, {run[2]}"


def plot_energy(histories, path):
    """Total energy T + V relative to its initial value, linear and logarithmic."""
    fig, axes = plt.subplots(1, 2, figsize=(14, 5))
    for run, history in histories:
        energy = history["total_energy"]
        deviation = (energy - energy[0]) / abs(energy[0])
        axes[0].plot(history["time"], deviation, lw=0.8, label=label(run))
        axes[1].semilogy(history["time"][1:], np.abs(deviation[1:]) + 1e-17, lw=0.8,
                         label=label(run))
        if run[1] == "energy stepping":
            terraced = history["terraced_total_energy"]
            axes[1].semilogy(history["time"][1:],
                             np.abs(terraced[1:] - terraced[0]) / abs(terraced[0]) + 1e-17,
                             lw=0.8, ls="--", color="black",
                             label="energy stepping: terraced energy T + L h")
    axes[0].set_title("total energy: (E(t) - E(0)) / E(0), E = T + V")
    axes[1].set_title("|E(t) - E(0)| / E(0) (log scale; + 1e-17 to show zeros)")
    for axis in axes:
        axis.set_xlabel("t")
    axes[1].legend(fontsize=7)
    fig.suptitle("spinning cube: energy of every method (history samples every 0.1)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_point_error(histories, reference, path):
    fig, axis = plt.subplots(figsize=(9, 5))
    for run, history in histories:
        times, errors = tracked_point_error(history, reference)
        axis.semilogy(times[1:], errors[1:] + 1e-17, lw=0.8, label=label(run))
    axis.set_xlabel("t")
    axis.set_ylabel("|x(t) - x_ref(t)|")
    axis.set_title("spinning cube: tracked point X = (0.5, 1, 1) against Newmark dt = 1e-4")
    axis.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run_all(runs, estep, output, end_time, reuse):
    """Run (or reuse) every run; return {name: exit code} (None for a reused run)."""
    exit_codes = {}
    for run in runs:
        directory = os.path.join(output, run[0])
        if reuse and can_reuse(directory, end_time):
            print(f"{run[0]}: reused")
            exit_codes[run[0]] = None
            continue
        start = time.monotonic()
        exit_codes[run[0]] = run_estep(estep, run[3], directory, end_time)
        print(f"{run[0]}: exit code {exit_codes[run[0]]}, {time.monotonic() - start:.1f} s",
              flush=True)
    return exit_codes


def main():
    arguments = parse_arguments()
    if not os.access(arguments.estep, os.X_OK):
        print(f"error: no estep executable at {arguments.estep} (use --estep or $ESTEP)")
        return 1
    output = os.path.abspath(arguments.output)
    runs = RUNS + [REFERENCE]
    exit_codes = run_all(runs, arguments.estep, output, arguments.end_time, arguments.reuse)

    results = [(run, read_summary(os.path.join(output, run[0])),
                read_history(os.path.join(output, run[0]))) for run in runs]
    reference = results[-1][2]
    if reference is None:
        print("warning: no reference history; the tracked-point errors are left empty")
    rows = [evaluate(run, summary, history, reference, exit_codes[run[0]])
            for run, summary, history in results]
    write_markdown(rows, os.path.join(output, "comparison.md"))
    write_csv(rows, os.path.join(output, "comparison.csv"))

    histories = [(run, history) for run, _, history in results[:-1] if history is not None]
    plot_energy(histories, os.path.join(output, "energy.png"))
    if reference is not None:
        plot_point_error(histories, reference, os.path.join(output, "tracked_point_error.png"))
    with open(os.path.join(output, "comparison.md")) as f:
        print(f.read(), end="")
    print(f"written: {output}/comparison.md, comparison.csv, energy.png, tracked_point_error.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
