#!/usr/bin/env bash
# The estep command line: help, version, print-parameters, overrides, outputs, and every kind
# of bad input with its one-line message and exit code.
# Environment (set by ctest): ESTEP, the estep executable.
set -u
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0

fail() {
  echo "FAILED: $*"
  failures=$((failures + 1))
}

# expect CODE PATTERN -- ARGS...: run estep, check the exit code, that PATTERN (extended regex)
# occurs in its output, and that an error is one line without an abort trace.
expect() {
  local code=$1 pattern=$2
  shift 3
  "$ESTEP" "$@" > out.txt 2> err.txt
  local rc=$?
  [[ $rc == "$code" ]] || fail "estep $* exited with $rc, expected $code"
  grep -Eq -- "$pattern" out.txt err.txt || fail "estep $*: no <$pattern> in its output: $(cat out.txt err.txt | head -5)"
  if [[ $code == 1 ]]; then
    [[ $(wc -l < err.txt) == 1 ]] || fail "estep $*: the error is not one line: $(cat err.txt)"
    grep -Eq "error:" err.txt || fail "estep $*: no 'error:' on standard error"
  fi
  if grep -Eq "Stacktrace|An error occurred in line|Aborted|terminate called" err.txt; then
    fail "estep $*: abort trace on standard error"
  fi
}

cat > run.prm <<'PRM'
set Output directory = run
subsection Time integration
  set End time = 2
end
subsection Output
  set History interval = 0.5
end
PRM

# Help, version, parameters.
expect 0 "Usage: estep" -- --help
expect 0 "Usage: estep" -- -h
expect 0 "^estep [0-9]+\.[0-9]+\.[0-9]+ \(deal.II 9\.[0-9.]+, cell kernels (x86-64(-v[34])?|portable C\+\+)\)" -- --version
expect 0 "set Energy step" -- --print-parameters
expect 0 "# Energy step h \(energy units of the system\)" -- --print-parameters
# The Selection patterns and documentation come from the registries.
expect 0 "^ *# - colliding balls: Two elastic balls" -- --print-parameters
expect 0 "^ *# - explicit newmark: the explicit Newmark method" -- --print-parameters
expect 0 "^ *# - neo-Hookean: W\(F\) =" -- --print-parameters
expect 0 "^ *# - field output: snapshots of an elastic body" -- --print-parameters
expect 0 "Time integration/Method: +arkode irk, arkode midpoint, energy momentum, energy stepping, explicit newmark, ida bdf" -- --help
expect 0 "set End time += 2" -- --print-parameters run.prm
expect 0 "set End time += 7" -- --print-parameters run.prm --set "Time integration/End time=7"
"$ESTEP" --print-parameters > all.prm
for section in "Time integration" "Output" "Problem" "Argon cluster"; do
  grep -q "^subsection $section\$" all.prm || fail "--print-parameters lacks subsection $section"
done
# Every entry is documented: each 'set' line follows a comment.
awk '/^ *set /{ if (prev !~ /^ *#/) { print "undocumented: " $0; bad=1 } } { if ($0 !~ /^ *$/) prev=$0 } END { exit bad }' all.prm ||
  fail "--print-parameters shows undocumented entries"
# The printed file is a valid input, and JSON round-trips.
"$ESTEP" --print-parameters run.prm > printed.prm
sed -i 's/^set Output directory.*/set Output directory = printed/' printed.prm
expect 0 "completed" -- printed.prm
"$ESTEP" --print-parameters printed.prm > /dev/null || fail "printed.prm cannot be read back"

# A run and its outputs.
expect 0 "completed at t = 2" -- run.prm
for file in parameters.prm history.csv summary.json step_histogram.csv; do
  [[ -s run/$file ]] || fail "run/$file missing or empty"
done
grep -q '"status": "completed"' run/summary.json || fail "summary.json lacks status completed"
tail -n 1 run/log.txt | grep -Eq "^estep: t = 2 \(100.0%\), [0-9]+ steps, .*, completed$" || fail "log.txt lacks its last line: $(tail -n 1 run/log.txt)"
expect 0 "estep: t = [0-9.e+-]+ \([0-9.]+%\), [0-9]+ steps" -- run.prm -s "Output directory=batch" -s "Time integration/End time=1000" -s "Output/History interval=1" -s "Postprocessors/Progress/Interval=0.1"
(( $(wc -l < batch/log.txt) >= 2 )) || fail "a batch run of several tenths of a second logged fewer than two lines"
expect 0 "completed" -- run.prm -s "Output directory=nolog" -s "Postprocessors/List=history, step histogram"
[[ ! -e nolog/log.txt ]] || fail "Progress = off wrote log.txt"
grep -q '"final time": 2' run/summary.json || fail "summary.json lacks the final time"
grep -q '"wall seconds"' run/summary.json || fail "summary.json lacks the wall time"
grep -q '"peak memory \[MiB\]"' run/summary.json || fail "summary.json lacks the peak memory"
grep -Eq '"cell kernels": "(x86-64(-v[34])?|portable C\+\+)"' run/summary.json ||
  fail "summary.json lacks the cell kernels' instruction set"
[[ $(wc -l < run/history.csv) == 6 ]] || fail "history.csv should have a header and 5 rows (t = 0, 0.5, ..., 2)"
python3 -c "import json,sys; json.load(open('run/summary.json'))" || fail "summary.json is not valid JSON"
# A run to a later end time passes through the same states: its rows before the earlier end
# time are those of the shorter run to the last digit (the search's windows do not depend on it).
expect 0 "completed at t = 3" -- run.prm -s "Time integration/End time=3" -s "Output directory=longer"
[[ $(head -n 5 longer/history.csv) == "$(head -n 5 run/history.csv)" ]] || fail "the run to t = 3 differs from the run to t = 2 before t = 2"
# A history interval of 0: the start and the end.
expect 0 "completed at t = 2" -- run.prm -s "Output/History interval=0" -s "Output directory=ends"
[[ $(cut -d, -f1 ends/history.csv | tail -n +2 | tr '\n' ' ') == "0 2 " ]] || fail "history.csv with interval 0 should have the rows t = 0 and 2: $(cut -d, -f1 ends/history.csv)"

