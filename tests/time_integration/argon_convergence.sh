#!/usr/bin/env bash
# The argon convergence study (figure 2.8 of the reference text): fitted slopes of the relative
# H1 error, the mean step and the maximum step against the energy step, with the reference
# text's 1/2, 1 and 1/2.
set -eu
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$ESTEP_SOURCE_DIR/scripts/argon_convergence.py" --estep "$ESTEP" --output "$work"
test -s "$work/convergence.csv"
test -s "$work/convergence.png"
test -s "$work/trajectories.png"
/usr/bin/python3 - "$work/slopes.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
# The H1 error compares chaotic trajectories (doc/argon_cluster.md): its fitted slope moves with
# round-off-level changes of the integrator (0.58, 0.646, 0.661 measured), hence the wider window.
checks = [("H1 error", s["h1_error"], 0.35, 0.8), ("mean step", s["mean_step_fs"], 0.85, 1.15),
          ("maximum step", s["max_step_fs"], 0.35, 0.65)]
bad = [f"{name} slope {value:.3f} outside [{lo}, {hi}]" for name, value, lo, hi in checks
       if not lo <= value <= hi]
print("\n".join(bad) or "slopes within the bounds")
sys.exit(1 if bad else 0)
PY
