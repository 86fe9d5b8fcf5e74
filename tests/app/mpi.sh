#!/usr/bin/env bash
# MPI: a run gives the same trajectory to the last bit on 1 process and on 2 MPI processes (of 1
# and of 2 threads), and for the cube on 3: the ranks share the blocks of cells, and every rank
# adds the blocks' sums in block order. With and without contact, and with an implicit method. A run on 2 processes ended by SIGTERM resumes on 1 to
# the same end, and one on 1 resumes on 2. Field output writes a piece per process in vtu, and
# the same datasets as one process in HDF5. An output that fails mid-run, or at the start, ends
# every process. A system without elastic cells, or with fewer cells
# than processes, is refused; so is a mesh the first process (which alone builds it) cannot read,
# and processes that read different input files or checkpoints. An error one process meets alone
# ends every process, instead of a hang.
# Compared: the final checkpoint and history.csv, byte for byte (as in threads.sh), and the final
# energies of summary.json. summary.json records the cells each process holds, and the coordinates
# of the state each keeps current.
# Environment (set by ctest): ESTEP, the estep executable; ESTEP_SOURCE_DIR, the source tree;
# MPIEXEC, the MPI launcher.
set -u
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
files=$ESTEP_SOURCE_DIR/parameter_files
# Open MPI refuses to start as root without these (containers, CI); a rank's threads may use any
# core (by default Open MPI binds each of 2 ranks to one core).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpi=("$MPIEXEC" --bind-to none --oversubscribe -np 2)

fail() {
  echo "FAILED: $*"
  failures=$((failures + 1))
}

# same_final_energies REFERENCE RUN WHAT: summary.json of RUN/ gives the final energies of
# REFERENCE/ (WHAT names RUN in the message).
same_final_energies() {
  /usr/bin/python3 - "$1" "$2" << 'PY' || fail "$3: summary.json's final energies differ from $1"
import json, sys
energies = [json.load(open(run + "/summary.json"))["energies"] for run in sys.argv[1:]]
sys.exit(0 if all(e["final kinetic"] == energies[0]["final kinetic"] and
                  e["final potential"] == energies[0]["final potential"] for e in energies)
         else str(energies))
PY
}

# same_end REFERENCE RUN WHAT: RUN/ holds the final checkpoint and history.csv of REFERENCE/,
# byte for byte, and the same final energies.
same_end() {
  for file in checkpoint.bin history.csv; do
    cmp -s "$1/$file" "$2/$file" || fail "$3: $file differs from $1"
  done
  same_final_energies "$1" "$2" "$3"
}

# same_on_ranks NAME ARGS...: run ARGS on 1 process (1 thread), on 2 processes of 1 thread and
# of 2 threads, into NAME-<ranks>x<threads>/, and compare.
same_on_ranks() {
  local name=$1 run before=$failures
  shift
  "$ESTEP" "$@" --threads 1 --set "Output directory=$name-1x1" > "$name-1x1.txt" 2>&1 ||
    fail "$name on 1 process: $(tail -2 "$name-1x1.txt")"
  for threads in 1 2; do
    run=$name-2x$threads
    "${mpi[@]}" "$ESTEP" "$@" --threads $threads --set "Output directory=$run" > "$run.txt" 2>&1 ||
      fail "$name on 2 processes of $threads threads: $(tail -2 "$run.txt")"
    grep -q '"MPI processes": 2,' "$run/summary.json" ||
      fail "$run: summary.json does not record 2 MPI processes"
    same_end "$name-1x1" "$run" "$name on 2 processes of $threads threads"
  done
  ((failures == before)) || return
  echo "$name: $(grep -o '"steps": [0-9]*' "$name-1x1/summary.json"), identical on 1 process and on 2 processes of 1 and 2 threads"
}

# The cube, 24,000 cells (24 blocks of cells). (Without its field output: the checkpoint
# records the series, whose files are named differently on 2 processes; see below.)
cube=("$files/spinning_cube.prm" --set "Elastic body/Mesh/Subdivisions=10"
      --set "Time integration/End time=1.5" --set "Output/Checkpoint interval=0.25"
      --set "Postprocessors/List=history, step histogram, progress")
