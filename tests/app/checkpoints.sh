#!/usr/bin/env bash
# Checkpoints and --resume: a run killed at any instant (SIGKILL) and resumed ends exactly as
# the uninterrupted run, for energy-stepping with and without contact (with field output in vtu
# and in HDF5, whose files and series equal those of the uninterrupted run), Newmark and the
# energy-momentum method; the SUNDIALS methods resume from the checkpoint's exact state and
# agree within their tolerance; SIGTERM leaves a final checkpoint; a damaged checkpoint,
# changed parameters or a changed mesh file are refused in one line; a resume that fails
# leaves the output directory's summary and parameters as they were.
# Environment (set by ctest): ESTEP, the estep executable; ESTEP_SOURCE_DIR, the source tree.
set -u
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
files=$ESTEP_SOURCE_DIR/parameter_files

fail() {
  echo "FAILED: $*"
  failures=$((failures + 1))
}

# same_run REFERENCE DIRECTORY WHAT: the outputs of two runs of the same parameters agree bit for
# bit (the checkpoint holds the final state: positions, velocities, counters; the summaries
# differ only in wall time and memory).
same_run() {
  local f
  for f in history.csv checkpoint.bin step_histogram.csv; do
    cmp -s "$1/$f" "$2/$f" || fail "$3: $f differs from the uninterrupted run"
  done
  if [[ -d $1/fields ]]; then
    diff -rq "$1/fields" "$2/fields" > /dev/null || fail "$3: the field snapshots differ"
  fi
  for f in solution.pvd solution.xdmf; do
    [[ ! -f $1/$f ]] || cmp -s "$1/$f" "$2/$f" || fail "$3: $f differs from the uninterrupted run"
  done
  local skip="wall|memory|resumed from time"
  diff -q <(grep -Ev "$skip" "$1/summary.json") <(grep -Ev "$skip" "$2/summary.json") \
    > /dev/null || fail "$3: summary.json differs: $(diff <(grep -Ev "$skip" "$1/summary.json") <(grep -Ev "$skip" "$2/summary.json") | head -4)"
}

# kill_after_checkpoint SECONDS ARGS...: start a run, kill it (SIGKILL) SECONDS after its first
# checkpoint appears (or when it ends); the caller resumes it.
kill_after_checkpoint() {
  local delay=$1
  shift
  "$ESTEP" "$@" > /dev/null 2>&1 &
  local pid=$!
  while kill -0 $pid 2> /dev/null && [[ ! -f run/checkpoint.bin ]]; do sleep 0.02; done
  sleep "$delay"
  kill -9 $pid 2> /dev/null
  wait $pid 2> /dev/null
}

# kill_during_run SECONDS ARGS...: kill_after_checkpoint in a fresh run/, and if the run ended
# before the kill (a machine faster than the reference run's), again with a third of the delay,
# up to three times; the delay of the last attempt is left in $delay_used.
kill_during_run() {
  delay_used=$1
  shift
  local attempt
  for attempt in 1 2 3; do
    rm -rf run
    kill_after_checkpoint "$delay_used" "$@"
    grep -q '"status": "running"' run/summary.json && return
    delay_used=$(awk -v d="$delay_used" 'BEGIN { printf "%.3f", d / 3 }')
  done
}

# The cube by energy-stepping with every postprocessor that keeps state, killed at 20 random
# instants of its run.
cube=("$files/quick_start.prm" --set "Output directory=run" --set "Time integration/End time=2"
      --set "Output/Checkpoint interval=0.25"
      --set "Postprocessors/List=history, step histogram, progress, field output, h1 norm"
      --set "Postprocessors/Field output/Interval=0.5")
