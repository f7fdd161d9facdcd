#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build of the library, tools and tests, then the
# whole suite under the sanitizers (any report fails the run: -fno-sanitize-recover=all).
# -g1: line tables only, enough for the reports' stack traces, and a faster build than full -g.
# The browser test is left out: it tests the view page's JavaScript in Chromium, which the sanitizers
# do not see (the `plateball view` runs that write its pages are the cli.view tests, which run here).
# So are six statistical sweeps that repeat one computation over 200 seeds or thousands of sampled
# parameters to measure a rate or a worst case (the Release suite runs them): one pass of that code
# is what the sanitizers need, and the suite's other identify and certificate tests make it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
source scripts/compiler_cache.sh
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
      -DPLATEBALL_SANITIZE=ON \
      -DPLATEBALL_BUILD_BENCHMARKS=OFF -DPLATEBALL_WERROR=ON "${compiler_cache[@]}"
cmake --build build-asan -j "$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
sweeps='InAbout95PercentOfSeeds$|^IsoparallelCertifyJacobian\.(JacobianHoldsItsMarginAtHighRates|ResidualIsWithinItsErrorBoundAtHighRatesAndLengths)$'
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" --timeout 1800 --label-exclude browser --exclude-regex "$sweeps"
