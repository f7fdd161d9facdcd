#!/usr/bin/env bash
# Bad input at the tools' surfaces: each case with its exact exit code (3 bad input, 5 I/O), the
# field or file its message must name, and a 10 s bound (a FIFO must not block the reader).
# Usage: surfaces_cli.sh PLATEBALL ISOPARALLEL_SOLVE SOURCE_DIR WORKDIR
set -u
pb=$(realpath "$1")
iso=$(realpath "$2")
src=$(realpath "$3")
work="$4"
rm -rf "$work" && mkdir -p "$work"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*"; }

python3 - "$work" "$src" <<'PY'
import json, sys
w, src = sys.argv[1], sys.argv[2]
# A rigid ball with inertias of 1e299 and a mass of 1e300 at mu = 1e12: every model quantity is finite
# (lambda, beta), the kinetic energy mu (I1 + M r^2) / 2 is not.
d = json.load(open(f"{src}/problems/physical_units.json"))
d["ball"]["physical"].update(inertia_1=1e299, inertia_3=1e299, ball_mass=1e300, radius=1.0)
d["initial"]["mu"] = 1e12
json.dump(d, open(f"{w}/infinite_energy.json", "w"))
# A valid problem padded with blanks beyond the 16 MiB limit of a problem file.
text = open(f"{src}/problems/simulate_example.json").read()
open(f"{w}/huge_problem.json", "w").write(text + " " * (16 * 2**20))
PY
mkfifo "$work/fifo.json"

# name | expected exit code | text the message must contain | tool | arguments...   ("<FILE" feeds FILE on stdin)
cases=(
  "kinetic energy inf (simulate)|3|initial.mu|pb|simulate|$work/infinite_energy.json|--samples|10"
  "kinetic energy inf (reach)|3|initial.mu|pb|reach|$work/infinite_energy.json"
  "problem on standard input above 16 MiB|3|16 MiB|pb|simulate|-|<$work/huge_problem.json"
  "FIFO as the problem file|5|a FIFO or socket, not a file|pb|simulate|$work/fifo.json"
  "FIFO as the problem file (isoparallel_solve)|5|a FIFO or socket, not a file|iso|$work/fifo.json"
  "FIFO as the result of view|5|a FIFO or socket, not a file|pb|view|$work/fifo.json|--html|$work/v.html"
  "unknown subcommand|2|\"bogus\": unknown subcommand|pb|bogus"
  "unknown subcommand rig (or rig's unknown member)|2|unknown subcommand|pb|rig|x.json"
  "--exact with 2 impulses, before the solve|3|--impulses: value 2|iso|$src/problems/figure7.json|--exact|--impulses|2"
)

for entry in "${cases[@]}"; do
  IFS='|' read -r -a f <<< "$entry"
  name="${f[0]}"; want="${f[1]}"; needle="${f[2]}"; which="${f[3]}"; args=("${f[@]:4}")
  tool="$pb"; [[ "$which" == iso ]] && tool="$iso"
  stdin=/dev/null
  last="${args[${#args[@]}-1]}"
  if [[ "$last" == "<"* ]]; then stdin="${last:1}"; unset 'args[${#args[@]}-1]'; fi
  out=$(timeout 10 "$tool" "${args[@]}" 2>&1 >/dev/null < "$stdin")
  code=$?
  problem=""
  [[ $code -eq 124 ]] && problem="took more than 10 s"
  [[ -z "$problem" && $code -ne $want ]] && problem="exit code $code, expected $want"
  [[ -z "$problem" && "$out" != *"$needle"* ]] && problem="message does not name '$needle'"
  if [[ -z "$problem" ]]; then ok; else bad "$name: $problem"; echo "  output: ${out:0:300}"; fi
done

# --exact --impulses 2 is refused before the solve: nothing on standard output.
out=$(timeout 10 "$iso" "$src/problems/figure7.json" --exact --impulses 2 2>/dev/null)
if [[ -z "$out" ]]; then ok; else bad "--exact --impulses 2 printed a solve first: ${out:0:200}"; fi

# Control characters in a name: the SVG stays well-formed XML, the terminal sees no raw ESC.
python3 - "$work" "$src" <<'PY'
import json, sys
w, src = sys.argv[1], sys.argv[2]
for name in ["circle", "figure7"]:
    d = json.load(open(f"{src}/problems/{name}.json"))
    d["name"] = "a\u0001b\u001b]0;retitled\u0007\u001b[2J end"
    json.dump(d, open(f"{w}/control_{name}.json", "w"))
