#!/usr/bin/python3
"""Accuracy per cost of every time integrator of estep, on the spinning cube and the argon cluster.

For each problem the script runs a reference and, at several settings each, energy-stepping,
explicit Newmark and (on the cube) the four implicit SUNDIALS methods, and measures per run the
error against the reference, the cost (wall seconds of the time loop, gradient evaluations and
the other work counters of summary.json, CPU seconds of the process), the largest energy error
over the history and the largest step taken. A bracketing search over the time step finds the
largest step at which explicit Newmark stays stable.

The cube (parameter_files/spinning_cube.prm, to t = 10, history every 0.1):
  reference  explicit Newmark, dt = 1e-4;
  error      the largest distance over the history rows (t = 0, 0.1, ..., 10) between the
             tracked point X = (0.5, 1, 1) and its position in the reference; also the distance
             at the last row;
  runs       energy-stepping h = 1.25e-6 ... 4e-5, Newmark dt = 1e-3 ... 2e-2, IDA BDF and
             ARKode DIRK at three relative tolerances (absolute tolerance 1e-2 of it), the
             implicit midpoint rule at dt = 0.025 ... 0.2 and the energy-momentum scheme at
             dt = 0.025 ... 0.2 (the largest steps fail: their Newton iteration does not converge).
The argon cluster (parameter_files/argon_cluster*.prm, over 1 ns, history every 1 ps):
  reference  velocity Verlet, dt = 10 fs, as in scripts/argon_convergence.py;
  error      the relative H1 error | ||q_h|| - ||q|| | / ||q|| of scripts/argon_convergence.py;
  runs       energy-stepping h = 1e-4 ... 1e-1 |E0|, Verlet dt = 5 ... 80 fs. The implicit
             methods need the Hessian of the system, which the Lennard-Jones cluster does not
             provide: they are not run.

Counting: "gradient evaluations" are the gradient evaluations of energy-stepping and Newmark
and the residual evaluations of the implicit methods (each evaluates the internal force once,
and the energy to reject inverted cells); energy-stepping's energy evaluations and enclosures,
and the implicit methods' Jacobian setups (assembly of the tangent stiffness and its sparse LU
factorisation), are counted separately; "all evaluations" adds energy-stepping's gradient and
energy evaluations and enclosures, each counted as one.

Stability: a trial run of explicit Newmark over a horizon (the cube: t = 250, the seed's longest
run; argon: 1 ns) is stable when it completes with its largest relative energy error over the
history below 0.1; the search doubles or halves until it holds a stable and an unstable step,
then bisects (--bisections). It assumes that stability is monotone in dt.

Writes to <output>/<problem>/: accuracy_per_cost_<problem>.csv and .md (one row per run),
stability_<problem>.csv (the trials of the search), accuracy_per_cost_<problem>.png (error
against wall seconds, gradient evaluations and process CPU seconds, log-log, one series per
method); each
run in runs/<name>/ with run.json (its settings, exit code, process wall and CPU seconds). A run
whose run.json has the same settings and whose summary.json is final (not running or
interrupted) is reused, so an interrupted study picks up where it stopped. At most --jobs runs go
at a time, each under `nice -n <--nice>`.

Usage: scripts/accuracy_per_cost.py [--problem cube|argon|both] [--estep PATH] [--output DIR]
           [--jobs N] [--nice N] [--methods LIST] [--cube-end-time T] [--argon-end-time T]
           [--bisections N]
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import subprocess
import sys
import threading
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from argon_convergence import E0 as ARGON_E0, ONE_NS, TAU_FS  # noqa: E402
from spinning_cube_comparison import (read_history, read_summary,  # noqa: E402
                                      tracked_point_error)

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PARAMETERS = os.path.join(SOURCE_DIR, "parameter_files")

METHODS = ["energy stepping", "explicit newmark", "ida bdf", "arkode irk", "arkode midpoint",
           "energy momentum"]
MARKERS = dict(zip(METHODS, ["o", "s", "^", "v", "D", "P"]))
COLOURS = dict(zip(METHODS, ["C3", "C0", "C2", "C4", "C1", "C5"]))
STABILITY_ENERGY_LIMIT = 0.1

# The cube: energy steps, Newmark steps, tolerances and implicit steps.
CUBE_END_TIME = 10.0
CUBE_REFERENCE_STEP = 1e-4
CUBE_ENERGY_STEPS = [1.25e-6, 2.5e-6, 5e-6, 1e-5, 2e-5, 4e-5]
CUBE_NEWMARK_STEPS = [1e-3, 2e-3, 5e-3, 1e-2, 2e-2]
CUBE_TOLERANCES = {"ida bdf": [1e-3, 1e-4, 1e-5], "arkode irk": [1e-2, 1e-3, 1e-4]}
# The fixed-step implicit methods at their larger steps fail to converge (Newton, 10 iterations)
# near t = 1.8: midpoint at 0.2, energy-momentum at 0.1 and 0.2; those runs stay in the table.
CUBE_IMPLICIT_STEPS = {"arkode midpoint": [0.025, 0.05, 0.1, 0.2],
                       "energy momentum": [0.025, 0.035, 0.05, 0.1, 0.2]}
CUBE_FIRST_STEP = 0.0204          # the initial step of the adaptive methods (their .prm files)
CUBE_STABILITY = dict(horizon=250.0, stable=0.0204, unstable=0.0381)

# The argon cluster, in reduced units (scripts/argon_convergence.py): energy steps in |E0|,
# Verlet steps in fs.
ARGON_HISTORY_INTERVAL = 0.46305  # 1 ps (the H1 norm does not depend on it)
ARGON_REFERENCE_FS = 10.0
ARGON_ENERGY_STEPS = [1e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1]
ARGON_NEWMARK_FS = [5.0, 20.0, 30.0, 40.0, 60.0, 80.0]
ARGON_STABILITY = dict(horizon=ONE_NS, stable=80.0, unstable=120.0)

COLUMNS = [
    ("run", "run"), ("method", "method"), ("setting", "setting"), ("status", "status"),
    ("error", "error"), ("final_error", "error at end"), ("steps", "steps"),
    ("gradient_evaluations", "gradient evaluations"),
    ("energy_evaluations", "energy evaluations"), ("enclosures", "enclosures"),
    ("all_evaluations", "all evaluations"), ("jacobian_setups", "Jacobian setups"),
    ("newton_iterations", "Newton iterations"), ("mean_step", "mean step"),
    ("max_step", "largest step"), ("energy_error", "energy error T+V"),
    ("terraced_energy_error", "energy error T+Lh"), ("wall_seconds", "wall s"),
    ("cpu_seconds", "process CPU s"),
]


class Run:
    """One estep run: where it goes, what it is, and the settings it is run with."""

    def __init__(self, name, method, setting, value, parameter_file, settings):
        self.name, self.method, self.setting, self.value = name, method, setting, value
        self.parameter_file, self.settings = parameter_file, settings


class Study:
    """Runs estep jobs into <output>/runs/, reusing finished ones, at most `jobs` at a time."""

    def __init__(self, estep, output, nice, jobs):
        self.estep, self.output, self.nice = estep, output, nice
        self.slots = threading.Semaphore(jobs)
        self.lock = threading.Lock()

    def directory(self, run):
        return os.path.join(self.output, "runs", run.name)

    def request(self, run):
        return {"parameter file": run.parameter_file, "settings": run.settings}

    def reusable(self, run):
        directory = self.directory(run)
        summary = read_summary(directory)
        path = os.path.join(directory, "run.json")
        if summary is None or summary.get("status") in ("running", "interrupted") \
                or not os.path.exists(path):
            return False
        with open(path) as f:
            record = json.load(f)
        return record.get("request") == self.request(run)

    def execute(self, run):
        """Run (or reuse) one job; return (summary, history, run.json record)."""
        directory = self.directory(run)
        if self.reusable(run):
            self.report(f"{run.name}: reused")
        else:
            with self.slots:
                self.launch(run, directory)
        with open(os.path.join(directory, "run.json")) as f:
            record = json.load(f)
        return read_summary(directory), read_history(directory), record

    def launch(self, run, directory):
        os.makedirs(directory, exist_ok=True)
        for stale in ("summary.json", "history.csv", "run.json"):
            if os.path.exists(os.path.join(directory, stale)):
                os.remove(os.path.join(directory, stale))
        settings = dict(run.settings, **{"Output directory": directory})
        command = ["nice", "-n", str(self.nice)] if self.nice else []
        command += [self.estep, os.path.join(PARAMETERS, run.parameter_file)]
        for key, value in settings.items():
            command += ["--set", f"{key}={value}"]
        start = time.monotonic()
        with open(os.path.join(directory, "log.txt"), "w") as log:
            process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
            _, status, usage = os.wait4(process.pid, 0)
            process.returncode = os.waitstatus_to_exitcode(status)
        record = {"request": self.request(run), "exit code": process.returncode,
                  "process wall seconds": time.monotonic() - start,
                  "cpu seconds": usage.ru_utime + usage.ru_stime}
        with open(os.path.join(directory, "run.json"), "w") as f:
            json.dump(record, f, indent=2)
        self.report(f"{run.name}: exit code {process.returncode}, "
                    f"{record['process wall seconds']:.1f} s wall, "
                    f"{record['cpu seconds']:.1f} s CPU")

    def report(self, text):
        with self.lock:
            print(text, flush=True)


# ---------------------------------------------------------------------------------------------
# The runs of each problem.

def cube_settings(end_time, method, **entries):
    settings = {"Time integration/End time": f"{end_time:.17g}",
                "Time integration/Method": method,
                "Output/History interval": "0.1",
                "Postprocessors/List": "history"}
    settings.update(entries)
    return settings


def cube_newmark(name, dt, end_time):
    return Run(name, "explicit newmark", f"dt = {dt:g}", dt, "spinning_cube.prm",
               cube_settings(end_time, "explicit newmark",
                             **{"Time integration/Explicit Newmark/Time step": f"{dt:.17g}"}))


def cube_runs(end_time, methods):
    """The reference and the study's runs of the cube."""
    reference = cube_newmark("reference_newmark_dt0.0001", CUBE_REFERENCE_STEP, end_time)
    runs = []
    implicit = "Time integration/Implicit integrators/"
    if "energy stepping" in methods:
        for h in CUBE_ENERGY_STEPS:
            runs.append(Run(f"energy_stepping_h{h:g}", "energy stepping", f"h = {h:g}", h,
                            "spinning_cube.prm",
                            cube_settings(end_time, "energy stepping", **{
                                "Time integration/Energy stepping/Energy step": f"{h:.17g}"})))
    if "explicit newmark" in methods:
        runs += [cube_newmark(f"newmark_dt{dt:g}", dt, end_time) for dt in CUBE_NEWMARK_STEPS]
    for method, tolerances in CUBE_TOLERANCES.items():
        if method in methods:
            for rtol in tolerances:
                runs.append(Run(f"{method.replace(' ', '_')}_rtol{rtol:g}", method,
                                f"rtol = {rtol:g}", rtol, "spinning_cube.prm",
                                cube_settings(end_time, method, **{
                                    implicit + "Time step": f"{CUBE_FIRST_STEP:g}",
                                    implicit + "Relative tolerance": f"{rtol:g}",
                                    implicit + "Absolute tolerance": f"{rtol * 1e-2:g}"})))
    for method, steps in CUBE_IMPLICIT_STEPS.items():
        if method in methods:
            for dt in steps:
                runs.append(Run(f"{method.replace(' ', '_')}_dt{dt:g}", method, f"dt = {dt:g}",
                                dt, "spinning_cube.prm",
                                cube_settings(end_time, method, **{
                                    implicit + "Time step": f"{dt:.17g}",
                                    implicit + "Newton tolerance": "1e-10"})))
    return reference, runs


