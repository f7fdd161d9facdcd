#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) and runs each for a bounded time.
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET]   (default 30)
#        scripts/fuzz.sh --ci                    (what CI runs: a deterministic run, seed 1, a fixed
#                                                 number of inputs per target, fresh corpus, each
#                                                 target also capped at 120 s)
# -g1 (line tables) is enough for the crash reports and builds faster than -g.
# Longer exploratory runs: scripts/fuzz.sh 3600. Crashes are written to build-fuzz/crashes/<target>/; copy each
# into fuzz/regressions/<target>/ so tests/fuzz_regression_test.cc replays it forever.
set -euo pipefail
cd "$(dirname "$0")/.."
ci_mode=0
if [[ "${1:-}" == "--ci" ]]; then
  ci_mode=1
  seconds=120
else
  seconds="${1:-30}"
fi
declare -A ci_runs=([problem_reader_fuzzer]=20000 [solve_entries_fuzzer]=1500 [reach_fuzzer]=300 [isoparallel_fuzzer]=100
                   [steer_fuzzer]=150 [view_input_fuzzer]=1000)
bash scripts/setup.sh
if ! command -v clang++ >/dev/null; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq clang libclang-rt-14-dev
fi
dpkg-query -W -f='${Status}' libclang-rt-14-dev 2>/dev/null | grep -q "install ok installed" || \
  { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libclang-rt-14-dev; }
source scripts/compiler_cache.sh
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPLATEBALL_FUZZ=ON \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
      -DPLATEBALL_BUILD_TESTS=OFF -DPLATEBALL_BUILD_BENCHMARKS=OFF -DPLATEBALL_BUILD_TOOLS=OFF "${compiler_cache[@]}"
cmake --build build-fuzz -j "$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
for fuzzer in build-fuzz/fuzz/*_fuzzer; do
  name=$(basename "$fuzzer")
  corpus=build-fuzz/corpus/$name
  extra=()
  if ((ci_mode)); then
    rm -rf "$corpus"
    extra=(-seed=1 -runs="${ci_runs[$name]:-2000}")
  fi
  mkdir -p "$corpus" "build-fuzz/crashes/$name"
  seeds=(fuzz/seeds/$name)
  [[ "$name" == problem_reader_fuzzer || "$name" == steer_fuzzer ]] && seeds+=(problems)
  [[ -d fuzz/regressions/$name ]] && seeds+=(fuzz/regressions/$name)
  echo "fuzz: $name for ${seconds}s"
  if ! "$fuzzer" "${extra[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
        -artifact_prefix="build-fuzz/crashes/$name/" "$corpus" "${seeds[@]}" 2>"build-fuzz/$name.log"; then
    echo "fuzz: $name FOUND A FAILURE:"; tail -60 "build-fuzz/$name.log"; status=1
  else
    grep -E "stat::number_of_executed_units|Done" "build-fuzz/$name.log" | tail -2
  fi
done
exit $status
