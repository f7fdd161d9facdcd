#!/usr/bin/env bash
# Fails when a tracked C or C++ file differs from what clang-format makes of it under the repository's
# .clang-format (Ceres Solver's style, 120 columns). Fix with: scripts/format.sh
# Usage: check_format.sh SOURCE_DIR CLANG_FORMAT
set -u
cd "$1" || exit 2
mapfile -t files < <(git ls-files '*.cc' '*.h' '*.c' '*.cpp')
if ((${#files[@]} == 0)); then
  echo "no tracked C or C++ files (not a git checkout?)"
  exit 2
fi
if ! report=$("$2" --dry-run --Werror "${files[@]}" 2>&1); then
  printf '%s\n' "$report" | head -60
  echo "not formatted (run scripts/format.sh)"
  exit 1
fi
echo "${#files[@]} files formatted"
