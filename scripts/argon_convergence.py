#!/usr/bin/python3
"""Convergence study of energy-stepping on the frozen argon cluster (figure 2.8 of the reference text).

Runs velocity Verlet with dt = 10 fs as the reference and energy-stepping with energy steps
spanning three decades in units of |E0|, all over T = 1 ns, and reports for each energy step
the relative H1 error | ||q_h|| - ||q|| | / ||q|| (H1 norms of the trajectories in time), the
mean and the maximum time step. Writes convergence.csv, convergence.png (log-log with fitted slopes),
trajectories.png (figure 2.7 of the reference text: the atoms' paths over the last 50 ps) and
slopes.json to the output directory.

Usage: scripts/argon_convergence.py [--estep build/bin/estep] [--output output/argon_convergence]
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

E0 = 10.51925          # |E0| in epsilon
TAU_FS = 2159.6        # the time unit tau in fs
ONE_NS = 463.05        # 1 ns in tau


def run_estep(estep, parameter_file, directory, settings):
    command = [estep, parameter_file, "--set", "Output directory=" + directory,
               "--set", "Postprocessors/List=history, step histogram, h1 norm"]
    for key, value in settings.items():
        command += ["--set", f"{key}={value}"]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(directory, "summary.json")) as f:
        return json.load(f)


def fitted_slope(x, y):
    lx = [math.log10(v) for v in x]
    ly = [math.log10(v) for v in y]
    n = len(lx)
    mx, my = sum(lx) / n, sum(ly) / n
    sxx = sum((a - mx) ** 2 for a in lx)
    sxy = sum((a - mx) * (b - my) for a, b in zip(lx, ly))
    slope = sxy / sxx
    return slope, my - slope * mx


def read_history(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    source = os.path.dirname(here)
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--estep", default=os.path.join(source, "build", "bin", "estep"))
    parser.add_argument("--output", default=os.path.join("output", "argon_convergence"))
    parser.add_argument("--steps", default="1e-4,2e-4,5e-4,1e-3,2e-3,5e-3,1e-2,2e-2,5e-2,1e-1",
                        help="energy steps in units of |E0|, comma separated")
    parser.add_argument("--no-plots", action="store_true")
    args = parser.parse_args()

    os.makedirs(args.output, exist_ok=True)
    parameters = os.path.join(source, "parameter_files")
    end = {"Time integration/End time": ONE_NS, "Output/History interval": 0.046305}

    reference = run_estep(args.estep, os.path.join(parameters, "argon_cluster_verlet.prm"),
                          os.path.join(args.output, "verlet"), end)
    norm_ref = reference["h1 norm"]
    # The floor of the study: the reference's own H1 error, estimated against Verlet at 5 fs.
    finer = run_estep(args.estep, os.path.join(parameters, "argon_cluster_verlet.prm"),
                      os.path.join(args.output, "verlet_5fs"),
                      dict(end, **{"Time integration/Explicit Newmark/Time step": 0.5 * 4.6305e-3}))
    reference_error = abs(finer["h1 norm"] - norm_ref) / finer["h1 norm"]
    print(f"reference: velocity Verlet, dt = 10 fs: H1 norm {norm_ref:.10g}; "
          f"its own relative H1 error against dt = 5 fs: {reference_error:.3e}", flush=True)

    rows = []
    for text in args.steps.split(","):
        h_rel = float(text)
        directory = os.path.join(args.output, f"energy_stepping_{text}")
        settings = dict(end)
        settings["Time integration/Energy stepping/Energy step"] = repr(h_rel * E0)
        summary = run_estep(args.estep, os.path.join(parameters, "argon_cluster.prm"),
                            directory, settings)
        rows.append({
            "energy_step_over_E0": h_rel,
            "h1_error": abs(summary["h1 norm"] - norm_ref) / norm_ref,
            "mean_step_fs": summary["mean step"] * TAU_FS,
            "max_step_fs": summary["max step"] * TAU_FS,
            "min_step_fs": summary["min step"] * TAU_FS,
            "steps": summary["counters"]["steps"],
            "terraced_energy_drift": summary["energies"]["terraced energy drift"],
            "wall_seconds": summary["wall seconds"],
        })
        print(f"h = {h_rel:8.1e} |E0|: H1 error {rows[-1]['h1_error']:.3e}, "
              f"mean step {rows[-1]['mean_step_fs']:.4g} fs, "
              f"max step {rows[-1]['max_step_fs']:.4g} fs, {rows[-1]['steps']} steps",
              flush=True)

    with open(os.path.join(args.output, "convergence.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)

    h = [r["energy_step_over_E0"] for r in rows]
    slopes = {}
    fits = {}
    for key in ("h1_error", "mean_step_fs", "max_step_fs"):
        slopes[key], fits[key] = fitted_slope(h, [r[key] for r in rows])
    slopes["reference_h1_norm"] = norm_ref
    slopes["reference_h1_error"] = reference_error
    with open(os.path.join(args.output, "slopes.json"), "w") as f:
        json.dump(slopes, f, indent=2)
    print(f"fitted slopes: H1 error {slopes['h1_error']:.3f} (reference text 1/2), "
          f"mean step {slopes['mean_step_fs']:.3f} (reference text 1), "
          f"max step {slopes['max_step_fs']:.3f} (reference text 1/2)")

    if args.no_plots:
        return 0
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    hh = [min(h), max(h)]
    left.loglog(h, [r["h1_error"] for r in rows], "o", label="energy-stepping")
    left.loglog(hh, [10 ** fits["h1_error"] * x ** slopes["h1_error"] for x in hh], "-",
                label=f"fit: slope {slopes['h1_error']:.2f}")
    left.axhline(reference_error, color="gray", ls=":", label="reference's own error")
    left.set_xlabel("energy step [|E0|]")
    left.set_ylabel("relative H1 error")
    left.set_title("H1 error against velocity Verlet, dt = 10 fs, T = 1 ns")
    left.legend()
    right.loglog(h, [r["mean_step_fs"] for r in rows], "*", label="mean step")
    right.loglog(h, [r["max_step_fs"] for r in rows], "o", label="maximum step")
    for key, name in (("mean_step_fs", "mean"), ("max_step_fs", "max")):
        right.loglog(hh, [10 ** fits[key] * x ** slopes[key] for x in hh], "-",
                     label=f"{name} fit: slope {slopes[key]:.2f}")
    right.set_xlabel("energy step [|E0|]")
    right.set_ylabel("time step [fs]")
    right.set_title("time steps selected")
    right.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.output, "convergence.png"), dpi=120)

    # Figure 2.7: paths of the seven atoms over the last 50 ps.
    runs = [("velocity Verlet, dt = 10 fs", os.path.join(args.output, "verlet"))]
    for text in (args.steps.split(",")[len(rows) // 2], args.steps.split(",")[-1]):
        runs.append((f"energy-stepping, h = {float(text):g} |E0|",
                     os.path.join(args.output, f"energy_stepping_{text}")))
    fig, axes = plt.subplots(1, len(runs), figsize=(5 * len(runs), 4.8))
    sigma_nm = 0.341
    for axis, (title, directory) in zip(axes, runs):
        history = read_history(os.path.join(directory, "history.csv"))
        start = ONE_NS - 50e3 / TAU_FS
        history = [r for r in history if float(r["time"]) >= start]
        for atom in range(7):
            axis.plot([float(r[f"x{atom + 1}"]) * sigma_nm for r in history],
                      [float(r[f"y{atom + 1}"]) * sigma_nm for r in history], lw=0.5)
        axis.set_aspect("equal")
        axis.set_title(title, fontsize=10)
        axis.set_xlabel("x [nm]")
        axis.set_ylabel("y [nm]")
    fig.suptitle("frozen argon cluster: atom paths over the last 50 ps of 1 ns")
    fig.tight_layout()
    fig.savefig(os.path.join(args.output, "trajectories.png"), dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