same_on_ranks cube "${cube[@]}"
# held_as_expected RUN OWN...: summary.json of RUN records the cells each process holds: the last
# process its own cells alone (every cell of its points comes after its first cell), each other
# its own (OWN, in process order) and a layer of the next one's.
held_as_expected() {
  /usr/bin/python3 - "$@" << 'PY' || fail "$1: summary.json's cells held by each process"
import json, sys
held = json.load(open(sys.argv[1] + "/summary.json"))["problem"]["cells held by each process"]
own = [int(n) for n in sys.argv[2:]]
last = len(own) - 1
sys.exit(0 if len(held) == len(own) and held[last] == own[last]
         and all(own[r] < held[r] < 1.5 * own[r] for r in range(last))
         else f"held {held}, own {own}")
PY
}
held_as_expected cube-2x1 $((12 * 1024)) $((24000 - 12 * 1024))
# kept_as_expected RUN FRACTION: summary.json of RUN records the coordinates of the state each
# process keeps current (those its cells and its blocks of coordinates read, and with contact
# every boundary point): together every coordinate, each process less than FRACTION of them.
kept_as_expected() {
  /usr/bin/python3 - "$1" "$2" << 'PY' || fail "$1: summary.json's coordinates kept by each process"
import json, sys
summary = json.load(open(sys.argv[1] + "/summary.json"))
kept, n = summary["problem"]["coordinates kept by each process"], summary["degrees of freedom"]
sys.exit(0 if len(kept) == summary["MPI processes"] and sum(kept) >= n
         and all(k < float(sys.argv[2]) * n for k in kept) else f"kept {kept} of {n}")
PY
}
kept_as_expected cube-2x1 0.75
# Without checkpoints the processes complete the state at the end all the same, for the summary.
"${mpi[@]}" "$ESTEP" "${cube[@]}" --threads 1 --set "Output/Checkpoint interval=0" \
  --set "Output/Checkpoint wall interval=0" --set "Output directory=cube-unsaved" \
  > cube-unsaved.txt 2>&1 || fail "cube on 2 processes without checkpoints: $(tail -2 cube-unsaved.txt)"
[[ ! -e cube-unsaved/checkpoint.bin ]] || fail "cube-unsaved: a checkpoint was written"
cmp -s cube-1x1/history.csv cube-unsaved/history.csv ||
  fail "cube on 2 processes without checkpoints: history.csv differs from cube-1x1"
same_final_energies cube-1x1 cube-unsaved "cube on 2 processes without checkpoints"
# Checkpoints by wall time, every 30 ms: the first process's clock decides for both (each
# checkpoint completes the state, which they do together), so the run neither hangs nor strays.
"${mpi[@]}" "$ESTEP" "${cube[@]}" --threads 1 --set "Output/Checkpoint interval=0" \
  --set "Output/Checkpoint wall interval=0.0005" --set "Output directory=cube-wall" \
  > cube-wall.txt 2>&1 || fail "cube on 2 processes, checkpoints by wall time: $(tail -2 cube-wall.txt)"
same_end cube-1x1 cube-wall "cube on 2 processes, checkpoints by wall time"

# On 3 processes (of 1 thread, more than the cores): the middle one has ghost cells of the
# processes on both sides, and, like the first, holds chunks of the next one's cells for its
# points' gradient.
"$MPIEXEC" --bind-to none --oversubscribe -np 3 "$ESTEP" "${cube[@]}" --threads 1 \
  --set "Output directory=cube-3x1" > cube-3x1.txt 2>&1 ||
  fail "cube on 3 processes: $(tail -2 cube-3x1.txt)"
same_end cube-1x1 cube-3x1 "cube on 3 processes"
held_as_expected cube-3x1 $((8 * 1024)) $((8 * 1024)) $((24000 - 16 * 1024))
kept_as_expected cube-3x1 0.75

# An implicit method: its Hessian needs every cell, which each process gathers from the others
# (each holds only the cells it computes). The cube of 5,184 cells (6 blocks), IDA to t = 1; and
# of 648 cells, one block, which the second process computes alone.
same_on_ranks ida "$files/spinning_cube_ida_bdf.prm" --set "Elastic body/Mesh/Subdivisions=6" \
  --set "Time integration/End time=1" --set "Postprocessors/List=history"
