#!/usr/bin/env bash
# Sets up and runs the main job: isoparallel_solve on the paper's Figure 7 problem (extra arguments
# are passed to isoparallel_solve). Installs and builds only what that needs (the library and the
# isoparallel_solve target; no tests, benchmarks, Python module or browser view): scripts/test.sh
# builds everything else into the same build/ directory.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --main
bash scripts/build.sh --main > build.log 2>&1 || { tail -50 build.log; exit 1; }
./build/isoparallel_solve "$@"