PY
"$pb" plan "$work/control_circle.json" --quiet --out "$work/control.json" --svg "$work/control.svg" 2>/dev/null
if python3 -c "import sys, xml.dom.minidom as m; m.parse(sys.argv[1])" "$work/control.svg" 2>/dev/null; then ok
else bad "SVG of a name with control characters is not well-formed XML"; fi
"$iso" "$work/control_figure7.json" > "$work/control_iso.txt" 2>&1
if [[ -s "$work/control_iso.txt" ]] && ! grep -q $'\x1b\|\x01\|\x07' "$work/control_iso.txt" && grep -q 'a\\x01b\\x1b' "$work/control_iso.txt"
then ok; else bad "isoparallel_solve printed control characters raw: $(head -c 200 "$work/control_iso.txt" | od -c | head -3)"; fi

# SIGTERM while an output is being written: the temporary file is removed, no output appears.
"$pb" simulate "$src/problems/simulate_example.json" --samples 100000 --out "$work/sig.json" 2>/dev/null &
pid=$!
seen=0
for _ in $(seq 1 4000); do
  if compgen -G "$work/.sig.json.tmp*" > /dev/null; then seen=1; kill -TERM $pid; break; fi
  sleep 0.005
done
wait $pid
code=$?
left=$(compgen -G "$work/.sig.json.tmp*" | wc -l)
if [[ $seen -eq 1 && $code -eq 143 && $left -eq 0 && ! -e "$work/sig.json" ]]; then ok
else bad "SIGTERM during a write: temporary seen $seen, exit $code, $left temporaries left"; fi

# A run's outputs go in place together: when the SVG cannot be written, the JSON is not replaced
# either (and no temporary file is left).
echo old > "$work/together.json"
timeout 60 "$iso" "$src/problems/figure7.json" --out "$work/together.json" --svg /dev/full > /dev/null 2>&1
code=$?
left=$(compgen -G "$work/.together.json.tmp*" | wc -l)
if [[ $code -eq 5 && "$(cat "$work/together.json")" == old && $left -eq 0 ]]; then ok
else bad "--out with a failing --svg: exit $code, --out now $(head -c 40 "$work/together.json"), $left temporaries left"; fi

# view accepts real results: steer --stop-at-goal (a last arc of duration 0) and the fewest search.
"$pb" steer "$src/problems/figure7_exact.json" --stop-at-goal --quiet --out "$work/stop.json" 2>/dev/null
"$pb" steer "$src/problems/figure7_fewest.json" --quiet --out "$work/fewest.json" 2>/dev/null
for r in stop fewest; do
  out=$(timeout 60 "$pb" view "$work/$r.json" --html "$work/$r.html" 2>&1)
  code=$?
  if [[ $code -eq 0 && -s "$work/$r.html" ]]; then ok; else bad "view of a steer $r result: exit $code: ${out:0:300}"; fi
done

# view of a montecarlo result whose "initial" is not an object: exit 3 naming the field.
"$pb" montecarlo "$src/problems/circle.json" --trials 4 --threads 1 --quiet --out "$work/mc.json" 2>/dev/null
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['initial']=0; json.dump(d, open(sys.argv[2], 'w'))" \
  "$work/mc.json" "$work/mc_initial0.json"
out=$(timeout 60 "$pb" view "$work/mc_initial0.json" --html "$work/mc0.html" 2>&1)
code=$?
if [[ $code -eq 3 && "$out" == *"initial: value 0"* ]]; then ok; else bad "view of initial 0: exit $code: ${out:0:300}"; fi

# view of a montecarlo result edited to n = 10^4 and 10^6 trials: the re-run keeps to its work
# budget (a few trials per cell, said on the page) instead of running for minutes.
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['options'].update(impulses=10000, trials=1000000); json.dump(d, open(sys.argv[2], 'w'))" \
  "$work/mc.json" "$work/mc_big.json"
out=$(timeout 60 "$pb" view "$work/mc_big.json" --html "$work/mc_big.html" 2>&1)
code=$?
if [[ $code -eq 0 ]] && grep -q "work budget" "$work/mc_big.html"; then ok; else bad "view of an n = 10^4 montecarlo result: exit $code: ${out:0:300}"; fi

echo "$passed passed, $failed failed"