same_on_ranks ida_one_block "$files/spinning_cube_ida_bdf.prm" \
  --set "Elastic body/Mesh/Subdivisions=3" --set "Time integration/End time=1" \
  --set "Postprocessors/List=history"
# Explicit Newmark shares the state as energy-stepping does: each process keeps its part, which
# the history's rows and the checkpoints (the acceleration and the previous step too) complete.
# The cube of 24,000 cells.
same_on_ranks newmark "$files/spinning_cube_newmark_0.0082.prm" \
  --set "Elastic body/Mesh/Subdivisions=10" --set "Time integration/End time=0.5" \
  --set "Postprocessors/List=history"
kept_as_expected newmark-2x1 0.75

# Field output in HDF5: every process writes its rows into the same files, which hold the
# same datasets, to the last bit, as those of one process, and the same series. The cube of
# 5,184 cells (6 blocks, 3 per process), and the ball drop (one block, which the second process
# writes alone: the first writes no cell, but points and the obstacle's rows).
h5=(--set "Postprocessors/List=history, field output" --set "Postprocessors/Field output/Format=hdf5")
# h5_on_ranks NAME SNAPSHOTS ARGS...
h5_on_ranks() {
  local name=$1 snapshots=$2
  shift 2
  "$ESTEP" "$@" "${h5[@]}" --threads 1 --set "Output directory=$name-1" > "$name-1.txt" 2>&1 ||
    fail "HDF5 output of $name on 1 process: $(tail -2 "$name-1.txt")"
  "${mpi[@]}" "$ESTEP" "$@" "${h5[@]}" --threads 1 --set "Output directory=$name-2" \
    > "$name-2.txt" 2>&1 || fail "HDF5 output of $name on 2 processes: $(tail -2 "$name-2.txt")"
  cmp -s "$name-1/solution.xdmf" "$name-2/solution.xdmf" ||
    fail "$name: solution.xdmf on 2 processes differs from 1 process"
  /usr/bin/python3 - "$name" "$snapshots" << 'PY' || fail "$name: HDF5 output on 2 processes differs from 1 process"
import h5py, numpy, pathlib, sys
name, snapshots = sys.argv[1], int(sys.argv[2])
one = sorted(pathlib.Path(f"{name}-1/fields").glob("*.h5"))
two = sorted(pathlib.Path(f"{name}-2/fields").glob("*.h5"))
assert len(one) == snapshots + 1 and [p.name for p in one] == [p.name for p in two], (one, two)
def datasets(h5):
    names = []
    h5.visit(lambda n: names.append(n) if isinstance(h5[n], h5py.Dataset) else None)
    return names
n = 0
for a, b in zip(one, two):
    with h5py.File(a) as x, h5py.File(b) as y:
        assert dict(x.attrs) == dict(y.attrs), a.name
        assert datasets(x) and datasets(x) == datasets(y), (a.name, datasets(x), datasets(y))
        for d in datasets(x):
            assert x[d].dtype == y[d].dtype and numpy.array_equal(x[d][:], y[d][:]), (a.name, d)
            n += 1
print(f"HDF5 output of {name} on 2 processes: {len(two)} files, {n} datasets, equal to those of 1 process")
PY
}
h5_on_ranks h5-cube 3 "$files/spinning_cube.prm" --set "Elastic body/Mesh/Subdivisions=6" \
  --set "Time integration/End time=0.5" --set "Postprocessors/Field output/Interval=0.25"
h5_on_ranks h5-drop 3 "$files/scene_ball_drop.prm" --set "Time integration/End time=0.05" \
  --set "Postprocessors/Field output/Interval=0.025"

# An output of the first process alone that cannot start (history.csv is a directory) while
# every process starts HDF5 output: one message, exit code 4, no process left waiting.
mkdir -p blocked/history.csv/x
timeout 120 "${mpi[@]}" "$ESTEP" "$files/spinning_cube.prm" "${h5[@]}" --set "Output directory=blocked" \
  --set "Elastic body/Mesh/Subdivisions=6" > blocked.txt 2>&1