def argon_settings(end_time, **entries):
    settings = {"Time integration/End time": f"{end_time:.17g}",
                "Output/History interval": f"{ARGON_HISTORY_INTERVAL:g}",
                "Postprocessors/List": "history, h1 norm"}
    settings.update(entries)
    return settings


def argon_newmark(name, fs, end_time):
    return Run(name, "explicit newmark", f"dt = {fs:g} fs", fs, "argon_cluster_verlet.prm",
               argon_settings(end_time, **{
                   "Time integration/Explicit Newmark/Time step": f"{fs / TAU_FS:.17g}"}))


def argon_runs(end_time, methods):
    reference = argon_newmark("reference_verlet_10fs", ARGON_REFERENCE_FS, end_time)
    runs = []
    if "energy stepping" in methods:
        for h in ARGON_ENERGY_STEPS:
            runs.append(Run(f"energy_stepping_h{h:g}", "energy stepping", f"h = {h:g} |E0|", h,
                            "argon_cluster.prm",
                            argon_settings(end_time, **{
                                "Time integration/Energy stepping/Energy step":
                                    f"{h * ARGON_E0:.17g}"})))
    if "explicit newmark" in methods:
        runs += [argon_newmark(f"verlet_{fs:g}fs", fs, end_time) for fs in ARGON_NEWMARK_FS]
    return reference, runs


