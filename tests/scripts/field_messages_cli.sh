#!/usr/bin/env bash
# Messages about bad values name the field as the user wrote it and the value ("FILE: FIELD: value V:
# what is wrong", "command line: --OPTION: value V: ..."), not a variable of the code ("partition
# (uniform_parameter, n = 64)[1]", "speed", "x1", "x0", "target[0]", "absolute_tolerance"), with no
# doubled prefix: each case with its exit code and the exact start of its message.
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
# A real isoparallel result (fuzz/seeds/view_input_fuzzer) with one bad value each, for `view`.
def result(change, name):
    d = json.load(open(f"{src}/fuzz/seeds/view_input_fuzzer/isoparallel.json"))
    change(d)
    save(d, name)
result(lambda d: d["model"].update({"lambda": 0}), "view_lambda.json")
result(lambda d: d["plan"]["steps"][0].update(duration=1e300), "view_duration.json")
result(lambda d: d["plan"]["steps"][0]["omega_after_impulse"].__setitem__(2, -1.0), "view_omega.json")
result(lambda d: d["optimal_path"][0].__setitem__(0, 1e300), "view_path.json")
d = json.load(open(f"{src}/fuzz/seeds/view_input_fuzzer/montecarlo.json")); d["options"]["miss_tolerance"] = 0
save(d, "view_miss_tolerance.json")
result(lambda d: d["integration"].update(absolute_tolerance=1e-30), "view_integration.json")
# One step around the closed circle: its two partition points coincide, a fault of the n given.
d = load("circle.json"); d["plan"]["partition"]["n"] = 1; save(d, "one_step.json")
d = load("circle.json"); d["plan"]["converge_n"] = [16, 16]; save(d, "converge_twice.json")
PY

# name | expected exit code | start of the message after "plateball TOOL: invalid input: " | arguments...
cases=(
  "circle tau_begin 1e300 (was: partition (uniform_parameter, n = 64)[1])|3|$work/tau_begin.json: plan.path.tau_begin: value 1e+300: must be in [-1e6, 1e6]|plan|$work/tau_begin.json|--summary-only"
  "circle tau_end -2e6|3|$work/tau_end.json: plan.path.tau_end: value -2e+06: must be in [-1e6, 1e6]|plan|$work/tau_end.json|--summary-only"
  "circle radius 1e-300 (was: plan.path.speed (speed at tau = 0))|3|$work/radius.json: plan.path.radius: value 1e-300: the path's speed|plan|$work/radius.json|--summary-only"
  "sine wavelength 1e-300 (was: plan.path.pieces[2].speed (speed at tau = 0))|3|$work/wavelength.json: plan.path.pieces[2].wavelength: value 1e-300: the path's speed|plan|$work/wavelength.json|--summary-only"
  "steer goal outside the rig's plate (was: x1)|3|$work/rig_goal.json: steer.goal: value (3, 3): lies outside rig.plate|steer|$work/rig_goal.json|--summary-only"
  "steer start in an obstacle (was: x0)|3|$work/rig_start.json: isoparallel.start: value (0, 0): lies inside rig.obstacles[0]|steer|$work/rig_start.json|--summary-only"
  "view: model.lambda 0 (was: lambda)|3|$work/view_lambda.json: model.lambda: value 0:|view|$work/view_lambda.json|--html|$work/v.html"
  "view: a step's duration 1e300 (was: t)|3|$work/view_duration.json: plan.steps[0].duration: value |view|$work/view_duration.json|--html|$work/v.html"
  "view: omega_after_impulse with spin (was: start.state.omega[2])|3|$work/view_omega.json: plan.steps[0].omega_after_impulse[2]: value -1:|view|$work/view_omega.json|--html|$work/v.html"
  "view: optimal_path point 1e300 (was: points)|3|$work/view_path.json: optimal_path[0]: value (1e+300, |view|$work/view_path.json|--html|$work/v.html"
  "view: Monte Carlo miss_tolerance 0 (was: miss_tolerance)|3|$work/view_miss_tolerance.json: options.miss_tolerance: value 0:|view|$work/view_miss_tolerance.json|--problem|$src/problems/circle.json|--html|$work/v.html"
  "view: integration.absolute_tolerance 1e-30 (was: integration: value (see message))|3|$work/view_integration.json: integration.absolute_tolerance: value 1e-30: must be in [1e-15, 1)|view|$work/view_integration.json|--html|$work/v.html"
  "plan: partition.n 1 on a closed path (was: partition (uniform_parameter, n = 1)[1] (p(tau_k) - p(tau_k-1)))|3|$work/one_step.json: plan.partition.n: value 1: partition points 0 and 1 are |plan|$work/one_step.json|--summary-only"
  "plan --impulses 1 on a closed path (was: partition (uniform_parameter, n = 1)[1])|3|command line: --impulses: value 1: partition points 0 and 1 are |plan|$src/problems/circle.json|--impulses|1|--summary-only"
  "converge --impulses 1,2 (was: partition (uniform_parameter, n = 1)[1])|3|command line: --impulses[0]: value 1: partition points 0 and 1 are |converge|$src/problems/circle.json|--impulses|1,2"
  "converge: converge_n repeated (was: no file name)|3|$work/converge_twice.json: plan.converge_n[1]: value 16: repeated|converge|$work/converge_twice.json"
  "montecarlo --sweep-n 1 (was: partition (uniform_parameter, n = 1)[1])|3|command line: --sweep-n: value 1: partition points 0 and 1 are |montecarlo|$src/problems/circle.json|--trials|1|--sweep-n|1"
  "montecarlo --noise timing=0.5 (was: --noise.timing)|3|command line: --noise timing: value 0.5: must be a number in [0, 0.1]|montecarlo|$src/problems/circle.json|--noise|timing=0.5"
  "join --targets 1e300,0 (was: target[0])|3|command line: --targets[0]: value 1e+300,0: |join|$src/problems/circle.json|--targets|1e300,0"
  "reach --targets 0,1e300 (was: target[1])|3|command line: --targets[0]: value 0,1e+300: |reach|$src/problems/figure8_reach.json|--targets|0,1e300"
  "roll --atol -1 (was: --atol/--rtol: value (-1, 1e-12): absolute_tolerance: value -1)|3|command line: --atol: value -1: must be in [1e-15, 1)|roll|--points|0,0;1,1|--atol|-1"
  "roll --orientation x (was: command line: (document))|3|command line: --orientation: value 'x': malformed JSON|roll|--points|0,0;1,1|--orientation|x"
  "identify --impulses 100 (was: --impulses: impulse_times[0])|3|command line: --impulses[0]: value 100: must be inside the track|identify|$src/tests/data/identify_track.csv|--impulses|100"
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