rc=$?
[[ $rc == 4 ]] || fail "an output that cannot start on 2 processes with HDF5 output: exit code $rc, expected 4"

# The colliding balls during their contact (about 3,000 cells per ball, 3 blocks each).
balls=("$files/ball_collision.prm" --set "Colliding balls/Mesh size=0.2"
       --set "Time integration/End time=0.125")
same_on_ranks penalty "${balls[@]}"
same_on_ranks impenetrable "${balls[@]}" --set "Contact/Mode=impenetrability"
# Small balls: most of their points lie on or next to the boundary, which every process keeps.
kept_as_expected penalty-2x1 1
# A scene of bodies in contact alone (no gravity, supports or obstacles) shares its state as its
# contact system does: Newton's cradle, through its first impacts.
same_on_ranks cradle "$files/scene_newtons_cradle.prm" --set "Time integration/End time=0.2" \
  --set "Postprocessors/List=history, contact monitor"
grep -q '"coordinates kept by each process"' cradle-2x1/summary.json ||
  fail "cradle-2x1: summary.json records no coordinates kept by each process"
# So does a scene with gravity and a half-space obstacle, which read the bodies' boundary points
# alone: the ball dropped onto the floor, into its bounce, in penalty contact (whose gradient the
# obstacle adds at the boundary points).
same_on_ranks drop "$files/scene_ball_drop.prm" --set "Time integration/End time=0.318" \
  --set "Contact/Mode=penalty" --set "Postprocessors/List=history, contact monitor"
grep -q '"coordinates kept by each process"' drop-2x1/summary.json ||
  fail "drop-2x1: summary.json records no coordinates kept by each process"
# Supports renumber the coordinates: a rank keeps the free coordinates its bodies keep and its own
# blocks of the free ones, some of whose gradient other ranks compute. The cantilever (1,920
# cells, 2 blocks), clamped at one end; and the ball dropped onto a floor of triangles in
# impenetrable contact (a surface's points are held where they are as supported points are).
same_on_ranks cantilever "$files/scene_cantilever.prm" --set "Time integration/End time=1" \
  --set "Postprocessors/List=history"
kept_as_expected cantilever-2x1 0.75
printf 'solid floor\n facet normal 0 0 1\n  outer loop\n   vertex -1 -1 0\n   vertex 1 -1 0\n   vertex 1 1 0\n  endloop\n endfacet\n facet normal 0 0 1\n  outer loop\n   vertex -1 -1 0\n   vertex 1 1 0\n   vertex -1 1 0\n  endloop\n endfacet\nendsolid floor\n' > floor.stl
same_on_ranks drop_on_surface "$files/scene_ball_drop.prm" --set "Time integration/End time=0.318" \
  --set "Scene/Obstacles/Half-spaces=" --set "Scene/Obstacles/Surface files=floor.stl" \
  --set "Postprocessors/List=history, contact monitor"
grep -q '"coordinates kept by each process"' drop_on_surface-2x1/summary.json ||
  fail "drop_on_surface-2x1: summary.json records no coordinates kept by each process"

# SIGTERM to the launcher after the first checkpoint: it passes the signal to both processes,
# which end after the same step (status interrupted, a final checkpoint; each exits with 143,
# Open MPI's launcher, signalled itself, with 1); resumed on 1
# process, the run ends where the one on 1 process without a stop ends. Open MPI's launcher
# passes the signal on about a second late, so the run must last well beyond that (to t = 8 it
# took 0.9 s and completed first).
long_cube=("${cube[@]}" --set "Time integration/End time=30")
"$ESTEP" "${long_cube[@]}" --threads 1 --set "Output directory=whole" > whole.txt 2>&1 ||
  fail "the cube to t = 8 on 1 process: $(tail -2 whole.txt)"
"${mpi[@]}" "$ESTEP" "${long_cube[@]}" --threads 1 --set "Output directory=resumed" > stopped.txt 2>&1 &
pid=$!
while kill -0 $pid 2> /dev/null && [[ ! -f resumed/checkpoint.bin ]]; do sleep 0.02; done
kill -TERM $pid 2> /dev/null
wait $pid
code=$?
((code != 0)) || fail "SIGTERM on 2 processes: exit code 0: $(tail -3 stopped.txt)"
grep -q '"status": "interrupted"' resumed/summary.json ||
  fail "SIGTERM on 2 processes: summary.json does not say interrupted"