# ---------------------------------------------------------------------------------------------
# Measures.

def largest_energy_error(history, column="total_energy"):
    """max over the history rows of |E(t) - E(0)| / |E(0)|."""
    energy = history[column]
    return float(np.max(np.abs(energy - energy[0])) / abs(energy[0]))


def status_of(summary, record):
    if summary is None:
        return f"failed (exit code {record['exit code']}, no summary.json)"
    if summary["status"] == "completed":
        return "completed"
    return f"{summary['status']} at t = {summary['final time']:.4g}"


def evaluate(problem, run, summary, history, record, reference):
    """One row of the table; `reference` is (summary, history) of the reference run."""
    row = {key: "" for key, _ in COLUMNS}
    row.update(run=run.name, method=run.method, setting=run.setting,
               status=status_of(summary, record), cpu_seconds=record["cpu seconds"])
    row["value"] = run.value  # not a column: orders a method's points in the plot
    if summary is None or history is None:
        return row
    counters = summary["counters"]
    gradients = counters.get("gradient evaluations", counters.get("residual evaluations"))
    row.update(steps=counters["steps"], gradient_evaluations=gradients,
               mean_step=summary["mean step"], max_step=summary["max step"],
               energy_error=largest_energy_error(history),
               wall_seconds=summary["wall seconds"])
    for key in ("energy evaluations", "enclosures", "jacobian setups", "newton iterations"):
        if key in counters:
            row[key.replace(" ", "_")] = counters[key]
    if run.method == "energy stepping":
        row["terraced_energy_error"] = largest_energy_error(history, "terraced_total_energy")
        row["all_evaluations"] = (gradients + counters["energy evaluations"]
                                  + counters["enclosures"])
    if problem == "cube":
        times, distances = tracked_point_error(history, reference[1])
        if len(distances):
            row["error"] = float(np.max(distances))
            row["final_error"] = float(distances[-1])
    elif "h1 norm" in summary and summary["status"] == "completed":
        norm = reference[0]["h1 norm"]
        row["error"] = abs(summary["h1 norm"] - norm) / norm
    if problem == "argon":
        for key in ("mean_step", "max_step"):
            row[key] *= TAU_FS  # in fs
    return row


