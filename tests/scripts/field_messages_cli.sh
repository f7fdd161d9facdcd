#!/usr/bin/env bash
# Messages about bad problem-file values name the file's field and the value ("FILE: FIELD: value V:
# what is wrong"), not a variable of the code ("partition (uniform_parameter, n = 64)[1]", "speed",
# "x1", "x0"): each case with its exit code and the exact start of its message.
# Usage: field_messages_cli.sh PLATEBALL SOURCE_DIR WORKDIR
set -u
pb=$(realpath "$1")
src=$(realpath "$2")
work="$3"
rm -rf "$work" && mkdir -p "$work"
passed=0
failed=0

python3 - "$work" "$src" <<'PY'
import json, sys
w, src = sys.argv[1], sys.argv[2]
def load(name):
    return json.load(open(f"{src}/problems/{name}"))
def save(d, name):
    json.dump(d, open(f"{w}/{name}", "w"))
d = load("circle.json"); d["plan"]["path"]["tau_begin"] = 1e300; save(d, "tau_begin.json")
d = load("circle.json"); d["plan"]["path"]["tau_end"] = -2e6; save(d, "tau_end.json")
d = load("circle.json"); d["plan"]["path"]["radius"] = 1e-300; save(d, "radius.json")
d = load("piecewise.json"); d["plan"]["path"]["pieces"][2]["wavelength"] = 1e-300; save(d, "wavelength.json")
d = load("figure7_rig.json"); d["rig"]["plate"]["center"] = [0.0, 0.0]; save(d, "rig_goal.json")
d = load("figure7_rig.json"); d["rig"]["obstacles"][0]["center"] = [0.0, 0.0]; save(d, "rig_start.json")
PY

# name | expected exit code | start of the message after "plateball TOOL: invalid input: " | arguments...
cases=(
  "circle tau_begin 1e300 (was: partition (uniform_parameter, n = 64)[1])|3|$work/tau_begin.json: plan.path.tau_begin: value 1e+300: must be in [-1e6, 1e6]|plan|$work/tau_begin.json|--summary-only"
  "circle tau_end -2e6|3|$work/tau_end.json: plan.path.tau_end: value -2e+06: must be in [-1e6, 1e6]|plan|$work/tau_end.json|--summary-only"
  "circle radius 1e-300 (was: plan.path.speed (speed at tau = 0))|3|$work/radius.json: plan.path.radius: value 1e-300: the path's speed|plan|$work/radius.json|--summary-only"
  "sine wavelength 1e-300 (was: plan.path.pieces[2].speed (speed at tau = 0))|3|$work/wavelength.json: plan.path.pieces[2].wavelength: value 1e-300: the path's speed|plan|$work/wavelength.json|--summary-only"
  "steer goal outside the rig's plate (was: x1)|3|$work/rig_goal.json: steer.goal: value (3, 3): lies outside rig.plate|steer|$work/rig_goal.json|--summary-only"
  "steer start in an obstacle (was: x0)|3|$work/rig_start.json: isoparallel.start: value (0, 0): lies inside rig.obstacles[0]|steer|$work/rig_start.json|--summary-only"
)

for entry in "${cases[@]}"; do
  IFS='|' read -r -a f <<< "$entry"
  name="${f[0]}"; want="${f[1]}"; start="${f[2]}"; args=("${f[@]:3}")
  out=$(timeout 20 "$pb" "${args[@]}" 2>&1 >/dev/null < /dev/null)
  code=$?
  problem=""
  [[ $code -eq 124 ]] && problem="took more than 20 s"
  [[ -z "$problem" && $code -ne $want ]] && problem="exit code $code, expected $want"
  [[ -z "$problem" && "$out" != "plateball ${args[0]}: invalid input: $start"* ]] && problem="message does not start with '$start'"
  if [[ -z "$problem" ]]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: $name: $problem"; echo "  output: ${out:0:400}"; fi
done
echo "field messages: $passed passed, $failed failed"