"$ESTEP" "${long_cube[@]}" --threads 1 --set "Output directory=resumed" --resume > resumed.txt 2>&1 ||
  fail "the resume on 1 process: $(tail -2 resumed.txt)"
grep "resuming from" resumed.txt
same_end whole resumed "stopped on 2 processes, resumed on 1"

# And the other way round: a run on 1 process stopped by SIGTERM, resumed on 2.
"$ESTEP" "${long_cube[@]}" --threads 1 --set "Output directory=resumed-on-2" > stopped-1.txt 2>&1 &
pid=$!
while kill -0 $pid 2> /dev/null && [[ ! -f resumed-on-2/checkpoint.bin ]]; do sleep 0.02; done
kill -TERM $pid 2> /dev/null
wait $pid
"${mpi[@]}" "$ESTEP" "${long_cube[@]}" --threads 1 --set "Output directory=resumed-on-2" --resume \
  > resumed-on-2.txt 2>&1 || fail "the resume on 2 processes: $(tail -2 resumed-on-2.txt)"
same_end whole resumed-on-2 "stopped on 1 process, resumed on 2"

# Field output on 2 processes: each writes its piece (the cells of its blocks), the first the
# .pvtu joining them, which the series lists; the pieces hold the cells, points and values of the
# file one process writes. Then a run with field output stopped by SIGTERM and resumed on 2
# processes continues the series and ends as the run without a stop.
fields=("${cube[@]}" --set "Postprocessors/List=history, progress, field output"
        --set "Postprocessors/Field output/Interval=0.5")
"$ESTEP" "${fields[@]}" --threads 1 --set "Output directory=fields-1" > fields-1.txt 2>&1 ||
  fail "field output on 1 process: $(tail -2 fields-1.txt)"
for run in fields-2 fields-whole; do
  "${mpi[@]}" "$ESTEP" "${fields[@]}" --threads 1 --set "Output directory=$run" > $run.txt 2>&1 ||
    fail "field output on 2 processes: $(tail -2 $run.txt)"
done
/usr/bin/python3 - << 'PY' || fail "field output on 2 processes: the pieces do not hold the snapshot"
import os, re, sys
sys.path.insert(0, os.path.join(os.environ["ESTEP_SOURCE_DIR"], "tests"))
from vtu_arrays import arrays
whole = arrays("fields-1/fields/solution-00002.vtu")
pvtu = open("fields-2/fields/solution-00002.pvtu").read()
pieces = re.findall(r'<Piece Source="([^"]+)"', pvtu)
assert pieces == ["solution-00002-p0.vtu", "solution-00002-p1.vtu"], pieces
assert "fields/solution-00002.pvtu" in open("fields-2/solution.pvd").read()
point_fields = [("points", 3), ("displacement", 3), ("velocity", 3)]
cell_fields = [("J", 1), ("strain_energy_density", 1), ("cauchy_stress", 9), ("von_mises_stress", 1)]
first = 0
for piece in pieces:
    part = arrays("fields-2/fields/" + piece)
    n = len(part["connectivity"]) // 4
    for e in range(n):
        for a in range(4):
            p, q = part["connectivity"][4 * e + a], whole["connectivity"][4 * (first + e) + a]
            for name, k in point_fields:
                assert part[name][k * p:k * p + k] == whole[name][k * q:k * q + k], (piece, e, name)
        for name, k in cell_fields:
            assert part[name][k * e:k * e + k] == whole[name][k * (first + e):k * (first + e) + k], (piece, e, name)
    first += n
assert 4 * first == len(whole["connectivity"]), first
print(f"field output on 2 processes: {len(pieces)} pieces of {first} cells in all, as on 1 process")
PY
"${mpi[@]}" "$ESTEP" "${fields[@]}" --set "Time integration/End time=30" --threads 1 \
  --set "Output directory=fields-whole" > fields-whole.txt 2>&1 ||
  fail "field output on 2 processes to t = 30: $(tail -2 fields-whole.txt)"
