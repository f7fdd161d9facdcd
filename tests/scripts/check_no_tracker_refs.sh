#!/usr/bin/env bash
# Fails when code, tests, benchmarks, scripts, build files, help texts, problem files, schemas or the
# documentation (all but its history appendix, docs/appendix/) cite the issue tracker
# ("issue N", "(issue N)", "Issue N, task ..." with a number for N): the number means nothing to
# a user; say what the thing is instead (history belongs in the commit log or docs/appendix/).
# Usage: check_no_tracker_refs.sh SOURCE_DIR
set -u
cd "$1" || exit 2
hits=$(grep -rnIE '[Ii]ssue [0-9]+' src include tools python problems schemas web cmake CMakeLists.txt \
         scripts bench tests fuzz examples .ci docs \
         --exclude-dir=node_modules --exclude-dir=appendix --exclude-dir=_generated --exclude-dir=_generated_gallery --exclude-dir=__pycache__ 2>/dev/null || true)
if [[ -n "$hits" ]]; then
  echo "tracker references (say what the thing is instead):"
  echo "$hits"
  echo "$(printf '%s\n' "$hits" | grep -c .) tracker reference(s)"
  exit 1
fi
echo "no tracker references"
