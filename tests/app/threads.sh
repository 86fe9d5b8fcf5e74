#!/usr/bin/env bash
# Threads: a run gives the same trajectory to the last bit on 1, 2 and 3 threads (the loops over
# cells sum fixed blocks of cells in block order; the bodies of a scene are evaluated side by side
# and their results added in body order), with and without contact, and a checkpoint
# written on 2 threads resumes on 1 to the same end. Compared: the final checkpoint (positions,
# velocities, terrace level, counters, the postprocessors' states; it records only the entries
# that fix the trajectory, not the threads) and history.csv, byte for byte.
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

# same_on_threads NAME ARGS...: run ARGS on 1, 2 and 3 threads into NAME-<threads>/ and compare.
same_on_threads() {
  local name=$1 threads before=$failures
  shift
  for threads in 1 2 3; do
    "$ESTEP" "$@" --threads $threads --set "Output directory=$name-$threads" > "$name-$threads.txt" 2>&1 ||
      fail "$name on $threads threads: $(tail -2 "$name-$threads.txt")"
    grep -q "\"threads\": $threads," "$name-$threads/summary.json" ||
      fail "$name: summary.json does not record $threads threads"
  done
  for threads in 2 3; do
    for file in checkpoint.bin history.csv; do
      cmp -s "$name-1/$file" "$name-$threads/$file" ||
        fail "$name: $file on $threads threads differs from 1 thread"
    done
  done
  ((failures == before)) || return
  echo "$name: $(grep -o '"steps": [0-9]*' "$name-1/summary.json"), $(grep -o '"degrees of freedom": [0-9]*' "$name-1/summary.json"), identical on 1, 2 and 3 threads"
}

# The cube, 24,000 cells (24 blocks of cells).
cube=("$files/spinning_cube.prm" --set "Elastic body/Mesh/Subdivisions=10"
      --set "Time integration/End time=1.5" --set "Output/Checkpoint interval=0.25")
same_on_threads cube "${cube[@]}"

# The colliding balls during their contact, with the penalty and as impenetrable bodies (about
# 3,000 cells per ball).
balls=("$files/ball_collision.prm" --set "Colliding balls/Mesh size=0.2"
       --set "Time integration/End time=0.125")
same_on_threads penalty "${balls[@]}"
same_on_threads impenetrable "${balls[@]}" --set "Contact/Mode=impenetrability"

# Eight balls falling on a floor: bodies of one block of cells each, which the threads share out
# among themselves (the bodies' results are added in body order).
same_on_threads eight-balls "$files/scene_eight_balls.prm" --set "Time integration/End time=0.1"

# A run on 2 threads killed (SIGKILL) after its first checkpoint, resumed on 1.
"$ESTEP" "${cube[@]}" --threads 2 --set "Output directory=resumed" > /dev/null 2>&1 &
pid=$!
while kill -0 $pid 2> /dev/null && [[ ! -f resumed/checkpoint.bin ]]; do sleep 0.02; done
kill -9 $pid 2> /dev/null
wait $pid 2> /dev/null
"$ESTEP" "${cube[@]}" --threads 1 --set "Output directory=resumed" --resume > resumed.txt 2>&1 ||
  fail "the resume on 1 thread: $(tail -2 resumed.txt)"
grep "resuming from" resumed.txt
for file in checkpoint.bin history.csv; do
  cmp -s cube-1/$file resumed/$file || fail "resumed on 1 thread: $file differs from the run on 1"
done

if ((failures > 0)); then
  echo "$failures failures"
  exit 1
fi
echo "all runs identical"