# parameters.json beside parameters.prm, a valid input itself.
[[ -s run/parameters.json ]] || fail "run/parameters.json missing"
"$ESTEP" --print-parameters run/parameters.json > /dev/null || fail "run/parameters.json cannot be read back"
# JSON input: numbers as values; the long form that --print-parameters writes reads back.
printf '{ "Output directory": "json", "Time integration": { "End time": 0.5 } }\n' > numbers.json
expect 0 "completed at t = 0.5" -- numbers.json
"$ESTEP" --print-parameters numbers.json > long.json
expect 0 "completed at t = 0.5" -- long.json -s "Output directory=long"

# A run into a directory holding another run's field snapshots removes them (and its series).
mkdir -p stale/fields && touch stale/fields/solution-00007.vtu stale/solution.pvd stale/step_histogram.csv
touch stale/fields/mine.txt
expect 0 "completed" -- run.prm -s "Output directory=stale"
[[ ! -e stale/fields/solution-00007.vtu && ! -e stale/solution.pvd ]] || fail "an earlier run's snapshots were left beside a new run"
[[ -e stale/fields/mine.txt ]] || fail "a file that is not estep's was removed"

# Overrides.
expect 0 "completed at t = 1" -- run.prm --set "Time integration/End time=1" --set "Output directory=over"
grep -q "End time *= 1" over/parameters.prm || fail "parameters.prm does not record the override"
expect 0 "explicit newmark" -- run.prm -s "Time integration/Method=explicit newmark" -s "Output directory=nm"

# Bad input: one clear message naming the problem, exit code 1, output left alone.
cp run/summary.json summary.before
expect 1 "does not exist" -- missing.prm
expect 1 "No input file" --
expect 1 "Unknown option <--frobnicate>" -- --frobnicate run.prm
# deal.II's .prm reader does not check a value with a '{' against its pattern; estep does.
printf 'subsection Time integration\n  set Method = {nergy stepping\nend\n' > brace.prm
expect 1 "Time integration/Method: the value <\{nergy stepping> does not match" -- brace.prm
expect 1 "needs a number of threads" -- run.prm --threads
expect 1 "The option --threads needs a number of threads from 0 to 4096 \(0: one per core\), not <-2>\.$" -- run.prm --threads -2
expect 1 "The option --threads needs a number of threads from 0 to 4096 \(0: one per core\), not <100000>\.$" -- run.prm --threads 100000
# The progress line of an end time too far to reach gives three digits of the time left, not
# three hundred.
"$ESTEP" run.prm -s "Time integration/End time=1e300" -s "Output/History interval=0" -s "Postprocessors/List=progress" \
  -s "Postprocessors/Progress/Interval=0.1" -s "Output directory=far" > far.txt 2>&1 &
