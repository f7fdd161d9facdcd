#!/usr/bin/env bash
# The limits of plateball/limits.h as the tools apply them: a problem on standard input has the
# problem file's 16 MiB limit (and is refused without reading further), simulate's samples have
# one limit on the command line and in a file, `view` draws a result of that many samples, and
# `view` refuses a montecarlo result whose trial count the tool could not have written.
# Usage: limits_cli.sh PLATEBALL SOURCE_DIR WORKDIR [SANITIZED]
# SANITIZED = 1 (a sanitizer build) skips `view` of the largest simulation: a capacity check that
# the Release suite makes, at ten times the time under the sanitizers.
set -u
pb=$(realpath "$1")
src=$(realpath "$2")
work="$3"
sanitized="${4:-0}"
rm -rf "$work" && mkdir -p "$work"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }
# expect NAME CODE NEEDLE OUTPUT_AND_CODE: the exit code and a text the message must contain.
expect() {
  local name="$1" want="$2" needle="$3" out="$4" code="$5"
  if [[ $code -ne $want ]]; then bad "$name: exit code $code, expected $want"; echo "  output: ${out:0:300}"
  elif [[ "$out" != *"$needle"* ]]; then bad "$name: message does not contain '$needle'"; echo "  output: ${out:0:300}"
  else ok; fi
}

# Standard input: 80 MB of zeros is refused at the 16 MiB problem-file limit, named as standard
# input (the tool used to buffer 64 MiB first and report its own 64 MiB limit).
out=$(head -c 80000000 /dev/zero | timeout 20 "$pb" simulate - 2>&1 >/dev/null); code=$?
expect "stdin beyond 16 MiB" 3 "(standard input): (file): value (more than 16777216 bytes): larger than the 16 MiB limit" "$out" $code
# A valid problem padded to exactly 16 MiB is read; one byte more is refused, as for a file.
python3 - "$src/problems/simulate_example.json" "$work" <<'PY'
import sys
text = open(sys.argv[1]).read()
limit = 16 << 20
open(sys.argv[2] + "/at_limit.json", "w").write(text + " " * (limit - len(text.encode())))
open(sys.argv[2] + "/over_limit.json", "w").write(text + " " * (limit + 1 - len(text.encode())))
PY
out=$(timeout 20 "$pb" simulate - --samples 2 < "$work/at_limit.json" 2>&1 >/dev/null); code=$?
expect "stdin of exactly 16 MiB" 0 "" "$out" $code
out=$(timeout 20 "$pb" simulate - --samples 2 < "$work/over_limit.json" 2>&1 >/dev/null); code=$?
expect "stdin of 16 MiB + 1" 3 "16 MiB limit of a problem file" "$out" $code
out=$(timeout 20 "$pb" simulate "$work/over_limit.json" --samples 2 2>&1 >/dev/null); code=$?
expect "file of 16 MiB + 1" 3 "16 MiB limit of a problem file" "$out" $code

# simulate's samples: 10^5 on the command line and in a file, 10^5 + 1 refused by both.
out=$(timeout 20 "$pb" simulate --samples 100001 2>&1 >/dev/null); code=$?
expect "--samples 100001" 3 "--samples: value 100001: must be <= 100000" "$out" $code
python3 - "$src/problems/simulate_example.json" "$work" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
doc["simulate"]["samples"] = 100001
json.dump(doc, open(sys.argv[2] + "/samples_over.json", "w"))
PY
out=$(timeout 20 "$pb" simulate "$work/samples_over.json" 2>&1 >/dev/null); code=$?
expect "file simulate.samples 100001" 3 "simulate.samples: value 100001: must be <= 100000" "$out" $code
# The largest simulation the tools accept is one `view` draws (view is built where three.js is).
has_view=0
"$pb" view --help > /dev/null 2>&1 && has_view=1
out=$(timeout 60 "$pb" simulate "$src/problems/figure7.json" --samples 100000 --out "$work/s100k.json" 2>&1); code=$?
expect "simulate --samples 100000" 0 "" "$out" $code
if [[ $has_view -eq 1 && $sanitized -eq 1 ]]; then
  echo "sanitizer build: view of 10^5 samples is skipped (the Release suite checks it)"
elif [[ $has_view -eq 1 ]]; then
  out=$(timeout 60 "$pb" view "$work/s100k.json" --html "$work/s100k.html" 2>&1); code=$?
  expect "view of 10^5 samples" 0 "" "$out" $code
else
  echo "view is not built: its cases are skipped"
fi

# view of a montecarlo result: counts the tool cannot write are refused, naming the field.
out=$(timeout 60 "$pb" montecarlo "$src/problems/circle.json" --trials 2 --impulses 16 -q --out "$work/mc.json" 2>&1); code=$?
expect "montecarlo --trials 2" 0 "" "$out" $code
[[ $has_view -eq 1 ]] && for edit in "trials=-5" "trials=2.5" "trials=1000001" "impulses=0" "impulses=10001"; do
  key=${edit%%=*}; value=${edit#*=}
  python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['options'][sys.argv[2]]=json.loads(sys.argv[3]); json.dump(d,open(sys.argv[4],'w'))" \
    "$work/mc.json" "$key" "$value" "$work/mc_edit.json"
  out=$(timeout 60 "$pb" view "$work/mc_edit.json" --html "$work/mc.html" 2>&1); code=$?
  expect "view with options.$edit" 3 "options.$key: value $value: must be an integer in" "$out" $code
done

echo "$passed passed, $failed failed"
[[ $failed -eq 0 ]]
