#!/usr/bin/env bash
# All runs of the spinning-cube figures 2.11-2.14 of the reference text: energy-stepping with
# h = 1e-5 (t to 80), 3e-5 and 6e-5 (t to 250), and explicit Newmark with dt = 0.0082, 0.0204, 0.0381 and the
# converged 1e-4. Writes output/spinning_cube*/ and prints each run's wall time; then
# scripts/spinning_cube_figures.py draws the figures. The converged Newmark run takes several
# minutes; the others take seconds to a minute each (Release, one core).
#
# Usage: scripts/spinning_cube_runs.sh [path/to/estep]
set -euo pipefail
source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
estep=${1:-$source_dir/build/bin/estep}
cd "$source_dir"
for run in spinning_cube spinning_cube_h3e-5 spinning_cube_h6e-5 spinning_cube_newmark_0.0082 \
           spinning_cube_newmark_0.0204 spinning_cube_newmark_0.0381 \
           spinning_cube_newmark_converged; do
  # Newmark at dt = 0.0381 ends unstable on purpose (exit code 2).
  "$estep" "parameter_files/$run.prm" -s "Postprocessors/List=history, step histogram" || [[ $? == 2 ]]
done
