#!/usr/bin/python3
"""How the spinning cube's energy-stepping run depends on where its terraces lie.

The levels of energy-stepping lie at (k + c) h; the offset c in [0, 1) is the additive constant
of V that the method leaves free (`Time integration/Energy stepping/Terrace offset`). This study
runs the spinning cube (parameter_files/spinning_cube.prm, the seed's 12,288 tetrahedra) at
h = 1e-5, 2e-5, 3e-5 and 6e-5 for 20 offsets c = 0, 0.05, ..., 0.95, to t = 20 and to t = 250,
and, to separate the two candidate causes of the reference text's mean steps, the same with the
reference text's sampled crossing search (`Crossing search = sampled`, 8 samples per window,
audited by the certified search) at a few offsets of h = 3e-5 and 6e-5.

It writes, in the output directory:
- terrace_offset_study.csv: one row per run (h, c, end time, search, steps, mean step, climbs,
  descents, reflections, reflection share, crossings stepped over, wall seconds, status);
- terrace_offset_mean_step.png: the mean step against c, one panel per end time, a curve per h,
  with the reference text's mean steps (0.0082, 0.0204, 0.0381 for h = 1e-5, 3e-5, 6e-5) marked;
- terrace_offset_events.png: climbs, descents and reflections against c, one panel per h and
  end time.

Runs go into <output>/runs/<name>/ and are reused when their summary.json says completed, so an
interrupted study picks up where it stopped. Two runs go at a time (--jobs).

Usage: scripts/terrace_offset_study.py [--estep PATH] [--output DIR] [--jobs N]
                                       [--end-times 20,250] [--offsets 20]
"""
import argparse
import concurrent.futures
import csv
import json
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENERGY_STEPS = [1e-5, 2e-5, 3e-5, 6e-5]
# The reference text's mean steps (spec: method.md, the spinning cube).
REFERENCE_MEAN_STEP = {1e-5: 0.0082, 3e-5: 0.0204, 6e-5: 0.0381}
SAMPLED_STEPS = [3e-5, 6e-5]
SAMPLED_OFFSETS = [0.0, 0.25, 0.5, 0.75]


def run_one(estep, output, h, c, end_time, search):
    name = f"h{h:g}_c{c:.2f}_t{end_time:g}_{search}"
    directory = os.path.join(output, "runs", name)
    summary_file = os.path.join(directory, "summary.json")
    if os.path.exists(summary_file):
        with open(summary_file) as f:
            summary = json.load(f)
        if summary.get("status") == "completed":
            return h, c, end_time, search, summary
    settings = {
        "Output directory": directory,
        "Time integration/End time": f"{end_time:g}",
        "Time integration/Energy stepping/Energy step": f"{h:g}",
        "Time integration/Energy stepping/Terrace offset": f"{c:.4f}",
        "Time integration/Energy stepping/Crossing search": search,
        "Time integration/Energy stepping/Audit sampled search":
            "true" if search == "sampled" else "false",
        "Output/History interval": "1",
        "Postprocessors/List": "history, step histogram",
    }
    command = [estep, os.path.join(SOURCE_DIR, "parameter_files", "spinning_cube.prm")]
    for key, value in settings.items():
        command += ["--set", f"{key}={value}"]
    subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    with open(summary_file) as f:
        return h, c, end_time, search, json.load(f)


def row(h, c, end_time, search, summary):
    counts = summary["counters"]
    jumps = counts["climbs"] + counts["descents"] + counts["reflections"]
    return {
        "h": h, "offset": c, "end_time": end_time, "search": search,
        "status": summary["status"], "steps": counts["steps"],
        "mean_step": summary["mean step"], "climbs": counts["climbs"],
        "descents": counts["descents"], "reflections": counts["reflections"],
        "reflection_share": counts["reflections"] / jumps if jumps else 0.,
        "stepped_over": counts.get("crossings stepped over (audit)", ""),
        "wall_seconds": summary["wall seconds"],
    }


