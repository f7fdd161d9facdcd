#!/usr/bin/env bash
# CI, after scripts/test.sh (which runs the notebooks and the doc-comment check in ctest): the
# documentation site with warnings as errors and the gallery's examples executed. With --pip, also
# the Python package built by pip (offline, Debian's setuptools) into a scratch directory and
# imported: a second build of the library (about 10 minutes on 2 cores), so CI leaves it out.
# Prints the time of each step.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
cmake --build build --target docs
echo "docs.sh: documentation site built in $((SECONDS - start)) s (build/docs/html/index.html)"
[[ ${1:-} == --pip ]] || exit 0
start=$SECONDS
target=$(mktemp -d)
trap 'rm -rf "$target"' EXIT
# The same compile flags as scripts/build.sh's build/, through the same compiler cache.
source scripts/compiler_cache.sh
PLATEBALL_CMAKE_ARGS="-DPLATEBALL_WERROR=ON" \
  /usr/bin/python3 -m pip install . --no-build-isolation --no-deps --no-index --target "$target" -q
(cd "$target" && PYTHONPATH="$target" /usr/bin/python3 -c \
  "import plateball as pb; s = pb.join(model=pb.BallModel(2.0), start=(1.0471975511965976, 0.4, 0.1), target=(0.05, 0)); assert s.status == 'converged', s.status; print('docs.sh: pip-installed plateball', pb.__version__, 'joins:', s.status)")
echo "docs.sh: pip install and import in $((SECONDS - start)) s"
