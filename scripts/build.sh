#!/usr/bin/env bash
# Configures and builds plateball (Release, warnings on) into ./build: everything (tests, benchmarks,
# Python module where found), or with `--main` only the isoparallel_solve target of the main job.
# Further arguments go to the configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/compiler_cache.sh
if [[ ${1:-} == --main ]]; then
  shift
  # Without the tests, benchmarks and Python module, so that configuring needs none of their packages.
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPLATEBALL_WERROR=ON "${compiler_cache[@]}" -DPLATEBALL_BUILD_TESTS=OFF \
        -DPLATEBALL_BUILD_BENCHMARKS=OFF -DPLATEBALL_BUILD_PYTHON=OFF "$@"
  cmake --build build -j "$(nproc)" --target isoparallel_solve
else
  # Everything back on after a `--main` build (-U: the Python module's default is recomputed).
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPLATEBALL_WERROR=ON "${compiler_cache[@]}" -DPLATEBALL_BUILD_TESTS=ON \
        -DPLATEBALL_BUILD_BENCHMARKS=ON -UPLATEBALL_BUILD_PYTHON "$@"
  cmake --build build -j "$(nproc)"
fi