far=$!
sleep 2
kill -TERM $far
wait $far
grep -Eq "s elapsed, [0-9.]+e\+[0-9]+ s left$" far/log.txt || fail "the progress line of an end time of 1e300: $(tail -c 300 far/log.txt)"
expect 1 "Threads.*does not match" -- run.prm -s "Threads=-2"
# Started as several processes by a launcher whose MPI is not estep's (its environment says 2
# processes, as Open MPI's and MPICH's set it, but MPI sees 1): the first says so once; the
# others exit as quietly. (unit/mpi runs estep on 2 processes.)
export OMPI_COMM_WORLD_SIZE=2 OMPI_COMM_WORLD_RANK=0
expect 1 "started as 2 MPI processes, but its MPI library sees 1" -- run.prm --set "Output directory=mpi"
export OMPI_COMM_WORLD_RANK=1
"$ESTEP" run.prm --set "Output directory=mpi" > out.txt 2>&1
[[ $? == 1 && ! -s out.txt ]] || fail "the second of two MPI processes: $(head -3 out.txt)"
unset OMPI_COMM_WORLD_SIZE OMPI_COMM_WORLD_RANK
[[ ! -e mpi ]] || fail "an MPI start wrote output"
expect 1 "More than one input file" -- run.prm run.prm
printf 'set Output directory = run\nsubsection Time integration\n  this is not a statement\nend\n' > malformed.prm
expect 1 "Line <3> of file <malformed.prm>.*could not be parsed" -- malformed.prm
printf 'set Output directory = run\nsubsection Time integration\n  set End time = 1\n' > unbalanced.prm
expect 1 "unequal numbers of 'subsection' and 'end'" -- unbalanced.prm
printf 'set Output directory = run\nsubsection Time integration\n  set Energy stepp = 1\nend\n' > unknown.prm
expect 1 "Line <3> of file <unknown.prm>.*Energy stepp" -- unknown.prm
printf 'set Output directory = run\nsubsection Time integraton\n  set End time = 1\nend\n' > section.prm
expect 1 "Line <2> of file <section.prm>: There is no such subsection to be entered: Time integraton\.$" -- section.prm
printf 'set Output directory = run\nsubsection Time integration\n  subsection Energy stepping\n    set Energy step = -1\n  end\nend\n' > pattern.prm
expect 1 "Line <4> of file <pattern.prm>.*Energy step" -- pattern.prm
# A setting of the sampled search in a certified run is a warning, not ignored silently (a
# comparison switches Crossing search with --set); the audit of a search not run is an error.
expect 0 "warning: Time integration/Energy stepping/Samples per window: Time integration/Energy stepping/Crossing search = certified does not read it \(sampled does\); it is ignored\." -- run.prm -s "Output directory=unsampled" -s "Time integration/Energy stepping/Samples per window=16"
expect 0 "warning: Time integration/Energy stepping/Bisection steps: Time integration/Energy stepping/Crossing search = certified does not read it" -- run.prm -s "Output directory=unsampled" -s "Time integration/Energy stepping/Bisection steps=30"
grep -q "Bisection steps: Time integration/Energy stepping/Crossing search = certified does not read it" unsampled/summary.json || fail "the unread Bisection steps are not among summary.json's warnings"
expect 1 "Time integration/Energy stepping/Audit sampled search: audits the sampled search" -- run.prm -s "Time integration/Energy stepping/Audit sampled search=true"
expect 0 "completed" -- run.prm -s "Output directory=sampled" -s "Time integration/Energy stepping/Crossing search=sampled" -s "Time integration/Energy stepping/Samples per window=16"
grep -q "Samples per window" err.txt && fail "a sampled run warns of its own Samples per window: $(cat err.txt)"
# The same in JSON: the file and the entry's full path.
printf '{\n  "Output directory": "run",\n  "Time integration": {\n    "Energy stepping": { "Energy stepp": "1" }\n  }\n}\n' > unknown.json
expect 1 "^estep: error: File <unknown.json>: there is no entry <Time integration/Energy stepping/Energy stepp>" -- unknown.json
printf '{ "Time integration": { "Energy stepping": { "Energy step": "-1" } } }\n' > pattern.json
expect 1 "^estep: error: File <pattern.json>: Time integration/Energy stepping/Energy step: The string <-1> does not match the given pattern <\[Double 0\.\.\.MAX_DOUBLE" -- pattern.json
printf '{ "Time integration": { "Method": "leapfrog" } }\n' > selection.json
expect 1 "File <selection.json>: Time integration/Method: The string <leapfrog> does not match the given pattern <\[Selection arkode irk" -- selection.json
printf '{ "Time integration": { "Nope": { "End time": "1" } } }\n' > section.json
expect 1 "File <section.json>: there is no subsection <Time integration/Nope>" -- section.json
printf '{ "Time integration": { "End time": [1, 2] } }\n' > array.json
expect 1 "File <array.json>: Time integration/End time is a JSON array" -- array.json
printf '{ "Time integration": { "Energy step": "1e-3" } }\n' > renamed.json
expect 1 "File <renamed.json>: Time integration/Energy step is now Time integration/Energy stepping/Energy step\.$" -- renamed.json
printf '{ "Time integration": {\n  "End time": 1,\n}\n' > malformed.json
expect 1 "Line <3> of file <malformed.json>: not valid JSON: expected key string" -- malformed.json
# An entry set twice in one file (deal.II would keep the later value unseen), in .prm and
# .json; a file may set again what a file it includes sets.
printf 'set Output directory = run\nsubsection Time integration\n  set End time = 0.5\nend\nsubsection Time integration\n  set End time = 2\nend\n' > twice.prm
expect 1 "Line <6> of file <twice.prm>: Time integration/End time is set again \(first on line 3\)" -- twice.prm
printf 'include twice_base.prm\nsubsection Time integration\n  set End time = 0.5\nend\n' > amends.prm
printf 'set Output directory = amended\nsubsection Time integration\n  set End time = 2\nend\n' > twice_base.prm
expect 0 "completed at t = 0.5" -- amends.prm
printf '{ "Output directory": "a", "Output directory": "b" }\n' > twice.json
expect 1 "File <twice.json>: Output directory is given twice in one object" -- twice.json
# A file that sets nothing (emptied by mistake) does not run the default problem.
printf '# nothing yet\nsubsection Time integration\nend\n' > nothing.prm
expect 1 "The input file <nothing.prm> sets no entry" -- nothing.prm
printf '{}\n' > nothing.json
expect 1 "The input file <nothing.json> sets no entry" -- nothing.json
printf '<?xml version="1.0"?>\n<ParameterHandler><Output_20directory>x</Output_20dir' > malformed.xml
expect 1 "Line <2> of file <malformed.xml>: not valid XML: expected >" -- malformed.xml
# Entries of the earlier input layout: the message names where they went.
printf 'set Output directory = run\nsubsection Time integration\n  set Energy step = 1e-3\nend\n' > renamed.prm
expect 1 "Line <3> of file <renamed.prm>: Time integration/Energy step is now Time integration/Energy stepping/Energy step\.$" -- renamed.prm
expect 1 "Output/Field output interval is now Postprocessors/Field output/Interval, with field output in Postprocessors/List" -- run.prm -s "Output/Field output interval=1"
# An unknown plugin: one line with the valid names, and where a plugin of one's own comes from
# (not for other choices).
hint="A plugin of your own is known by its name once 'Additional shared libraries' names its library"
expect 1 "<leapfrog> does not match the given pattern <\[Selection arkode irk\|arkode midpoint\|energy momentum\|energy stepping\|explicit newmark\|ida bdf \]>\. $hint" -- run.prm -s "Time integration/Method=leapfrog"
expect 1 "<sponge>.*\[Selection neo-Hookean.*$hint" -- run.prm -s "Material/Model=sponge"
expect 1 "<history, spreadsheet>.*MultipleSelection contact monitor.*$hint" -- run.prm -s "Postprocessors/List=history, spreadsheet"
printf 'subsection Problem\n  set System = my system\nend\n' > my_system.prm
expect 1 "Line <2> of file <my_system.prm>: .*my system.*\[Selection argon cluster.*$hint" -- my_system.prm
expect 1 "<foo> does not match the given pattern <\[Selection none\|penalty\|impenetrability \]>\.$" -- run.prm -s "Contact/Mode=foo"
expect 1 "Postprocessors/List: <history> is listed twice" -- run.prm -s "Postprocessors/List=history, history"
# Plugin libraries: a missing one, one that registers a name taken already, one that registers
# nothing.
expect 1 "Additional shared libraries: cannot load <./missing_plugin.so>" -- run.prm -s "Additional shared libraries=./missing_plugin.so"
expect 1 "Additional shared libraries: <$ESTEP_DUPLICATE_PLUGIN>: Two time integrator plugins are registered under the name <energy stepping>\.$" -- run.prm -s "Additional shared libraries=$ESTEP_DUPLICATE_PLUGIN"
expect 1 "Additional shared libraries: <$ESTEP_NOT_A_PLUGIN> registers no plugin" -- run.prm -s "Additional shared libraries=$ESTEP_NOT_A_PLUGIN"
printf 'set Output directory = run\nsubsection Time integration\n  set Method = leapfrog\nend\n' > selection.prm
expect 1 "leapfrog.*Method" -- selection.prm
printf 'set Output directory = run\nsubsection Time integration\n  set End time = -1\nend\n' > times.prm
expect 1 "End time: must be larger than the start time" -- times.prm
printf 'set Output directory = run\nsubsection Argon cluster\n  set Initial velocities = 1, 2; 3, 4\nend\n' > counts.prm
# A body flung at 1e100 m/s: its energy overflows at the first history row, which is not written.
expect 2 "The run became unstable at t = 0.01: the energies T = .* and V = inf are not both finite" -- "$ESTEP_SOURCE_DIR/parameter_files/scene_ball_drop.prm" -s "Output directory=flung" -s "Time integration/End time=0.02" -s "Output/History interval=0.01" -s "Scene/Obstacles/Half-spaces=" -s "Contact/Mode=none" -s "Scene/Body 1/Initial velocity/Translational velocity=1e100, 0, 0"
[[ $(wc -l < flung/history.csv) == 2 ]] || fail "flung: history.csv holds rows beyond t = 0: $(cat flung/history.csv | cut -c1-80)"
# An energy step below the round-off of V: refused before the output directory is touched.
expect 1 "Energy step: h = 1e-300 is too small for the initial potential energy" -- "$ESTEP_SOURCE_DIR/parameter_files/scene_ball_drop.prm" -s "Output directory=tiny_h" -s "Time integration/Energy stepping/Energy step=1e-300"
[[ ! -e tiny_h ]] || fail "tiny_h: an output directory was written for a refused energy step"
# Two atoms 1e-25 apart: a finite energy, forces beyond double precision.
expect 1 "gradient of the potential energy of the lennard-jones cluster at its initial configuration is not finite \(component 0\): the forces there exceed double precision" -- "$ESTEP_SOURCE_DIR/parameter_files/argon_cluster.prm" -s "Output directory=run" -s "Argon cluster/Initial positions=0, 0; 1e-25, 0; 0.34, 0.17; 0.36, -0.21; -0.02, -0.40; -0.35, -0.16; -0.31, 0.21"
expect 1 "7 initial positions but 2 initial velocities" -- counts.prm
expect 1 "<run.txt> does not exist" -- run.txt
touch run.txt
expect 1 "must end in .prm" -- run.txt
expect 1 "--set \"Time integration/End time=x\".*<x>" -- run.prm --set "Time integration/End time=x"
expect 1 "Endtime" -- run.prm --set "Time integration/Endtime=1"
expect 1 "no subsection <Nope>" -- run.prm --set "Nope/End time=1"
expect 1 "expected the form" -- run.prm --set "End time"
expect 1 "needs an argument" -- run.prm --set
# Inputs that crashed deal.II's readers, and what they should say instead.
echo "include self.prm" > self.prm
expect 1 "Line <1> of file <self.prm>: including <self.prm> forms a cycle" -- self.prm
python3 -c "print('[' * 20000 + ']' * 20000)" > deep.json
expect 1 "deep.json> nests deeper than 64 levels" -- deep.json
printf '\xEF\xBB\xBFset Output directory = bom\nsubsection Time integration\n  set End time = 0.5\nend\n' > bom.prm
expect 0 "completed at t = 0.5" -- bom.prm
expect 1 "Argon cluster/Particle mass: must be positive\.$" -- run.prm -s "Argon cluster/Particle mass=0"
expect 1 "Argon cluster/Epsilon over Boltzmann constant: must be positive\.$" -- run.prm -s "Argon cluster/Epsilon over Boltzmann constant=0"
cube=("$ESTEP_SOURCE_DIR/parameter_files/spinning_cube.prm" -s "Elastic body/Mesh/Subdivisions=1"
      -s "Time integration/End time=0.1" -s "Postprocessors/List=history, step histogram, progress")
