#!/usr/bin/env bash
# scripts/spinning_cube_comparison.py to a short end time: the table has one row per method (and
# the reference) with finite numbers, energy-stepping conserves its terraced energy, the plots
# are written; then, with --reuse, only the run without a summary is run again, and that run,
# made to fail (one Newton iteration at an unreachable tolerance, through a wrapper of estep),
# shows in the table as unstable without stopping the script.
# Environment (set by ctest): ESTEP, the estep executable; ESTEP_SOURCE_DIR, the source tree.
set -u
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
script=$ESTEP_SOURCE_DIR/scripts/spinning_cube_comparison.py
out=$work/comparison
failures=0

fail() {
  echo "FAILED: $*"
  failures=$((failures + 1))
}

# check_table [UNSTABLE_RUN...]: the CSV has a row for every run, in order; the named runs are
# unstable; every other row is completed, with finite numbers and an angular momentum drift at
# the end below 1e-6; energy-stepping's terraced energy drift is below 1e-10.
check_table() {
  /usr/bin/python3 - "$out/comparison.csv" "$@" <<'PY'
import csv, math, sys
path, unstable = sys.argv[1], sys.argv[2:]
expected = ["energy_stepping", "newmark_0.0082", "newmark_0.0204", "ida_bdf", "arkode_midpoint",
            "arkode_irk", "energy_momentum", "newmark_converged"]
numbers = ["steps", "mean_step", "energy_drift", "true_energy_drift", "end_energy_drift",
           "lz_drift", "end_lz_drift", "point_error", "wall_seconds"]
rows = list(csv.DictReader(open(path)))
bad = []


def number(row, key):
    try:
        return float(row[key])
    except ValueError:
        return math.nan


if [r["run"] for r in rows] != expected:
    bad.append(f"runs {[r['run'] for r in rows]}, expected {expected}")
for row in rows:
    if row["run"] in unstable:
        if not row["status"].startswith("unstable"):
            bad.append(f"{row['run']}: status {row['status']}, expected unstable")
        continue
    for key in numbers:
        if not math.isfinite(number(row, key)):
            bad.append(f"{row['run']}: {key} = '{row[key]}' is not a finite number")
    if row["status"] != "completed":
        bad.append(f"{row['run']}: status {row['status']}")
    if not number(row, "end_lz_drift") < 1e-6:
        bad.append(f"{row['run']}: Lz drift at the end {row['end_lz_drift']} >= 1e-6")
es = rows[0]
if not number(es, "energy_drift") < 1e-10:
    bad.append(f"energy stepping: terraced energy drift {es['energy_drift']} >= 1e-10")
for line in bad:
    print(line)
sys.exit(1 if bad else 0)
PY
}

# A full comparison to t = 0.2.
if ! /usr/bin/python3 "$script" --estep "$ESTEP" --end-time 0.2 --output "$out" > "$work/log1.txt" 2>&1; then
  fail "the comparison script failed: $(tail -20 "$work/log1.txt")"
fi
check_table || fail "the table of the first pass"
for file in comparison.md energy.png tracked_point_error.png; do
  [[ -s $out/$file ]] || fail "no $file"
done
[[ $(grep -c '^| ' "$out/comparison.md") == 9 ]] || fail "comparison.md has not 1 + 8 rows"
grep -q "^| energy_stepping | energy stepping | h = 1e-5 " "$out/comparison.md" ||
  fail "comparison.md lacks the energy-stepping row"

# Again with --reuse: everything is reused except the midpoint run, whose summary is gone and
# whose first Newton solve the wrapper makes fail (status unstable, exit code 2).
cat > "$work/unstable_estep" <<EOF
#!/usr/bin/env bash
exec "$ESTEP" "\$@" -s "Time integration/Implicit integrators/Maximum Newton iterations=1" \\
  -s "Time integration/Implicit integrators/Newton tolerance=1e-15"
EOF
chmod +x "$work/unstable_estep"
rm -f "$out/arkode_midpoint/summary.json"
if ! /usr/bin/python3 "$script" --estep "$work/unstable_estep" --end-time 0.2 --output "$out" --reuse \
  > "$work/log2.txt" 2>&1; then
  fail "the comparison script with an unstable run failed: $(tail -20 "$work/log2.txt")"
fi
[[ $(grep -c ": reused$" "$work/log2.txt") == 7 ]] || fail "--reuse did not reuse 7 runs: $(cat "$work/log2.txt")"
grep -q "^arkode_midpoint: exit code 2" "$work/log2.txt" || fail "the unstable run did not exit with 2"
check_table arkode_midpoint || fail "the table of the second pass"

if ((failures)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "spinning cube comparison: table, plots, reuse and an unstable run as expected"
