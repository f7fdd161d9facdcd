#!/usr/bin/env bash
# Configures and builds plateball (Release, warnings on) into ./build.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/compiler_cache.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPLATEBALL_WERROR=ON "${compiler_cache[@]}" "$@"
cmake --build build -j "$(nproc)"
