#!/usr/bin/env bash
# Install estep into a temporary prefix, then build and run the user project of
# doc/example_project against the installed package (find_package(estep), estep::estep).
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
"$work/build/spring"
echo "the installed package works"