# The instants are drawn between the first checkpoint and the end, as the uninterrupted run
# measures them, and counted from the first checkpoint of each run (the start-up before it,
# reading and meshing, takes a good part of so short a run and varies with the machine's
# load; kill_during_run retries a kill that came after the end).
"$ESTEP" "${cube[@]}" > /dev/null &
pid=$!
while kill -0 $pid 2> /dev/null && [[ ! -f run/checkpoint.bin ]]; do sleep 0.01; done
first=$(date +%s.%N)
wait $pid || fail "the uninterrupted cube run"
remaining=$(echo "$(date +%s.%N) - $first" | bc)
mv run cube_reference
resumed_mid_run=0
for k in $(seq 1 20); do
  kill_during_run "$(awk -v seed="$k" -v d="$remaining" 'BEGIN { srand(seed); printf "%.3f", rand() * d }')" "${cube[@]}"
  "$ESTEP" "${cube[@]}" --resume > resume.txt 2>&1 || fail "resume $k (killed $delay_used s after the first checkpoint): $(tail -2 resume.txt)"
  grep -q "resuming from" resume.txt && resumed_mid_run=$((resumed_mid_run + 1))
  same_run cube_reference run "cube, killed $delay_used s after the first checkpoint"
done
echo "cube: 20 kills up to $remaining s after the first checkpoint, $resumed_mid_run resumed from a checkpoint"
((resumed_mid_run >= 10)) || fail "only $resumed_mid_run of 20 kills left a checkpoint to resume from"

# SIGTERM: the run stops with a final checkpoint and status interrupted (143), and resumes.
rm -rf run
"$ESTEP" "${cube[@]}" > /dev/null 2>&1 &
pid=$!
while kill -0 $pid 2> /dev/null && [[ ! -f run/checkpoint.bin ]]; do sleep 0.02; done
kill -TERM $pid
wait $pid
rc=$?
[[ $rc == 143 ]] || fail "SIGTERM: exit code $rc, expected 143"
grep -q '"status": "interrupted"' run/summary.json || fail "SIGTERM: summary.json does not say interrupted"
"$ESTEP" "${cube[@]}" --resume > resume.txt 2>&1 || fail "resume after SIGTERM"
same_run cube_reference run "cube, SIGTERM"
# The summary names the time the run resumed from (its wall seconds are those since then); a run
# from the start names none.
resumed_at=$(sed -n 's/.*resuming from .* at t = \([^ ]*\) after.*/\1/p' resume.txt)
python3 -c "import json, sys; t = json.load(open('run/summary.json')).get('resumed from time')
sys.exit(t is None or abs(t - $resumed_at) > 1e-5 * abs(t))" ||
  fail "the resumed run's summary does not name t = $resumed_at: $(grep resumed run/summary.json)"
! grep -q "resumed from" cube_reference/summary.json || fail "a run from the start says it resumed"

# Contact (the impenetrable balls, killed during the collision), Newmark and energy-momentum.
# Each is killed halfway (in wall time) between its first checkpoint and its end, as the
# uninterrupted run measures them, so that the kill falls inside the run on a fast machine
# as on a loaded one.
check_exact() {
  local what=$1
  shift
  rm -rf run reference
  "$ESTEP" "$@" > /dev/null &
  local pid=$!
  while kill -0 $pid 2> /dev/null && [[ ! -f run/checkpoint.bin ]]; do sleep 0.01; done
  local first_checkpoint=$(date +%s.%N)
  wait $pid || fail "$what: the uninterrupted run"
  local delay=$(awk -v a="$first_checkpoint" -v b="$(date +%s.%N)" 'BEGIN { print (b - a) / 2 }')
  mv run reference
  kill_during_run "$delay" "$@"
  grep -q '"status": "running"' run/summary.json || fail "$what: the kill came too late to test anything"
  "$ESTEP" "$@" --resume > /dev/null 2>&1 || fail "$what: resume"
  same_run reference run "$what"
}
check_exact "impenetrable balls" "$files/ball_collision_impenetrable.prm" \
  --set "Output directory=run" --set "Time integration/End time=0.2" \
  --set "Output/Checkpoint interval=0.02"
check_exact "penalty balls" "$files/ball_collision.prm" \
  --set "Output directory=run" --set "Time integration/End time=0.12" \
  --set "Output/Checkpoint interval=0.01"
check_exact "hdf5 field output" "$files/quick_start.prm" \
  --set "Output directory=run" --set "Time integration/End time=2" \
  --set "Output/Checkpoint interval=0.25" --set "Postprocessors/Field output/Interval=0.25" \
  --set "Postprocessors/Field output/Format=hdf5"
