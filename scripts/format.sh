#!/usr/bin/env bash
# Formats every tracked C and C++ file in place with clang-format and the repository's .clang-format
# (Ceres Solver's style, 120 columns). The test Hygiene.Format checks the result.
set -euo pipefail
cd "$(dirname "$0")/.."
git ls-files '*.cc' '*.h' '*.c' '*.cpp' | xargs clang-format -i