expect 1 "Function expression: <sqrt\(; 0; 0> cannot be evaluated: <Unexpected end of expression" -- "${cube[@]}" -s "Elastic body/Initial velocity/Type=function" -s "Elastic body/Initial velocity/Function expression=sqrt(; 0; 0"
expect 1 "Elastic body/Initial velocity/Function expression: <sqrt\(-1\); 0; 0> is -?nan at the point \([-0-9.e+, ]+\) \(component 0\)\.$" -- "${cube[@]}" -s "Elastic body/Initial velocity/Type=function" -s "Elastic body/Initial velocity/Function expression=sqrt(-1); 0; 0"
expect 1 "Elastic body/Mesh: the deal.II generator 'hyper_cubee' with arguments '0 : 1 : false' failed: hyper_cubee\(0 : 1 : false\) not implemented" -- "${cube[@]}" -s "Elastic body/Mesh/Type=deal.II" -s "Elastic body/Mesh/Generator=hyper_cubee"
# Arguments missing one part (colorize): how many the generator takes, before deal.II's pattern.
expect 1 "Elastic body/Mesh: the deal.II generator 'subdivided_hyper_rectangle' with arguments '2, 2, 2 : 0, 0, 0 : 1, 1, 1' failed: it takes 4 arguments separated by ':', and these are 3\. The string" -- "${cube[@]}" -s "Elastic body/Mesh/Type=deal.II" -s "Elastic body/Mesh/Generator=subdivided_hyper_rectangle" -s "Elastic body/Mesh/Generator arguments=2, 2, 2 : 0, 0, 0 : 1, 1, 1"
# Subdivisions that deal.II would read as 4294967295, or too many, are refused before it allocates
# (-1 took 14 GB in a minute; 4294967295 crashed it).
gen=(-s "Elastic body/Mesh/Type=deal.II" -s "Elastic body/Mesh/Generator=subdivided_hyper_rectangle")
expect 1 "Elastic body/Mesh: Generator arguments: the subdivisions <-1, 2, 2> of subdivided_hyper_rectangle must be positive integers\.$" -- "${cube[@]}" "${gen[@]}" -s "Elastic body/Mesh/Generator arguments=-1, 2, 2 : 0, 0, 0 : 1, 1, 1 : false"
expect 1 "Elastic body/Mesh: the deal.II generator 'subdivided_hyper_rectangle' with 0 refinements would make about 2.4e\+16 tetrahedra" -- "${cube[@]}" "${gen[@]}" -s "Elastic body/Mesh/Generator arguments=100000, 100000, 100000 : 0, 0, 0 : 1, 1, 1 : false"
expect 1 "Function expression: <1; 2> cannot be evaluated: The number of components \(3\) is not equal to the number of expressions \(2\)" -- "${cube[@]}" -s "Elastic body/Initial velocity/Type=function" -s "Elastic body/Initial velocity/Function expression=1; 2"
# Warnings about the input, which let the run go on: a tracked point far from its body, more
# threads than cores; and the system named as Problem/System names it.
expect 0 "estep: warning: Elastic body/Tracked point: the point 5, 5, 5 lies 6.9282 outside the body's bounding box \(sides up to 1\); the body's point nearest to it is tracked\.$" -- "${cube[@]}" -s "Elastic body/Tracked point=5,5,5" -s "Output directory=warned"
grep -q '"warnings": \["Elastic body/Tracked point: the point 5, 5, 5' warned/summary.json || fail "the tracked point's warning is not in summary.json"
expect 0 "estep: warning: Threads: 1000 threads on a machine of [0-9]+ cores" -- "${cube[@]}" --threads 1000
! grep -q "Tracked point" <("$ESTEP" "${cube[@]}" -s "Elastic body/Tracked point=0.5, 1.2, 1" 2>&1) || fail "a warning for a tracked point just off the body"
expect 0 "energy stepping on the argon cluster: completed" -- "$ESTEP_SOURCE_DIR/parameter_files/argon_cluster.prm" -s "Time integration/End time=1" -s "Output directory=argon"
grep -q '"system": "argon cluster"' argon/summary.json || fail "summary.json does not name the argon cluster as Problem/System does"
# Ball meshes: a mesh size that would make too many tetrahedra, or none (gmsh's message).
expect 1 "Elastic body/Mesh: the mesh size 1e-09 \(relative to the radius\) would make a ball of about 2.4246e\+28 tetrahedra, more than 1e\+08; it must be at least 0.00623563\.$" -- "${cube[@]}" -s "Elastic body/Mesh/Type=ball" -s "Elastic body/Mesh/Mesh size=1e-9"
balls=("$ESTEP_SOURCE_DIR/parameter_files/ball_collision.prm" -s "Postprocessors/List=history, contact monitor")
expect 1 "Colliding balls/Mesh size: gmsh could not mesh a ball with the mesh size 100 \(relative to the radius\): " -- "${balls[@]}" -s "Colliding balls/Mesh size=100"
expect 1 "Colliding balls/Mesh size: must be positive\.$" -- "${balls[@]}" -s "Colliding balls/Mesh size=0"
expect 1 "Contact: the elastic body problem has no contact" -- "${cube[@]}" -s "Contact/Mode=impenetrability"
expect 1 "Contact: the elastic body problem has no contact" -- "${cube[@]}" -s "Contact/Collision tolerance=1e-3"
# A subsection that only other problems read keeps its defaults.
expect 1 "Scene: Problem/System = elastic body does not read this subsection \(scene does\); a setting there would be ignored\.$" -- "${cube[@]}" -s "Scene/Gravity=0, 0, -9.8"
expect 1 "Contact: Problem/System = argon cluster does not read this subsection" -- run.prm -s "Contact/Self contact=true"
expect 1 "Material: Problem/System = argon cluster does not read this subsection" -- run.prm -s "Material/Density=5000"
expect 1 "Material: Problem/System = scene does not read this subsection \(colliding balls and elastic body do\); a setting there would be ignored\.$" -- "$ESTEP_SOURCE_DIR/parameter_files/scene_ball_drop.prm" -s "Material/Density=5000" -s "Output directory=scene_material"
# So does the subsection of a material model other than the chosen one, at any depth.
expect 1 "Material/Neo-Hookean quadratic volume: Material/Model = neo-Hookean does not read this subsection \(neo-Hookean quadratic volume does\); a setting there would be ignored\.$" -- "${cube[@]}" -s "Material/Neo-Hookean quadratic volume/Lambda=0.02"
expect 1 "Scene/Body 2/Material/Neo-Hookean quadratic volume: Scene/Body 2/Material/Model = neo-Hookean does not read this subsection" -- "$ESTEP_SOURCE_DIR/parameter_files/scene_colliding_balls.prm" -s "Scene/Body 2/Material/Neo-Hookean quadratic volume/Mu=0.02" -s "Output directory=scene_model"
# An integrator without constraint events is refused for impenetrable contact, between bodies and
# with obstacles, instead of letting the bodies pass into each other; the implicit methods have no
# Hessian for contact, which they say first.
expect 1 "^estep: error: Time integration/Method: explicit newmark cannot keep bodies apart by impenetrability constraints" -- "$ESTEP_SOURCE_DIR/parameter_files/ball_collision_impenetrable.prm" -s "Time integration/Method=explicit newmark" -s "Output directory=newmark_impenetrable"
expect 1 "^estep: error: Time integration/Method: explicit newmark cannot keep bodies apart by impenetrability constraints" -- "$ESTEP_SOURCE_DIR/parameter_files/scene_bar_impact.prm" -s "Contact/Mode=impenetrability" -s "Time integration/Method=explicit newmark" -s "Output directory=newmark_wall"
expect 1 "^estep: error: Time integration/Method: the implicit integrators need the Hessian \(tangent stiffness\) of the system, and the system <scene> provides none" -- "$ESTEP_SOURCE_DIR/parameter_files/scene_cantilever.prm" -s "Scene/Obstacles/Half-spaces=0, 0, -1, 0, 0, 1" -s "Contact/Mode=impenetrability" -s "Time integration/Method=ida bdf" -s "Output directory=implicit_wall"
# A collision tolerance near the length of a boundary edge would make the balls touch while apart.
expect 1 "^estep: error: Contact/Collision tolerance = 0.001 is not small against the shortest boundary edge of the bodies, 0\.[0-9]+: primitives closer than it count as touching; give at most" -- "$ESTEP_SOURCE_DIR/parameter_files/ball_collision_impenetrable.prm" -s "Contact/Collision tolerance=0.001" -s "Output directory=large_tolerance"
# The subsections of other time integrators (one shared by several) and of postprocessors
# missing from the List: a warning each, at the start and in summary.json, and the run goes on.
expect 0 "warning: Time integration/Explicit Newmark: Time integration/Method = energy stepping does not read this subsection \(explicit newmark does\); its settings are ignored\.$" -- run.prm -s "Time integration/Explicit Newmark/Time step=0.01" -s "Output directory=ignored"
grep -q '"warnings": \["Time integration/Explicit Newmark: Time integration/Method = energy stepping does not read' ignored/summary.json || fail "summary.json lacks the ignored integrator settings"
expect 0 "warning: Time integration/Implicit integrators: Time integration/Method = energy stepping does not read this subsection \(arkode irk, arkode midpoint, energy momentum and ida bdf do\)" -- run.prm -s "Time integration/Implicit integrators/Relative tolerance=1e-3" -s "Output directory=ignored"
expect 0 "warning: Postprocessors/Field output: set, but Postprocessors/List = history does not name field output, which reads it; its settings are ignored\.$" -- run.prm -s "Postprocessors/List=history" -s "Postprocessors/Field output/Interval=1" -s "Output directory=ignored"
# Entries that only other mesh or velocity types read, changed from their defaults (blanks
# aside): a warning each.
expect 0 "warning: Elastic body/Mesh/Upper corner: Elastic body/Mesh/Type = ball does not read it \(box does\); it is ignored\.$" -- "${cube[@]}" -s "Elastic body/Mesh/Type=ball" -s "Elastic body/Mesh/Upper corner=2, 2, 2" -s "Time integration/End time=0.01" -s "Output directory=unread_entries"
grep -q "Elastic body/Mesh/Subdivisions: Elastic body/Mesh/Type = ball does not read it (box does)" err.txt || fail "no warning for the box's subdivisions of a ball mesh: $(cat err.txt)"
expect 0 "warning: Elastic body/Initial velocity/Function expression: Elastic body/Initial velocity/Type = rigid motion does not read it \(function does\); it is ignored\.$" -- "${cube[@]}" -s "Elastic body/Initial velocity/Function expression=1; 0; 0" -s "Time integration/End time=0.01" -s "Output directory=unread_entries"
grep -q '"warnings": \[.*Elastic body/Initial velocity/Function expression: ' unread_entries/summary.json || fail "summary.json lacks the ignored velocity function"
expect 0 "completed" -- "${cube[@]}" -s "Elastic body/Mesh/Upper corner=1,1,  1" -s "Time integration/End time=0.01" -s "Output directory=unread_entries"
if grep -q "Upper corner" err.txt; then fail "an entry at its default but for blanks warns: $(cat err.txt)"; fi
# An adaptive implicit method whose smallest step exceeds its first one: refused, not a failed run.
expect 1 "Time integration/Implicit integrators/Minimum step: 10 exceeds the initial step of the adaptive methods \(Time step = 0.001\); it must be at most that\.$" -- run.prm -s "Time integration/Method=ida bdf" -s "Time integration/Implicit integrators/Minimum step=10"
expect 1 "Time integration/Implicit integrators/Minimum step: 10 exceeds the initial step" -- run.prm -s "Time integration/Method=arkode irk" -s "Time integration/Implicit integrators/Minimum step=10"
expect 0 "completed" -- run.prm -s "Time integration/Method=explicit newmark" -s "Time integration/Explicit Newmark/Time step=0.01" -s "Output directory=read"
if grep -q "warning" err.txt; then fail "a run that reads every subsection it sets warns: $(cat err.txt)"; fi
# A scene as --print-parameters prints it (one body, at its defaults) is a valid input.
"$ESTEP" --print-parameters -s "Problem/System=scene" > scene_defaults.prm
expect 0 "completed at t = 0.01" -- scene_defaults.prm -s "Contact/Mode=none" -s "Time integration/End time=0.01" -s "Output directory=scene_defaults"
# A run that fails at set-up leaves an earlier run in the same directory alone.
expect 1 "has no fields to write" -- run.prm -s "Postprocessors/List=history, step histogram, progress, field output" -s "Postprocessors/Field output/Interval=0.1"
cmp -s summary.before run/summary.json || fail "a failed run changed the output of an earlier run"