check_exact "explicit newmark" "$files/spinning_cube_newmark_0.0082.prm" \
  --set "Output directory=run" --set "Time integration/End time=20" \
  --set "Output/Checkpoint interval=1"
check_exact "energy momentum" "$files/spinning_cube_energy_momentum.prm" \
  --set "Output directory=run" --set "Time integration/End time=2" \
  --set "Elastic body/Mesh/Subdivisions=4" --set "Output/Checkpoint interval=0.2"

# ARKode restarts at the checkpoint's state: the rows up to the checkpoint are those of the
# uninterrupted run, the rest agree within the method's accuracy.
arkode=("$files/spinning_cube_arkode_midpoint.prm" --set "Output directory=run"
        --set "Time integration/End time=2" --set "Elastic body/Mesh/Subdivisions=4"
        --set "Output/Checkpoint interval=1" --set "Output/History interval=0.1")
rm -rf run reference
"$ESTEP" "${arkode[@]}" > /dev/null || fail "arkode: the uninterrupted run"
mv run reference
kill_after_checkpoint 0 "${arkode[@]}"
"$ESTEP" "${arkode[@]}" --resume > /dev/null 2>&1 || fail "arkode: resume"
python3 - reference/history.csv run/history.csv <<'PY' || fail "arkode: resumed history"
import csv, sys
a, b = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
assert len(a) == len(b), f"{len(a)} rows against {len(b)}"
for ra, rb in zip(a, b):
    if float(ra["time"]) <= 1.0:
        assert ra == rb, f"row at t = {ra['time']} differs before the checkpoint"
    else:
        d = abs(float(ra["total_energy"]) - float(rb["total_energy"]))
        assert d < 1e-6, f"total energy at t = {ra['time']} off by {d}"
PY

# Without a checkpoint --resume starts over; a completed run continues to a later end time;
# changed parameters and a damaged checkpoint are refused.
rm -rf run
"$ESTEP" "${cube[@]}" --resume > out.txt 2>&1 || fail "--resume without a checkpoint"
grep -q "starts from the beginning" out.txt || fail "--resume without a checkpoint says nothing"
same_run cube_reference run "--resume without a checkpoint"
"$ESTEP" "${cube[@]}" --set "Time integration/End time=2.5" --resume > /dev/null 2>&1 \
  || fail "continuing a completed run"
tail -1 run/history.csv | grep -q "^2.5," || fail "continuing a completed run: no row at t = 2.5"
# A completed run continued to a later end time: its rows follow the old end's, none repeated
# and none lost (the end time 0.3 short of the grid time 3 x 0.1 in floating point, an end
# time between grid times, a history of the start and the end only).
continued_times() {
  local expected=$1 first_end=$2 second_end=$3
  shift 3
  rm -rf short
  local short=("$files/quick_start.prm" --set "Output directory=short" --set "Postprocessors/List=history" "$@")
  "$ESTEP" "${short[@]}" --set "Time integration/End time=$first_end" > /dev/null 2>&1 \
    || fail "the run to t = $first_end"
  "$ESTEP" "${short[@]}" --set "Time integration/End time=$second_end" --resume > /dev/null 2>&1 \
    || fail "continuing the run to t = $first_end"
  local times=$(cut -d, -f1 short/history.csv | tail -n +2 | tr '\n' ' ')
  [[ $times == "$expected " ]] \
    || fail "continuing the run to t = $first_end $*: the times of history.csv are $times, expected $expected"
}
continued_times "0 0.1 0.2 0.3 0.4 0.5 0.6" 0.3 0.6
continued_times "0 0.1 0.2 0.25 0.28" 0.25 0.28
continued_times "0 0.1 0.2 0.25 0.3 0.4" 0.25 0.4
continued_times "0 0.3 0.6" 0.3 0.6 --set "Output/History interval=0"
"$ESTEP" "${cube[@]}" --resume > out.txt 2> err.txt
rc=$?
[[ $rc == 1 ]] || fail "an end time before the checkpoint's: exit code $rc"
grep -q "End time = 2 is before the time of the checkpoint <run/checkpoint.bin>, t = 2.5" err.txt || fail "an end time before the checkpoint's: $(cat err.txt)"
tail -1 run/history.csv | grep -q "^2.5," || fail "a refused resume changed history.csv"
"$ESTEP" "${cube[@]}" --set "Time integration/Energy stepping/Energy step=2e-5" --resume \
  > out.txt 2> err.txt
