#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build of the library, tools and tests, then the
# whole suite under the sanitizers (any report fails the run: -fno-sanitize-recover=all).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
source scripts/compiler_cache.sh
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPLATEBALL_SANITIZE=ON \
      -DPLATEBALL_BUILD_BENCHMARKS=OFF -DPLATEBALL_WERROR=ON "${compiler_cache[@]}"
cmake --build build-asan -j "$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" --timeout 1800
