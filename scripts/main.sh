#!/usr/bin/env bash
# Sets everything up and runs the main job: isoparallel_solve on the paper's Figure 7 problem
# (extra arguments are passed to isoparallel_solve).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh > build.log 2>&1 || { tail -50 build.log; exit 1; }
./build/isoparallel_solve "$@"