# ---------------------------------------------------------------------------------------------
# The stability search of explicit Newmark.

def stability_search(study, make_run, stable, unstable, bisections):
    """Bracket the largest stable step of explicit Newmark; return the trials in order."""
    trials = []

    def is_stable(dt):
        run = make_run(dt)
        summary, history, record = study.execute(run)
        energy_error = largest_energy_error(history) if history is not None else math.inf
        ok = (summary is not None and summary["status"] == "completed"
              and energy_error < STABILITY_ENERGY_LIMIT)
        trials.append({"dt": dt, "status": status_of(summary, record),
                       "final_time": summary["final time"] if summary else "",
                       "energy_error": energy_error, "stable": ok,
                       "cpu_seconds": record["cpu seconds"]})
        return ok

    for _ in range(4):
        if is_stable(stable):
            break
        stable, unstable = stable / 2, stable
    for _ in range(4):
        if not is_stable(unstable):
            break
        stable, unstable = unstable, 2 * unstable
    for _ in range(bisections):
        middle = 0.5 * (stable + unstable)
        if is_stable(middle):
            stable = middle
        else:
            unstable = middle
    return trials


def cube_stability(study, bisections):
    horizon = CUBE_STABILITY["horizon"]

    def make_run(dt):
        run = cube_newmark(f"stability_newmark_dt{dt:.6g}", dt, horizon)
        run.settings["Output/History interval"] = "1"
        return run

    return stability_search(study, make_run, CUBE_STABILITY["stable"],
                            CUBE_STABILITY["unstable"], bisections)


def argon_stability(study, bisections):
    def make_run(fs):
        run = argon_newmark(f"stability_verlet_{fs:.6g}fs", fs, ARGON_STABILITY["horizon"])
        run.settings["Output/History interval"] = "0.46305"
        run.settings["Postprocessors/List"] = "history"
        return run

    return stability_search(study, make_run, ARGON_STABILITY["stable"],
                            ARGON_STABILITY["unstable"], bisections)


# ---------------------------------------------------------------------------------------------
# Output.

def formatted(key, value):
    if value == "" or isinstance(value, str):
        return value
    if key in ("steps", "gradient_evaluations", "energy_evaluations", "enclosures",
               "all_evaluations", "jacobian_setups", "newton_iterations"):
        return f"{value:,}"
    if key in ("wall_seconds", "cpu_seconds"):
        return f"{value:.0f}" if value >= 100 else f"{value:.3g}"
    if key in ("mean_step", "max_step"):
        return f"{value:.3g}"
    return f"{value:.2e}"


