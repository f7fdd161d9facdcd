#!/usr/bin/env bash
# The Python package as a user installs it without a Python registry: Debian's packages only
# (installed with apt-get when missing), a fresh virtual environment of Debian's /usr/bin/python3 that
# sees Debian's NumPy (--system-site-packages), and `pip install --no-build-isolation --no-index .`,
# which builds the library and the extension with CMake (setup.py) into build/pip-<python tag>/.
# Then, from outside the source tree, the installed module is imported from the environment and
# solves a join and a 64-impulse plan. Prints the time of each step; exits non-zero on any failure.
#   bash scripts/pip_check.sh            # the environment in a scratch directory, removed afterwards
#   bash scripts/pip_check.sh --keep DIR # the environment in DIR (created; kept for use)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
start=$SECONDS

# What `pip install .` needs: the library's build dependencies (scripts/setup.sh --main) and
# Debian's Python, venv, pip, setuptools, wheel, pybind11 and NumPy.
bash scripts/setup.sh --main
packages=(python3 python3-dev python3-venv python3-pip python3-setuptools python3-wheel python3-pybind11
          pybind11-dev python3-numpy)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "pip_check: installing ${missing[*]}"
  sudo_cmd=()
  [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
echo "pip_check: Debian packages present ($((SECONDS - start)) s)"

if [[ ${1:-} == --keep ]]; then
  venv=${2:?"--keep needs a directory"}
  mkdir -p "$venv"
  venv=$(cd "$venv" && pwd)
else
  venv=$(mktemp -d)
  trap 'rm -rf "$venv"' EXIT
fi
step=$SECONDS
/usr/bin/python3 -m venv --system-site-packages "$venv"
# The same compile flags as scripts/build.sh's build/, through its compiler cache when there is one.
source scripts/compiler_cache.sh
# --no-index: no registry is asked (NumPy, the only dependency, is Debian's, seen through
# --system-site-packages); --isolated: no pip configuration or PIP_* variable (e.g. a PIP_FIND_LINKS
# wheel folder) either; --no-build-isolation: Debian's setuptools builds the package.
PLATEBALL_CMAKE_ARGS="-DPLATEBALL_WERROR=ON" \
  "$venv/bin/python" -m pip install --isolated --no-build-isolation --no-index -q .
echo "pip_check: pip install into $venv in $((SECONDS - step)) s"

# Outside the source tree, so that only the installed package can be imported.
cd "$venv"
"$venv/bin/python" - "$venv" "$root/problems/circle.json" <<'PY'
import pathlib
import sys

import plateball as pb

venv, problem_file = pathlib.Path(sys.argv[1]), sys.argv[2]
where = pathlib.Path(pb.__file__).resolve()
assert venv in where.parents, f"plateball imported from {where}, not from the environment {venv}"
s = pb.join(model=pb.BallModel(2.0), start=(1.0471975511965976, 0.4, 0.1), target=(0.05, 0))
assert s.status == "converged", s.status
problem = pb.load_problem(problem_file)
plan = pb.plan(*pb.plan_setup_for(problem))
assert plan.usable and plan.delta_omega.shape == (64, 3), (plan.status, plan.delta_omega.shape)
print(f"pip_check: plateball {pb.__version__} from {where.parent}: join {s.status} (t = {s.t:.6f}), "
      f"plan of circle.json {plan.status}, measured error {plan.measured_error:.4g}")
PY
echo "pip_check: done in $((SECONDS - start)) s"
