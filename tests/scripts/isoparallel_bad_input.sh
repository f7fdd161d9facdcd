#!/usr/bin/env bash
# Table-driven bad-input suite for isoparallel_solve: each case must exit with the
# documented code (2 usage, 3 bad input, 4 no solution, 5 I/O, 7 not certified), name the offending field in its
# message, finish within the time bound, and never print a NaN.
# Usage: isoparallel_bad_input.sh TOOL WORKDIR
set -u
tool="$1"
work="$2"
rm -rf "$work" && mkdir -p "$work"
base='"ball": {"lambda": 2}, "initial": {"theta": 0, "phi": 0, "psi": 0, "mu": 1}'
iso() { printf '{%s, "isoparallel": {%s}}\n' "$base" "$1"; }
write() { printf '%s\n' "$2" > "$work/$1.json"; }

write bad_json '{"ball": {"lambda": 2},, }'
write unknown_key "$(iso '"start": [0, 0], "goal": [3, 3], "colour": "red"')"
write goal_not_rotation "$(iso '"start": [0, 0], "goal": [3, 3], "goal_orientation": {"matrix": [[1,0,0],[0,1,0],[0,0,-1]]}')"
write goal_scaled_matrix "$(iso '"start": [0, 0], "goal": [3, 3], "goal_orientation": {"matrix": [[2,0,0],[0,2,0],[0,0,2]]}')"
write zero_quaternion "$(iso '"start": [0, 0], "goal": [3, 3], "goal_orientation": {"quaternion": [0, 0, 0, 0]}')"
write huge_number "$(iso '"start": [0, 0], "goal": [1e999, 3]')"
write goal_wrong_type "$(iso '"start": [0, 0], "goal": "far away"')"
write goal_short "$(iso '"start": [0, 0], "goal": [3]')"
write zero_impulses "$(iso '"start": [0, 0], "goal": [3, 3], "impulses": 0')"
write zero_starts "$(iso '"start": [0, 0], "goal": [3, 3], "solver": {"starts": 0}')"
write negative_tolerance "$(iso '"start": [0, 0], "goal": [3, 3], "solver": {"tolerance": -1e-9}')"
write zero_iterations "$(iso '"start": [0, 0], "goal": [3, 3], "solver": {"max_iterations": 0}')"
write cap_below_one "$(iso '"start": [0, 0], "goal": [3, 3], "solver": {"length_cap_factor": 0.5}')"
write zero_threads "$(iso '"start": [0, 0], "goal": [3, 3], "solver": {"threads": 0}')"
write negative_mu '{"ball": {"lambda": 2}, "initial": {"theta": 0, "phi": 0, "psi": 0, "mu": -1}, "isoparallel": {"start": [0, 0], "goal": [3, 3]}}'
write zero_lambda '{"ball": {"lambda": 0}, "initial": {"theta": 0, "phi": 0, "psi": 0, "mu": 1}, "isoparallel": {"start": [0, 0], "goal": [3, 3]}}'
write no_task '{"ball": {"lambda": 2}, "initial": {"theta": 0, "phi": 0, "psi": 0, "mu": 1}}'
write negative_seed "{\"seed\": -4, $base, \"isoparallel\": {\"start\": [0, 0], \"goal\": [3, 3]}}"
write stall_one_iteration "$(iso '"start": [0, 0], "goal": [3, 3], "solver": {"starts": 1, "max_iterations": 1, "enumerate_families": false}')"

