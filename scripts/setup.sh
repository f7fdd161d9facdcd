#!/usr/bin/env bash
# Installs plateball's build and test dependencies from Debian's packages, only when missing.
# Idempotent; needs root (or sudo) on Debian 12. `--main`: only what the main job needs (the library
# and isoparallel_solve; scripts/main.sh), without the test, Python, browser and documentation tools.
set -euo pipefail
main_only=0
[[ ${1:-} == --main ]] && main_only=1
packages=(build-essential cmake pkg-config libeigen3-dev libceres-dev libnlopt-cxx-dev libboost-dev
          libboost-math-dev nlohmann-json3-dev libcli11-dev)
if ((!main_only)); then
packages+=(libgtest-dev libgmock-dev libbenchmark-dev)
packages+=(python3 python3-jsonschema)  # output contract: schema validation (tests/scripts/validate_schemas.py)
packages+=(python3-dev python3-pybind11 pybind11-dev python3-numpy python3-pytest python3-matplotlib)  # Python bindings, pytest, gallery
packages+=(libopenmpi-dev openmpi-bin)  # montecarlo: optional MPI component
packages+=(libmujoco-dev)  # rig: optional MuJoCo digital twin (C API; Debian has no Python bindings)
packages+=(libompl-dev)  # optional exact steering for OMPL's control-based planners (OMPL 1.5)
packages+=(chromium)  # view: Debian's Chromium for the browser tests of `plateball view`
command -v npm >/dev/null 2>&1 || packages+=(nodejs npm)  # view: npm ci in web/ (below)
packages+=(ccache)  # compiler cache for scripts/build.sh, sanitize.sh and fuzz.sh (scripts/compiler_cache.sh)
packages+=(clang-format)  # the format check (tests/scripts/check_format.sh)
packages+=(help2man)  # man pages of the tools (tools/man/make_man.sh)
# The documentation site (docs/, the `docs` target): Sphinx, breathe (C++ API from Doxygen's XML),
# MyST (Markdown), sphinx-gallery; the notebooks (docs/notebooks/) run by nbclient on ipykernel;
# mypy's stubgen for the Python type stubs.
packages+=(doxygen python3-sphinx python3-breathe python3-myst-parser python3-sphinx-gallery)
packages+=(python3-ipykernel python3-nbclient python3-nbformat mypy python3-setuptools python3-pip)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  # force-unsafe-io: dpkg skips its fsync calls while unpacking (as Debian's build chroots do),
  # which saves most of the unpacking time on a fresh machine; an interrupted install is redone
  # by running this script again.
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    -o Dpkg::Options::=--force-unsafe-io "${missing[@]}"
else
  echo "setup: all dependencies present"
fi

# view: three.js (embedded into `plateball view`'s pages at build time) and playwright-core
# (the browser tests), exactly as web/package-lock.json pins them; skipped when already installed.
((main_only)) && exit 0
web_dir="$(cd "$(dirname "$0")/../web" && pwd)"
if ! cmp -s "$web_dir/package-lock.json" "$web_dir/node_modules/.plateball-package-lock.json"; then
  echo "setup: npm ci in web/"
  (cd "$web_dir" && npm ci --no-audit --no-fund --loglevel=error)
  cp "$web_dir/package-lock.json" "$web_dir/node_modules/.plateball-package-lock.json"
fi
