#!/usr/bin/env bash
# CI, after scripts/test.sh (which runs the notebooks and the doc-comment check in ctest): the
# documentation site with warnings as errors and the gallery's examples executed. With --pip, also
# scripts/pip_check.sh: the Python package installed by pip into a scratch virtual environment,
# offline with Debian's packages, and imported. That is a second build of the library (13 min of CPU
# with an empty compiler cache), so CI leaves it out. Prints the time of each step.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
cmake --build build --target docs
echo "docs.sh: documentation site built in $((SECONDS - start)) s (build/docs/html/index.html)"
[[ ${1:-} == --pip ]] || exit 0
bash scripts/pip_check.sh