# name | expected exit code | text the message must contain | arguments...
cases=(
  "malformed JSON|3|bad_json.json|$work/bad_json.json"
  "unknown key|3|colour|$work/unknown_key.json"
  "goal orientation not a rotation (det -1)|3|goal_orientation|$work/goal_not_rotation.json"
  "goal orientation scaled|3|goal_orientation|$work/goal_scaled_matrix.json"
  "zero quaternion|3|goal_orientation|$work/zero_quaternion.json"
  "number too large for a double|3|isoparallel.goal|$work/huge_number.json"
  "goal of the wrong type|3|isoparallel.goal|$work/goal_wrong_type.json"
  "goal with one coordinate|3|isoparallel.goal|$work/goal_short.json"
  "zero impulses in the file|3|impulses|$work/zero_impulses.json"
  "zero starts|3|starts|$work/zero_starts.json"
  "negative tolerance|3|tolerance|$work/negative_tolerance.json"
  "zero iterations|3|max_iterations|$work/zero_iterations.json"
  "length cap below one|3|length_cap_factor|$work/cap_below_one.json"
  "zero threads|3|threads|$work/zero_threads.json"
  "negative energy|3|initial.mu|$work/negative_mu.json"
  "zero lambda|3|ball.lambda|$work/zero_lambda.json"
  "file without an isoparallel task|3|isoparallel|$work/no_task.json"
  "negative seed|3|seed|$work/negative_seed.json"
  "missing problem file|5|no_such_file.json|$work/no_such_file.json"
  "unwritable plan file|5|/nonexistent_dir/plan.json|--out|/nonexistent_dir/plan.json"
  "unwritable figure file|5|/nonexistent_dir/figure.svg|--svg|/nonexistent_dir/figure.svg"
  "zero impulses on the command line|3|--impulses|--impulses|0"
  "non-numeric seed|3|--seed|--seed|abc"
  "unknown option|2|--frobnicate|--frobnicate"
  "solver starved of iterations|4|solution|$work/stall_one_iteration.json"
  "certify cap below one|3|--certify-cap|--certify|--certify-cap|0.5"
  "certify budget zero|3|--certify-budget|--certify|--certify-budget|0"
  "certify cap without --certify|2|--certify|--certify-cap|2"
  "certify length below the chord|3|--certify-length|--certify|--certify-length|1"
  "certify length and cap together|2|--certify-cap|--certify|--certify-length|5|--certify-cap|2"
  "certificate out of budget|7|not closed|$(dirname "$0")/../../problems/isoparallel_rotation.json|--certify|--certify-budget|1"
)

passed=0
failed=0
for entry in "${cases[@]}"; do
  IFS='|' read -r -a f <<< "$entry"
  name="${f[0]}"; want="${f[1]}"; needle="${f[2]}"; args=("${f[@]:3}")
  out=$(timeout 60 "$tool" "${args[@]}" 2>&1)
  code=$?
  problem=""
  [[ $code -eq 124 ]] && problem="timed out (no bound on the solve)"
  [[ -z "$problem" && $code -ne $want ]] && problem="exit code $code, expected $want"
  [[ -z "$problem" && "$out" != *"$needle"* ]] && problem="message does not name '$needle'"
  [[ -z "$problem" ]] && echo "$out" | grep -qiw "nan" && problem="NaN in the output"
  if [[ -z "$problem" ]]; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL: $name: $problem"
    echo "  output: $out" | head -5
  fi
done

# Reproducibility: the same problem and seed give a byte-identical plan file, across runs and
# across 1 and 2 solver threads (--threads; the file names itself in the output's header, so the
# same file is used).
fig7="$(dirname "$0")/../../problems/figure7.json"
"$tool" "$fig7" --out "$work/plan_a.json" > /dev/null 2>&1
"$tool" "$fig7" --out "$work/plan_b.json" > /dev/null 2>&1
"$tool" "$fig7" --threads 2 --out "$work/plan_c.json" > /dev/null 2>&1
if [[ -s "$work/plan_a.json" ]] &&
   cmp -s "$work/plan_a.json" "$work/plan_b.json" && cmp -s "$work/plan_a.json" "$work/plan_c.json"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1))
  echo "FAIL: plan files differ across runs or thread counts"
fi

echo "$passed passed, $failed failed"
[[ $failed -eq 0 ]]