def write_table(rows, path_stem, columns):
    present = [(key, heading) for key, heading in columns
               if any(row.get(key, "") != "" for row in rows)]
    with open(path_stem + ".csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=[key for key, _ in columns])
        writer.writeheader()
        for row in rows:
            writer.writerow({key: (repr(row[key]) if isinstance(row[key], float) else row[key])
                             for key, _ in columns})
    with open(path_stem + ".md", "w") as f:
        f.write("| " + " | ".join(heading for _, heading in present) + " |\n")
        f.write("|" + "---|" * len(present) + "\n")
        for row in rows:
            f.write("| " + " | ".join(formatted(key, row[key]).replace("|", "\\|")
                                      for key, _ in present) + " |\n")


def write_stability(trials, path, unit):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=["dt", "status", "final_time", "energy_error",
                                               "stable", "cpu_seconds"])
        writer.writeheader()
        writer.writerows(trials)
    stable = [t["dt"] for t in trials if t["stable"]]
    unstable = [t["dt"] for t in trials if not t["stable"]]
    low = max(stable) if stable else float("nan")
    high = min(unstable) if unstable else float("nan")
    return (f"largest stable Newmark step in [{low:.5g}, {high:.5g}]{unit} "
            f"({len(trials)} trials: " + ", ".join(
                f"{t['dt']:.5g} {'stable' if t['stable'] else 'unstable'}" for t in trials) + ")")


def plot(rows, path, title, floor=None):
    """Error against wall seconds, gradient evaluations and process CPU seconds, one series per
    method (points in the order of their setting); failed or unstable runs are left out."""
    figure, axes = plt.subplots(1, 3, figsize=(18, 5.6))
    for method in METHODS:
        selected = sorted((r for r in rows if r["method"] == method and r["error"] != ""
                           and r["status"] == "completed" and r["error"] > 0),
                          key=lambda r: r["value"])
        if not selected:
            continue
        for axis, key in zip(axes, ("wall_seconds", "gradient_evaluations", "cpu_seconds")):
            axis.loglog([r[key] for r in selected], [r["error"] for r in selected],
                        marker=MARKERS[method], color=COLOURS[method],
                        label=method if key == "wall_seconds" else None)
        if method == "energy stepping":
            axes[1].loglog([r["all_evaluations"] for r in selected],
                           [r["error"] for r in selected], marker=MARKERS[method],
                           color=COLOURS[method], markerfacecolor="none", linestyle=":",
                           label="energy stepping: gradient + energy evaluations + enclosures")
        # The settings: explicit methods on the wall-time panel, implicit ones on the next.
        axis = axes[0] if METHODS.index(method) < 2 else axes[1]
        key = "wall_seconds" if METHODS.index(method) < 2 else "gradient_evaluations"
        for r in selected:
            axis.annotate(r["setting"], (r[key], r["error"]), fontsize=6,
                          textcoords="offset points", xytext=(4, 2))
    if floor is not None:
        for axis in axes:
            axis.axhline(floor[0], color="gray", linestyle="--", linewidth=0.8,
                         label=floor[1] if axis is axes[0] else None)
    axes[0].set_xlabel("wall seconds of the time loop (shared machine: upper bounds)")
    axes[1].set_xlabel("gradient evaluations (implicit methods: residual evaluations)")
    axes[2].set_xlabel("CPU seconds of the whole estep process (set-up included)")
    for axis in axes:
        axis.set_ylabel("error")
        axis.grid(True, which="both", linewidth=0.3)
    handles = [h for axis in axes for h in axis.get_legend_handles_labels()[0]]
    labels = [label for axis in axes for label in axis.get_legend_handles_labels()[1]]
    figure.legend(handles, labels, loc="lower center", ncol=4, fontsize=8)
    figure.suptitle(title)
    figure.tight_layout(rect=(0, 0.1, 1, 1))
    figure.savefig(path, dpi=110)
    plt.close(figure)


# ---------------------------------------------------------------------------------------------