# A run that blows up: status unstable in summary.json, a clear message, exit code 2.
expect 2 "became unstable" -- run.prm -s "Time integration/Method=explicit newmark" -s "Time integration/Explicit Newmark/Time step=0.5" -s "Output directory=blowup"
grep -q '"status": "unstable"' blowup/summary.json || fail "summary.json of a blow-up lacks status unstable"
grep -q '"message": "The run became unstable' blowup/summary.json || fail "summary.json of a blow-up lacks the message"
if grep -Eqi "nan|inf" blowup/history.csv; then fail "history.csv of a blow-up holds non-finite values"; fi

# Times that floating point cannot step through, and runaway output intervals: input errors.
expect 1 "End time: the time span .* below the resolution" -- run.prm -s "Time integration/Start time=1e16" -s "Time integration/End time=1.000000000000001e16"
expect 1 "History interval: below the resolution" -- run.prm -s "Output/History interval=1e-300"
expect 1 "Time integration/Explicit Newmark/Time step: 1e-300 is below the resolution of the run's times" -- run.prm -s "Time integration/Method=explicit newmark" -s "Time integration/Explicit Newmark/Time step=1e-300"
expect 1 "Time integration/Implicit integrators/Time step: 1e-300 is below the resolution" -- run.prm -s "Time integration/Method=energy momentum" -s "Time integration/Implicit integrators/Time step=1e-300"
expect 1 "Field output/Interval: would write more than" -- "${cube[@]}" -s "Postprocessors/List=history, step histogram, progress, field output" -s "Postprocessors/Field output/Interval=1e-9"