"${mpi[@]}" "$ESTEP" "${fields[@]}" --set "Time integration/End time=30" --threads 1 \
  --set "Output directory=fields-resumed" > fields-stopped.txt 2>&1 &
pid=$!
while kill -0 $pid 2> /dev/null && [[ ! -f fields-resumed/checkpoint.bin ]]; do sleep 0.02; done
kill -TERM $pid 2> /dev/null
wait $pid
grep -q '"status": "interrupted"' fields-resumed/summary.json ||
  fail "field output on 2 processes: SIGTERM did not interrupt the run"
"${mpi[@]}" "$ESTEP" "${fields[@]}" --set "Time integration/End time=30" --threads 1 \
  --set "Output directory=fields-resumed" --resume > fields-resumed.txt 2>&1 ||
  fail "the resume on 2 processes: $(tail -2 fields-resumed.txt)"
for file in checkpoint.bin history.csv fields/solution-00016.pvtu fields/solution-00016-p1.vtu; do
  cmp -s fields-whole/$file fields-resumed/$file ||
    fail "field output resumed on 2 processes: $file differs from the run without a stop"
done
cmp -s fields-whole/solution.pvd fields-resumed/solution.pvd ||
  fail "field output resumed on 2 processes: solution.pvd differs from the run without a stop"

# fails_mid_run NAME BLOCKED PATTERN ARGS...: the cube (ARGS added) on 2 processes into NAME/;
# once it runs, a directory is made at NAME/BLOCKED, where an output will go. Every process must
# end with exit code 4 (MPI_Abort) instead of one stepping on alone, with exactly one report
# matching PATTERN, and summary.json must say failed.
fails_mid_run() {
  local name=$1 blocked=$2 pattern=$3 pid code reports
  shift 3
  "${mpi[@]}" "$ESTEP" "$files/spinning_cube.prm" --set "Elastic body/Mesh/Subdivisions=10" \
    --set "Time integration/End time=40" --set "Output directory=$name" "$@" > "$name.txt" 2>&1 &
  pid=$!
  for _ in $(seq 300); do grep -q '"status": "running"' "$name/summary.json" 2> /dev/null && break; sleep 0.1; done
  mkdir -p "$name/$blocked"
  wait $pid
  code=$?
  ((code == 4)) || fail "$name: exit code $code, not 4: $(tail -3 "$name.txt")"
  reports=$(grep -c "^estep: error: $pattern" "$name.txt")
  ((reports == 1)) || fail "$name: $reports reports, not 1: $(head -3 "$name.txt")"
  grep -q '"status": "failed"' "$name/summary.json" || fail "$name: summary.json does not say failed"
  ((code == 4 && reports == 1)) && echo "$name: exit code 4, 1 report"
}
# An output of the first process: its first checkpoint meets a directory where the file goes.
fails_mid_run broken checkpoint.bin.part "Writing the checkpoint <broken/checkpoint.bin.part> failed" \
  --set "Output/Checkpoint interval=10" --set "Postprocessors/List=history, progress"
# An output of the second process alone: its piece of a field output snapshot. The first
# process knows nothing of it, so the second must say it (its standard output and error are
# otherwise silent).
fails_mid_run piece fields/solution-00006-p1.vtu/blocked "Field output: .*solution-00006-p1.vtu" \
  --set "Postprocessors/Field output/Interval=5" --set "Postprocessors/List=history, field output"
# Neither its piece of that snapshot nor the file joining the pieces stays behind (the first
# process removes its own when the second's failed).
ls piece/fields | grep -q "solution-00006-p0.vtu\|solution-00006.pvtu" &&
  fail "piece: a snapshot that the second process could not write stays: $(ls piece/fields)"
# The series lists every snapshot written whole before (the first process rewrites it at the end,
# as on one process).
written=$(ls piece/fields | grep -c "\.pvtu$")
listed=$(grep -c "<DataSet" piece/solution.pvd)
[[ $written -gt 1 && $listed == "$written" ]] || fail "piece: solution.pvd lists $listed of $written snapshots"