rc=$?
[[ $rc == 1 ]] || fail "changed parameters: exit code $rc"
grep -q "Energy stepping/Energy step" err.txt || fail "changed parameters: the entry is not named: $(cat err.txt)"
[[ $(wc -l < err.txt) == 1 ]] || fail "changed parameters: not one line: $(cat err.txt)"
# The same values written otherwise are the same parameters (they were compared as text).
"$ESTEP" "${cube[@]}" --set "Time integration/End time=2.5" --set "Time integration/Energy stepping/Energy step=0.000010" \
  --set "Elastic body/Initial velocity/Angular velocity=0,0,1.0" --resume > out.txt 2>&1 ||
  fail "the same parameters written otherwise: $(tail -1 out.txt)"
printf 'x' | dd of=run/checkpoint.bin bs=1 seek=200 conv=notrunc 2> /dev/null
"$ESTEP" "${cube[@]}" --resume > out.txt 2> err.txt
rc=$?
[[ $rc == 1 ]] || fail "damaged checkpoint: exit code $rc"
grep -q "damaged" err.txt || fail "damaged checkpoint: $(cat err.txt)"
# A checkpoint cut short, even to nothing, is damaged (not "of another version").
for size in 0 10; do
  head -c $size run/checkpoint.bin > short.bin
  cp run/checkpoint.bin whole.bin && mv short.bin run/checkpoint.bin
  "$ESTEP" "${cube[@]}" --resume > out.txt 2> err.txt
  rc=$?
  [[ $rc == 1 ]] || fail "a checkpoint of $size bytes: exit code $rc"
  grep -qx "estep: error: The checkpoint <run/checkpoint.bin> is damaged (cut short: $size bytes)." err.txt ||
    fail "a checkpoint of $size bytes: $(cat err.txt)"
  mv whole.bin run/checkpoint.bin
done
mv run/checkpoint.bin damaged.bin && mkdir run/checkpoint.bin
"$ESTEP" "${cube[@]}" --resume > out.txt 2> err.txt
rc=$?
[[ $rc == 1 ]] || fail "a checkpoint that is a directory: exit code $rc"
grep -qx "estep: error: Cannot read the checkpoint <run/checkpoint.bin>: it is not a file." err.txt || fail "a checkpoint that is a directory: $(cat err.txt)"
rmdir run/checkpoint.bin && mv damaged.bin run/checkpoint.bin

# A mesh file changed since the checkpoint is refused in one line (exit 1), and a resume that
# cannot take over an output (history.csv cut short: exit 4) leaves the directory's summary
# and parameters as they were.
printf '$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n$Elements\n1\n1 4 2 0 1 1 2 3 4\n$EndElements\n' > tet.msh
tet=("$files/scene_ball_drop.prm" --set "Output directory=tet" --set "Postprocessors/List=history"
     --set "Scene/Body 1/Mesh/Type=gmsh" --set "Scene/Body 1/Mesh/File name=tet.msh"
     --set "Output/Checkpoint interval=0.005")
"$ESTEP" "${tet[@]}" --set "Time integration/End time=0.01" > /dev/null 2>&1 || fail "the tetrahedron run"
cp tet/summary.json tet/parameters.prm .
sed -i 's/^4 0 0 1$/4 0 0 1.1/' tet.msh
"$ESTEP" "${tet[@]}" --set "Time integration/End time=0.02" --resume > out.txt 2> err.txt
rc=$?
[[ $rc == 1 ]] || fail "changed mesh file: exit code $rc"
grep -q "was written for another initial state" err.txt || fail "changed mesh file: $(cat err.txt)"
[[ $(wc -l < err.txt) == 1 ]] || fail "changed mesh file: not one line: $(cat err.txt)"
sed -i 's/^4 0 0 1.1$/4 0 0 1/' tet.msh

