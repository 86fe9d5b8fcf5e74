#!/usr/bin/env bash
# Install estep into a temporary prefix, build the user plugins of doc/example_project against the
# installed package (find_package(estep), estep_setup_plugin()), check that a Debug build of them
# would link estep's deal.II, and run them through the installed estep command: the spring problem by energy-stepping (completed, the terraced energy and the orbit's
# radius kept), then by the plugin integrator with the plugin postprocessor, and with the H1 norm
# on a cube on 1 and 2 MPI processes (the same norm); the plugin integrator is refused for
# impenetrable contact.
set -eu
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$ESTEP_BINARY_DIR" --prefix "$work/prefix" > "$work/install.log"
test -x "$work/prefix/bin/estep"
"$work/prefix/bin/estep" --version
cmake -S "$ESTEP_SOURCE_DIR/doc/example_project" -B "$work/build" \
  -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log" ||
  { cat "$work/configure.log"; exit 1; }
cmake --build "$work/build" > "$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }
# A Debug build of the plugins links the deal.II that estep links (the release library), not
# deal.II's debug library beside it: configured only, its link line is read.
cmake -S "$ESTEP_SOURCE_DIR/doc/example_project" -B "$work/debug" -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure_debug.log" ||
  { cat "$work/configure_debug.log"; exit 1; }
link_line=$(cat "$work/debug/CMakeFiles/example_plugins.dir/link.txt")
case $link_line in
  *libdeal.ii.g.so*) echo "a Debug build of the plugins links deal.II's debug library: $link_line"; exit 1 ;;
  *libdeal.ii.so*) ;;
  *) echo "the plugins link no deal.II: $link_line"; exit 1 ;;
esac
cd "$work/build"
"$work/prefix/bin/estep" "$ESTEP_SOURCE_DIR/doc/example_project/spring.prm" \
  -s "Postprocessors/List=history, step histogram"
"$work/prefix/bin/estep" "$ESTEP_SOURCE_DIR/doc/example_project/spring.prm" \
  -s "Postprocessors/List=history, max speed" -s "Output directory=euler_output" \
  -s "Time integration/Method=symplectic euler" \
  -s "Time integration/Symplectic Euler/Time step=1e-3"
# --help lists the plugins of the libraries the input names.
"$work/prefix/bin/estep" --help "$ESTEP_SOURCE_DIR/doc/example_project/spring.prm" > help.txt
grep -q "^  Problem/System: .*spring" help.txt || { cat help.txt; echo "--help does not list spring"; exit 1; }
# On 2 MPI processes, the plugin integrator, which leaves dense_state() to its default (a
# collective evaluation of V), with the H1 norm, which asks for it: the run completes, with the
# norm of the run on one process.
h1=("$work/prefix/bin/estep" "$ESTEP_SOURCE_DIR/parameter_files/quick_start.prm"
  -s "Additional shared libraries=./libexample_plugins.so" -s "Elastic body/Mesh/Subdivisions=3"
  -s "Time integration/Method=symplectic euler" -s "Time integration/Symplectic Euler/Time step=0.05"
  -s "Time integration/End time=1" -s "Postprocessors/List=history, h1 norm")
"${h1[@]}" -s "Output directory=h1_one" > h1_one.log
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # CI runs as root
timeout 120 "$MPIEXEC" --bind-to none --oversubscribe -np 2 "${h1[@]}" -s "Output directory=h1_two" \
  > h1_two.log 2>&1 || { cat h1_two.log; echo "the H1 norm on 2 processes failed"; exit 1; }
python3 -c '
import json
one, two = (json.load(open(d + "/summary.json")) for d in ("h1_one", "h1_two"))
assert two["status"] == "completed" and two["MPI processes"] == 2, two["status"]
assert one["h1 norm"] == two["h1 norm"], (one["h1 norm"], two["h1 norm"])
'
# A plugin integrator that does not follow constraint events is refused for impenetrable contact,
# through which it would step, before any output.
if "$work/prefix/bin/estep" "$ESTEP_SOURCE_DIR/parameter_files/ball_collision_impenetrable.prm" \
  -s "Additional shared libraries=./libexample_plugins.so" \
  -s "Time integration/Method=symplectic euler" -s "Output directory=euler_impenetrable" \
  2> refusal.txt; then
  echo "symplectic euler ran with impenetrable contact"; exit 1
fi
grep -q "^estep: error: Time integration/Method: symplectic euler cannot keep bodies apart by impenetrability constraints" refusal.txt ||
  { cat refusal.txt; exit 1; }
test ! -e euler_impenetrable
python3 - <<'PY'
import csv, json
s = json.load(open("spring_output/summary.json"))
assert s["status"] == "completed", s["status"]
assert s["system"] == "spring", s["system"]
drift = s["energies"]["terraced energy drift"]
assert drift < 1e-12, f"terraced energy drift {drift}"
assert s["counters"]["steps"] > 100, s["counters"]
radii = [float(row["radius"]) for row in csv.DictReader(open("spring_output/history.csv"))]
assert len(radii) == 21 and max(abs(r - 1) for r in radii) < 1e-2, radii
e = json.load(open("euler_output/summary.json"))
assert e["status"] == "completed" and e["method"] == "symplectic euler", e["status"]
assert e["counters"]["steps"] == 10000, e["counters"]
# |v| = 1 on the circle; symplectic Euler's orbit stays within O(dt) of it.
assert abs(e["max speed"]["value"] - 1) < 2e-3, e["max speed"]
assert e["energies"]["total energy drift"] < 2e-3, e["energies"]
print(f"the plugins ran through the installed estep: {s['counters']['steps']} steps, "
      f"terraced energy drift {drift:.1e}, radius within {max(abs(r - 1) for r in radii):.1e} of 1")
PY