# A run whose V has a round-off far above the energy step (Mu = 1e300) ends as stalled at once,
# exit code 3, naming the time, the energy step and the round-off (not a crawl, not a hang).
expect 3 "stalled at t = 0 with the energy step h = 1e-05: the round-off band of V along the flight, [0-9.e+]+, is not below half the energy step" -- "${cube[@]}" -s "Material/Neo-Hookean/Mu=1e300" -s "Output directory=stalled"
grep -q '"status": "stalled"' stalled/summary.json || fail "summary.json of a stalled run lacks status stalled"
# A stiff cube whose reflections return within the round-off band of their level: it completes.
expect 0 "completed at t = 0.1" -- "${cube[@]}" -s "Elastic body/Mesh/Subdivisions=2" -s "Material/Neo-Hookean/Mu=2e7" -s "Output directory=stiff"

# An energy step above the system's energy scale: a warning that says the results mean little.
expect 0 "warning: Time integration/Energy stepping/Energy step: h = 100 exceeds the initial energy scale" -- run.prm -s "Time integration/Energy stepping/Energy step=100" -s "Output directory=coarse"
grep -q '"warnings": \["Time integration/Energy stepping/Energy step: h = 100' coarse/summary.json || fail "summary.json lacks the coarse energy step's warning"
# A warning that arises during the run (energy-stepping held between two levels, the terrace
# offset study of doc/spinning_cube.md): at its end, and in summary.json.
expect 0 "warning: Time integration/Energy stepping/Energy step: all [0-9]+ level crossings were reflections, none climbed or descended" -- "$ESTEP_SOURCE_DIR/parameter_files/spinning_cube.prm" -s "Time integration/End time=3" -s "Time integration/Energy stepping/Energy step=3e-5" -s "Time integration/Energy stepping/Terrace offset=0.05" -s "Postprocessors/List=history" -s "Output directory=reflecting"
grep -q '"warnings": \["Time integration/Energy stepping/Energy step: all [0-9]* level crossings were reflections' reflecting/summary.json || fail "summary.json lacks the reflection warning"