# output_refused_on_resume WHAT DIRECTORY PATTERN ARGS...: ARGS with --resume exit with code 4
# and a message matching PATTERN, and leave DIRECTORY's summary and parameters as the copies in
# the working directory have them.
output_refused_on_resume() {
  local what=$1 directory=$2 pattern=$3 rc f
  shift 3
  "$ESTEP" "$@" --resume > out.txt 2> err.txt
  rc=$?
  [[ $rc == 4 ]] || fail "$what: exit code $rc"
  grep -q "$pattern" err.txt || fail "$what: $(cat err.txt)"
  for f in summary.json parameters.prm; do
    cmp -s "$f" "$directory/$f" || fail "$what: the failed resume changed $f"
  done
}
truncate -s 300 tet/history.csv
output_refused_on_resume "history.csv cut short" tet "Cannot resume the history file" \
  "${tet[@]}" --set "Time integration/End time=0.02"

# A snapshot of the field output's series deleted before the resume: refused (the series would
# list a missing file).
snap=("$files/spinning_cube.prm" --set "Output directory=snap" --set "Elastic body/Mesh/Subdivisions=2"
      --set "Postprocessors/List=history, field output" --set "Postprocessors/Field output/Interval=1"
      --set "Output/Checkpoint interval=2")
"$ESTEP" "${snap[@]}" --set "Time integration/End time=4" > /dev/null 2>&1 || fail "the snapshot run"
cp snap/summary.json snap/parameters.prm .
rm snap/fields/solution-00002.vtu
output_refused_on_resume "a snapshot deleted" snap \
  "^estep: error: Cannot resume the field output: its snapshot <snap/fields/solution-00002.vtu>" \
  "${snap[@]}" --set "Time integration/End time=6"

# Snapshots written after the last checkpoint by a run killed before its next one are not in
# the series: the resume removes them (they stayed on disk, unlisted).
rm -rf snap
"$ESTEP" "${snap[@]}" --set "Time integration/End time=4" > /dev/null 2>&1 || fail "the snapshot run"
touch snap/fields/solution-00005.vtu snap/fields/solution-00007-p1.vtu
"$ESTEP" "${snap[@]}" --set "Time integration/End time=4" --resume > out.txt 2>&1 || fail "resuming the snapshot run: $(tail -1 out.txt)"
[[ ! -e snap/fields/solution-00005.vtu && ! -e snap/fields/solution-00007-p1.vtu ]] ||
  fail "snapshots beyond the checkpoint's series were left: $(ls snap/fields)"
[[ -e snap/fields/solution-00004.vtu ]] || fail "the resume removed a snapshot of the series: $(ls snap/fields)"

# Two runs into one output directory (a job started again while the first still runs): the
# second is refused, fresh or resumed, and touches nothing of the first's (they mixed their
# history rows).
busy=("$files/spinning_cube.prm" --set "Output directory=busy" --set "Postprocessors/List=history")
"$ESTEP" "${busy[@]}" > busy.txt 2>&1 &
pid=$!
while kill -0 $pid 2> /dev/null && ! grep -q '"status": "running"' busy/summary.json 2> /dev/null; do
  sleep 0.01
done
cp busy/summary.json busy_summary.json
for resume in "" --resume; do
  "$ESTEP" "${busy[@]}" --set "Time integration/End time=1" $resume > out.txt 2> err.txt
  rc=$?
  [[ $rc == 4 ]] || fail "a second run ${resume:-(fresh)} into a busy output directory: exit code $rc"
  grep -q "^estep: error: the output directory <busy> is in use by another estep run" err.txt ||
    fail "a second run ${resume:-(fresh)} into a busy output directory: $(cat err.txt)"
done
cmp -s busy/summary.json busy_summary.json || fail "a refused second run changed the first's summary.json"
kill -TERM $pid
wait $pid
[[ $? == 143 ]] || fail "the first run into the busy directory: $(tail -2 busy.txt)"
grep -q '"status": "interrupted"' busy/summary.json || fail "the busy run's summary: $(grep status busy/summary.json)"
# Its lock ends with it (here by SIGTERM; the system releases it after SIGKILL too).
"$ESTEP" "${busy[@]}" --set "Time integration/End time=1" > /dev/null 2>&1 || fail "a run into the directory after the first ended"

echo "$failures failure(s)"
[[ $failures == 0 ]]
