#!/usr/bin/env bash
# doc/parameters.prm, the parameters reference, is what `estep --print-parameters` prints.
# Regenerate it with: build/bin/estep --print-parameters > doc/parameters.prm
set -u
if ! diff <("$ESTEP" --print-parameters) "$ESTEP_SOURCE_DIR/doc/parameters.prm"; then
  echo "doc/parameters.prm is out of date: build/bin/estep --print-parameters > doc/parameters.prm"
  exit 1
fi
echo "doc/parameters.prm is up to date"