def study_problem(problem, arguments, pool, study):
    """Submit the runs of one problem; return a function that waits and writes the output."""
    methods = set(arguments.methods.split(","))
    if problem == "cube":
        reference, runs = cube_runs(arguments.cube_end_time, methods)
        search = cube_stability
    else:
        reference, runs = argon_runs(arguments.argon_end_time, methods)
        search = argon_stability
    # The longest runs first: the reference, the implicit ones, then the rest.
    order = sorted(runs, key=lambda r: METHODS.index(r.method) < 2)
    futures = {run.name: pool.submit(study.execute, run) for run in [reference] + order}
    stability = (pool.submit(search, study, arguments.bisections)
                 if "explicit newmark" in methods and arguments.bisections >= 0 else None)

    def finish():
        output = os.path.join(arguments.output, problem)
        reference_result = futures[reference.name].result()
        if reference_result[0] is None or reference_result[0]["status"] != "completed":
            print(f"{problem}: the reference run did not complete; no errors")
        rows = [evaluate(problem, run, *futures[run.name].result(), reference_result[:2])
                for run in runs]
        rows.append(evaluate(problem, reference, *reference_result, reference_result[:2]))
        rows[-1]["method"] = "explicit newmark (reference)"
        rows[-1]["error"] = rows[-1]["final_error"] = ""
        stem = os.path.join(output, f"accuracy_per_cost_{problem}")
        write_table(rows, stem, COLUMNS)
        floor = None
        if problem == "cube":
            title = (f"spinning cube to t = {arguments.cube_end_time:g}: largest distance of "
                     f"the tracked point from Newmark dt = 1e-4")
        else:
            title = (f"argon cluster over {arguments.argon_end_time * TAU_FS / 1e6:g} ns: "
                     "relative H1 error against velocity Verlet, dt = 10 fs")
            finer = [r for r in rows if r["run"] == "verlet_5fs" and r["error"] != ""]
            if finer:
                floor = (finer[0]["error"], "the reference's own error (Verlet 5 fs)")
        plot(rows, stem + ".png", title, floor)
        lines = [f"{problem}: {stem}.csv, .md, .png"]
        if stability is not None:
            unit = "" if problem == "cube" else " fs"
            lines.append(write_stability(stability.result(),
                                         os.path.join(output, f"stability_{problem}.csv"),
                                         unit))
        total = [r["cpu_seconds"] for r in rows]
        if stability is not None:
            total += [t["cpu_seconds"] for t in stability.result()]
        lines.append(f"process CPU seconds of all its runs: {sum(total):.0f}")
        with open(stem + ".md") as f:
            print(f.read(), end="")
        print("\n".join(lines), flush=True)
        with open(stem + ".md", "a") as f:
            f.write("\n" + "\n".join(lines[1:]) + "\n")
        return rows

    return finish


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--problem", choices=["cube", "argon", "both"], default="both")
    parser.add_argument("--estep", default=os.environ.get(
        "ESTEP", os.path.join(SOURCE_DIR, "build", "bin", "estep")),
        help="the estep executable (default: $ESTEP, else build/bin/estep)")
    parser.add_argument("--output", default=os.path.join("output", "accuracy_per_cost"))
    parser.add_argument("--jobs", type=int, default=2, help="runs at a time (default 2)")
    parser.add_argument("--nice", type=int, default=5,
                        help="run estep under nice -n N (default 5; 0: not)")
    parser.add_argument("--methods", default=",".join(METHODS),
                        help="comma-separated methods to run (default: all)")
    parser.add_argument("--cube-end-time", type=float, default=CUBE_END_TIME)
    parser.add_argument("--argon-end-time", type=float, default=ONE_NS,
                        help="in tau (default 463.05 = 1 ns)")
    parser.add_argument("--bisections", type=int, default=5,
                        help="bisections of the Newmark stability search (-1: no search)")
    arguments = parser.parse_args()
    if not os.access(arguments.estep, os.X_OK):
        print(f"error: no estep executable at {arguments.estep} (use --estep or $ESTEP)")
        return 1
    unknown = set(arguments.methods.split(",")) - set(METHODS)
    if unknown:
        print(f"error: unknown methods {sorted(unknown)}; known: {', '.join(METHODS)}")
        return 1
    arguments.output = os.path.abspath(arguments.output)
    problems = ["cube", "argon"] if arguments.problem == "both" else [arguments.problem]
    # The pool only holds the tasks; Study's semaphore limits the estep processes to --jobs.
    with concurrent.futures.ThreadPoolExecutor(64) as pool:
        study = {p: Study(arguments.estep, os.path.join(arguments.output, p), arguments.nice,
                          arguments.jobs) for p in problems}
        shared = threading.Semaphore(arguments.jobs)
        for s in study.values():
            s.slots = shared
        finishers = [study_problem(p, arguments, pool, study[p]) for p in problems]
        for finish in finishers:
            finish()
    return 0


if __name__ == "__main__":
    sys.exit(main())