# A run that conserves nothing but stays below the blow-up factor (velocity Verlet on argon far
# above its stable step): it completes with a warning naming the drift and the rule, also in
# summary.json. The reference Verlet run has none.
verlet=("$ESTEP_SOURCE_DIR/parameter_files/argon_cluster_verlet.prm" -s "Postprocessors/List=history")
expect 0 "warning: Time integration/Energy drift warning: the energy T \+ V drifted from its initial value by [0-9.]+ times the initial energy scale \|T\| \+ \|V\| = 13.17.* \(at t = [0-9.]+\), more than the 0.1 allowed" -- "${verlet[@]}" -s "Time integration/Explicit Newmark/Time step=0.2" -s "Time integration/End time=2" -s "Output directory=drift"
grep -q '"status": "completed"' drift/summary.json || fail "a drifting run does not say completed"
grep -q '"warnings": \["Time integration/Energy drift warning: the energy T + V drifted' drift/summary.json || fail "summary.json lacks the drift warning"
expect 0 "completed at t = 463.05" -- "${verlet[@]}" -s "Output directory=verlet"
if grep -q "warning" err.txt; then fail "the reference Verlet run warns: $(cat err.txt)"; fi
grep -q '"warnings": \[\]' verlet/summary.json || fail "summary.json of the reference Verlet run has warnings"

# A penalty that lets the bodies pass (eps is a compliance: 1e300 makes the contact energy
# vanish): the run stops when a body is deeper than an element inside the other, status
# penetrated, exit code 5.
expect 5 "A body passed through contact at t = 0.2[0-9]*: a boundary point of body 2 \(point [0-9]+\) lies 0.5[0-9]* inside body 1, deeper than the longest boundary edge 0.508[0-9]* of the two meshes; the penalty \(Contact/Penalty parameter = 1e\+300, smaller is stiffer\) is too soft to keep them apart\.$" -- "${balls[@]}" -s "Contact/Penalty parameter=1e300" -s "Time integration/End time=0.3" -s "Output directory=passed"
grep -q '"status": "penetrated"' passed/summary.json || fail "summary.json of a penetrated run lacks status penetrated"
# The same with the first ball passing into the second, twice its size: found that way round too.
expect 5 "A body passed through contact at t = 0.[0-9]*: a boundary point of body 1 \(point [0-9]+\) lies [0-9.]+ inside body 2" -- "${balls[@]}" -s "Contact/Penalty parameter=1e300" -s "Colliding balls/Size ratio=2" -s "Time integration/End time=0.6" -s "Output directory=passed_into_larger"
# A penalty whose energy in an element-deep intersection is below the energy step: a flight
# could carry the bodies through each other unseen; energy-stepping warns at the start.
expect 0 "warning: Time integration/Energy stepping/Energy step: h = 1000 exceeds the energy 129.* that the contact penalty stores in an intersection one boundary edge deep" -- "${balls[@]}" -s "Contact/Penalty parameter=1e-3" -s "Time integration/End time=0.001" -s "Output directory=soft"

# An output that cannot be written (history.csv on a full device): status failed, exit code 4,
# the file named; the summary written first says running, then failed.
mkdir -p full && ln -sf /dev/full full/history.csv
expect 4 "Cannot write the history file <full/history.csv>" -- run.prm -s "Output directory=full"
grep -q '"status": "failed"' full/summary.json || fail "summary.json of a failed write lacks status failed"

# An output directory that cannot be prepared (summary.json a directory, a file where the
# directory should be): exit code 4, the directory named, no temporary file left behind.
mkdir -p unprepared/summary.json
expect 4 "cannot prepare the output directory <unprepared>: Cannot rename <unprepared/summary.json.part>" -- run.prm -s "Output directory=unprepared"
[[ ! -e unprepared/summary.json.part ]] || fail "a failed summary left summary.json.part behind"
touch plain_file
expect 4 "^estep: error: cannot prepare the output directory <plain_file/run>: <plain_file/run>: Not a directory$" -- run.prm -s "Output directory=plain_file/run"
# An earlier output's name taken by a directory that is not empty: the path named, without the
# C++ library's wording, and the summary written first says failed.
mkdir -p taken/solution.pvd/keep
expect 4 "^estep: error: cannot prepare the output directory <taken>: <taken/solution.pvd>: Directory not empty$" -- run.prm -s "Output directory=taken"
grep -q '"status": "failed"' taken/summary.json || fail "an output directory that cannot be prepared: summary.json does not say failed"
# A regular file where field output's directory should be: one line naming it, exit code 4.
mkdir -p fields_a_file && touch fields_a_file/fields
expect 4 "^estep: error: Field output: cannot create the directory <fields_a_file/fields>: Not a directory\.$" -- "$ESTEP_SOURCE_DIR/parameter_files/spinning_cube.prm" -s "Elastic body/Mesh/Subdivisions=2" -s "Time integration/End time=0.1" -s "Output directory=fields_a_file"
[[ $(wc -l < err.txt) == 1 ]] || fail "fields a file: not one line: $(cat err.txt)"