def plot(rows, end_times, output):
    figure, axes = plt.subplots(1, len(end_times), figsize=(6 * len(end_times), 4.5),
                                squeeze=False)
    colours = dict(zip(ENERGY_STEPS, ["C0", "C1", "C2", "C3"]))
    for panel, end_time in zip(axes[0], end_times):
        for h in ENERGY_STEPS:
            for search, marker, style in [("certified", "o", "-"), ("sampled", "x", "none")]:
                points = sorted((r["offset"], r["mean_step"]) for r in rows
                                if r["h"] == h and r["end_time"] == end_time
                                and r["search"] == search)
                if points:
                    panel.plot(*zip(*points), marker=marker, linestyle=style,
                               color=colours[h],
                               label=f"h = {h:g}" + (" sampled" if search == "sampled" else ""))
            if h in REFERENCE_MEAN_STEP:
                panel.axhline(REFERENCE_MEAN_STEP[h], color=colours[h], linestyle="--",
                              linewidth=0.8)
        panel.set_title(f"spinning cube to t = {end_time:g} (dashed: the reference text)")
        panel.set_xlabel("terrace offset c (levels at (k + c) h)")
        panel.set_ylabel("mean time step")
        panel.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(os.path.join(output, "terrace_offset_mean_step.png"), dpi=110)

    figure, axes = plt.subplots(len(end_times), len(ENERGY_STEPS),
                                figsize=(4 * len(ENERGY_STEPS), 3.2 * len(end_times)),
                                squeeze=False)
    for i, end_time in enumerate(end_times):
        for j, h in enumerate(ENERGY_STEPS):
            panel = axes[i][j]
            selected = sorted((r for r in rows if r["h"] == h and r["end_time"] == end_time
                               and r["search"] == "certified"), key=lambda r: r["offset"])
            for key in ["climbs", "descents", "reflections"]:
                panel.plot([r["offset"] for r in selected], [r[key] for r in selected],
                           marker=".", label=key)
            panel.set_title(f"h = {h:g}, t = {end_time:g}", fontsize=9)
            panel.set_xlabel("terrace offset c")
            panel.set_yscale("symlog", linthresh=10)
            panel.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(os.path.join(output, "terrace_offset_events.png"), dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--estep", default=os.path.join(SOURCE_DIR, "build", "bin", "estep"))
    parser.add_argument("--output", default="output/terrace_offset_study")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--end-times", default="20,250")
    parser.add_argument("--offsets", type=int, default=20)
    arguments = parser.parse_args()
    end_times = [float(t) for t in arguments.end_times.split(",")]
    offsets = [k / arguments.offsets for k in range(arguments.offsets)]
    os.makedirs(arguments.output, exist_ok=True)

    tasks = [(h, c, t, "certified") for t in end_times for h in ENERGY_STEPS for c in offsets]
    tasks += [(h, c, t, "sampled") for t in end_times for h in SAMPLED_STEPS
              for c in SAMPLED_OFFSETS]
    rows = []
    with concurrent.futures.ThreadPoolExecutor(arguments.jobs) as pool:
        futures = [pool.submit(run_one, arguments.estep, arguments.output, *task)
                   for task in tasks]
        for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
            r = row(*future.result())
            rows.append(r)
            print(f"[{done}/{len(tasks)}] h = {r['h']:g}, c = {r['offset']:.2f}, "
                  f"t = {r['end_time']:g}, {r['search']}: mean step {r['mean_step']:.4g} "
                  f"({r['climbs']}/{r['descents']}/{r['reflections']}), {r['status']}",
                  flush=True)
    rows.sort(key=lambda r: (r["search"], r["end_time"], r["h"], r["offset"]))
    with open(os.path.join(arguments.output, "terrace_offset_study.csv"), "w",
              newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    plot(rows, end_times, arguments.output)
    failed = [r for r in rows if r["status"] != "completed"]
    print(f"{len(rows)} runs, {len(failed)} not completed; tables and plots in "
          f"{arguments.output}/")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
