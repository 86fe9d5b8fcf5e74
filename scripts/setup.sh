#!/usr/bin/env bash
# Set up estep on Debian 12: install the Debian packages it needs (only those missing), then
# configure and build in Release. Idempotent: quick when everything is already there.
#
#   bash scripts/setup.sh             install what is missing, configure, build
#   bash scripts/setup.sh --example   ... then run the default example (the quick start)
#   bash scripts/setup.sh --test      ... then run the default test tier with ctest
#
# Environment: ESTEP_BUILD_DIR (default: build/ in the source tree), ESTEP_JOBS (default: the
# number of cores).
set -euo pipefail

source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${ESTEP_BUILD_DIR:-$source_dir/build}
jobs=${ESTEP_JOBS:-$(nproc)}
action=${1:-build}

# libdeal.ii-dev brings deal.II 9.4 with Trilinos, SUNDIALS, HDF5, gmsh, CGAL and MPI; numdiff
# is expected by deal.II's test tools; GoogleTest for the tests, Google Benchmark for the
# benchmarks, clang-format (14 on Debian 12) for the formatting check, Python with matplotlib
# for the plotting and study scripts.
packages=(libdeal.ii-dev cmake g++ make numdiff libgtest-dev libbenchmark-dev clang-format
          python3 python3-matplotlib python3-numpy)

packages_to_install=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    packages_to_install+=("$package")
  fi
done

if ((${#packages_to_install[@]})); then
  echo "estep setup: installing ${packages_to_install[*]}"
  sudo=""
  if [[ $(id -u) -ne 0 ]]; then
    sudo="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${packages_to_install[@]}"
fi

cmake -S "$source_dir" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build_dir" -j "$jobs"

case $action in
  build) ;;
  --example)
    cd "$source_dir"
    "$build_dir/bin/estep" parameter_files/quick_start.prm
    ;;
  --test)
    cd "$build_dir"
    ctest -LE "paper|long|mutation" -j "$jobs" --output-on-failure
    ;;
  *)
    echo "estep setup: unknown action <$action> (use --example or --test)" >&2
    exit 1
    ;;
esac