# Field output on a device that fills up (a file size limit of 64 KB, whose SIGXFSZ estep
# ignores): exit code 4, the file named, no crash at exit, and no partial snapshot left behind.
# The HDF5 mesh file fits, its first snapshot does not; the vtu snapshot does not.
cat > limited <<EOF
#!/usr/bin/env bash
ulimit -f 64
exec "$ESTEP" "\$@"
EOF
chmod +x limited
ESTEP=./limited expect 4 "Field output: cannot write <body1/[a-z_]+> into the HDF5 file <limited_h5/fields/solution-00000\.h5>" -- "$ESTEP_SOURCE_DIR/parameter_files/spinning_cube.prm" -s "Elastic body/Mesh/Subdivisions=4" -s "Time integration/End time=0.1" -s "Postprocessors/Field output/Format=hdf5" -s "Output directory=limited_h5"
[[ -f limited_h5/fields/mesh.h5 && ! -e limited_h5/fields/solution-00000.h5 ]] || fail "a failed HDF5 snapshot left: $(ls limited_h5/fields)"
# history.csv on such a device: the row that did not fit is not left cut in the middle.
ESTEP=./limited expect 4 "Writing a row of the history file <limited_history/history.csv> failed" -- "$ESTEP_SOURCE_DIR/parameter_files/spinning_cube.prm" -s "Elastic body/Mesh/Subdivisions=2" -s "Time integration/End time=5" -s "Output/History interval=1e-4" -s "Postprocessors/List=history" -s "Output directory=limited_history"
[[ $(tail -c 1 limited_history/history.csv | od -An -c | tr -d ' ') == '\n' ]] || fail "history.csv on a full device ends inside a row"
awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad }' limited_history/history.csv || fail "history.csv on a full device has a row of another length"
# Field output beside that history: the series lists every snapshot written before the failure
# (it is rewritten at most once a second during the run, and at its end, failed or not).
ESTEP=./limited expect 4 "Writing a row of the history file <limited_series/history.csv> failed" -- "$ESTEP_SOURCE_DIR/parameter_files/spinning_cube.prm" -s "Elastic body/Mesh/Subdivisions=2" -s "Time integration/End time=5" -s "Output/History interval=1e-4" -s "Postprocessors/List=history, field output" -s "Postprocessors/Field output/Interval=0.01" -s "Output directory=limited_series"
snapshots=$(ls limited_series/fields | grep -c "\.vtu$")
listed=$(grep -c "<DataSet" limited_series/solution.pvd)
[[ $snapshots -gt 1 && $listed == "$snapshots" ]] || fail "after a failure, solution.pvd lists $listed of $snapshots snapshots"
# A checkpoint that does not fit: no partial checkpoint left behind, the summary says failed, and
# the cause is the last line, an error.
ESTEP=./limited expect 4 "Writing the checkpoint <limited_checkpoint/checkpoint.bin.part> failed: File too large" -- "$ESTEP_SOURCE_DIR/parameter_files/quick_start.prm" -s "Output/Checkpoint interval=1" -s "Time integration/End time=2" -s "Postprocessors/List=history" -s "Output directory=limited_checkpoint"
[[ ! -e limited_checkpoint/checkpoint.bin.part ]] || fail "a checkpoint that did not fit left its partial file"
grep -q '"status": "failed"' limited_checkpoint/summary.json || fail "a checkpoint that did not fit: the summary does not say failed"
tail -n 1 err.txt | grep -q "^estep: error: Writing the checkpoint" || fail "a checkpoint that did not fit: the cause is not the last line: $(cat err.txt)"
ESTEP=./limited expect 4 "Field output: cannot write <limited_vtu/fields/solution-00000\.vtu>" -- "$ESTEP_SOURCE_DIR/parameter_files/spinning_cube.prm" -s "Elastic body/Mesh/Subdivisions=6" -s "Time integration/End time=0.1" -s "Output directory=limited_vtu"
[[ -z $(ls limited_vtu/fields) ]] || fail "a failed vtu snapshot left: $(ls limited_vtu/fields)"
grep -q '"status": "failed"' limited_vtu/summary.json || fail "summary.json of a failed field output lacks status failed"

# SIGTERM ends a run after its current step with its summary (status interrupted), exit 143.
"$ESTEP" run.prm -s "Output directory=killed" -s "Time integration/End time=1e7" > /dev/null 2>&1 &
pid=$!
for _ in $(seq 50); do grep -q '"status": "running"' killed/summary.json 2> /dev/null && break; sleep 0.1; done
sleep 0.3
kill -TERM $pid
wait $pid
rc=$?
[[ $rc == 143 ]] || fail "a run ended by SIGTERM exited with $rc, expected 143"
grep -q '"status": "interrupted"' killed/summary.json || fail "summary.json of an interrupted run lacks status interrupted"
# log.txt ends with the last progress line (no time left) and why the run ended.
tail -n 2 killed/log.txt | head -n 1 | grep -Eq "s elapsed, interrupted$" || fail "log.txt of an interrupted run does not say so: $(tail -n 2 killed/log.txt)"
tail -n 1 killed/log.txt | grep -q "^estep: Interrupted by signal 15 at t = " || fail "log.txt of an interrupted run does not say why: $(tail -n 1 killed/log.txt)"

# The ccd subcommand has its own help.
expect 0 "estep ccd FILE_OR_DIRECTORY" -- ccd --help

# The colliding balls through the application (explicit Newmark with penalty contact).
expect 0 "completed at t = 0.01" -- "$ESTEP_SOURCE_DIR/parameter_files/ball_collision_newmark.prm" \
  -s "Output directory=balls" -s "Time integration/End time=0.01"
grep -q '"cells per ball": 898' balls/summary.json || fail "the ball mesh is not the documented one"
grep -q "V1_x" balls/history.csv || fail "history.csv of the balls lacks the body velocities"

# No progress line when standard error is not a terminal; forced on, it appears.
"$ESTEP" run.prm -s "Output directory=quiet" 2> quiet.err > /dev/null
[[ ! -s quiet.err ]] || fail "something was written to a non-terminal standard error: $(cat quiet.err)"

echo "$((failures == 0 ? 1 : 0)) passed, $failures failed"
[[ $failures == 0 ]]
