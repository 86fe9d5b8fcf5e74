#!/usr/bin/env bash
# Set up estep on Debian 12: install the Debian packages it needs (only those missing), then
# configure and build in Release. Idempotent: quick when everything is already there.
#
#   bash scripts/setup.sh             install what is missing, configure, build
#   bash scripts/setup.sh --example   ... then run the default example (the quick start)
#   bash scripts/setup.sh --test      ... then run the default test tier with ctest
#   bash scripts/setup.sh --sanitize  configure and build with AddressSanitizer and
#                                     UndefinedBehaviorSanitizer in build-asan/ instead (no
#                                     Release build), then run the default tier there
#   bash scripts/setup.sh --fuzz      also install clang 14 with libFuzzer, configure and build
#                                     the fuzz drivers in build-fuzz/ instead, run ctest -L fuzz
#
# Environment: ESTEP_BUILD_DIR (default: build/, build-asan/ or build-fuzz/ in the source tree),
# ESTEP_JOBS (default: the number of cores), ESTEP_FUZZ_RUNS (inputs per fuzz driver, default
# 100000).
set -euo pipefail

source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
jobs=${ESTEP_JOBS:-$(nproc)}
action=${1:-build}
case $action in
  --sanitize) build_dir=${ESTEP_BUILD_DIR:-$source_dir/build-asan} ;;
  --fuzz) build_dir=${ESTEP_BUILD_DIR:-$source_dir/build-fuzz} ;;
  *) build_dir=${ESTEP_BUILD_DIR:-$source_dir/build} ;;
esac
# The tiers outside the default one: long runs, the figures, the mutation suite, the fuzzers.
default_tier=(-LE "paper|long|mutation|fuzz")

# libdeal.ii-dev brings deal.II 9.4 with Trilinos, SUNDIALS, HDF5, gmsh, CGAL and MPI (and
# openmpi-bin Open MPI's launcher, mpirun, for the runs on several processes); numdiff
# is expected by deal.II's test tools; GoogleTest for the tests, Google Benchmark for the
# benchmarks, clang-format (14 on Debian 12) for the formatting check, Python with matplotlib
# for the plotting and study scripts, h5py for the tests that read HDF5 output.
packages=(libdeal.ii-dev openmpi-bin cmake g++ make numdiff libgtest-dev libbenchmark-dev clang-format
          python3 python3-matplotlib python3-numpy python3-h5py)
if [[ $action == --fuzz ]]; then
  # clang 14 and its runtime libraries: libFuzzer and the sanitizers.
  packages+=(clang-14 libclang-rt-14-dev)
fi

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

configuration=(-DCMAKE_BUILD_TYPE=Release)
case $action in
  --sanitize) configuration+=(-DESTEP_SANITIZE=ON) ;;
  --fuzz)
    configuration+=(-DCMAKE_CXX_COMPILER=clang++-14 -DESTEP_SANITIZE=ON -DESTEP_BUILD_FUZZERS=ON
                    -DESTEP_BUILD_TESTS=OFF -DESTEP_BUILD_BENCHMARKS=OFF
                    -DESTEP_FUZZ_RUNS="${ESTEP_FUZZ_RUNS:-100000}")
    ;;
esac
cmake -S "$source_dir" -B "$build_dir" "${configuration[@]}"
cmake --build "$build_dir" -j "$jobs"

case $action in
  build) ;;
  --example)
    cd "$source_dir"
    "$build_dir/bin/estep" parameter_files/quick_start.prm
    ;;
  --test | --sanitize)
    cd "$build_dir"
    ctest "${default_tier[@]}" -j "$jobs" --output-on-failure
    ;;
  --fuzz)
    cd "$build_dir"
    ctest -L fuzz -j "$jobs" --output-on-failure
    ;;
  *)
    echo "estep setup: unknown action <$action> (use --example, --test, --sanitize or --fuzz)" >&2
    exit 1
    ;;
esac