# refused NAME PATTERN ARGS...: ARGS on 2 processes exit with code 1 and one line matching PATTERN.
refused() {
  local name=$1 pattern=$2
  shift 2
  "${mpi[@]}" "$ESTEP" "$@" --set "Output directory=$name" > "$name.txt" 2>&1
  local code=$?
  ((code == 1)) || fail "$name: exit code $code, not 1"
  [[ $(grep -c "^estep: error: .*$pattern" "$name.txt") == 1 ]] ||
    fail "$name: not one line saying '$pattern': $(cat "$name.txt")"
  [[ ! -e $name ]] || fail "$name: an output directory was written"
  echo "$name: $(grep '^estep: error' "$name.txt")"
}
refused argon "no elastic body whose cells" "$files/argon_cluster.prm"
cat > one_cell.msh << 'MSH'
$MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
$EndNodes
$Elements
1
1 4 2 0 1 1 2 3 4
$EndElements
MSH
refused one_cell "more than the 1 cells" "$files/spinning_cube.prm" \
  --set "Elastic body/Mesh/Type=gmsh" --set "Elastic body/Mesh/File name=one_cell.msh"
# Only the first process builds the mesh; the error it meets ends every process.
refused missing_mesh "cannot open the gmsh file 'missing.msh'" "$files/spinning_cube.prm" \
  --set "Elastic body/Mesh/Type=gmsh" --set "Elastic body/Mesh/File name=missing.msh"

# Processes that read different files, as on machines without a shared file system: each
# process runs in its own working directory (Open MPI's -wdir), with its own copy of run.prm
# and its own output directory run/.
mkdir -p first second
cp "$files/spinning_cube.prm" first/run.prm
cp "$files/spinning_cube.prm" second/run.prm
common=(--set "Elastic body/Mesh/Subdivisions=4" --set "Output directory=run"
        --set "Postprocessors/List=history" --set "Output/Checkpoint interval=0.5"
        --set "Time integration/End time=2")
apart() {
  timeout 120 "$MPIEXEC" --bind-to none --oversubscribe -np 1 -wdir "$work/first" "$ESTEP" run.prm \
    "${common[@]}" "$@" : -np 1 -wdir "$work/second" "$ESTEP" run.prm "${common[@]}" "$@"
}
# The copies differ: refused in one line by every process alike.
sed -i 's/set Energy step *=.*/set Energy step = 2e-5/' second/run.prm
cmp -s first/run.prm second/run.prm && fail "the second copy of run.prm was not changed"
apart > apart.txt 2>&1
code=$?
((code == 1)) || fail "different input files: exit code $code, not 1"
[[ $(grep -c "^estep: error: The processes read different parameters from <run.prm> and the command line (those of process 1 are not the first's)" apart.txt) == 1 && $(grep -c "^estep:" apart.txt) == 1 ]] ||
  fail "different input files: not one line: $(cat apart.txt)"
# The second's copy is malformed: the second process alone fails, while the first waits for it
# in a collective call; it says why and ends both (through MPI_Abort) instead of a hang.
echo "set No such entry = 1" >> second/run.prm
apart > apart.txt 2>&1
code=$?
((code != 0 && code != 124)) || fail "a malformed input file on the second process: exit code $code (124: a hang)"
[[ $(grep -c "^estep: error: .*No such entry" apart.txt) == 1 && $(grep -c "^estep: error:" apart.txt) == 1 ]] ||
  fail "a malformed input file on the second process: not one report: $(head -5 apart.txt)"
((code != 0 && code != 124)) && echo "malformed input on the second process alone: exit code $code, one report"
# The same copies, but only the first has a checkpoint: --resume is refused in one line.
cp first/run.prm second/run.prm
"$ESTEP" first/run.prm "${common[@]}" --set "Output directory=first/run" > /dev/null 2>&1 ||
  fail "the run that writes the first's checkpoint"
apart --resume > apart.txt 2>&1
code=$?
((code == 1)) || fail "different checkpoints: exit code $code, not 1"
grep -q "^estep: error: The processes read different checkpoints <run/checkpoint.bin> (those of process 1 are not the first's)" apart.txt ||
  fail "different checkpoints: $(cat apart.txt)"

if ((failures > 0)); then
  echo "$failures failures"
  exit 1
fi
echo "all runs identical"
