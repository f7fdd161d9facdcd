#!/usr/bin/env bash
# Hostile command-line cases (tool side): each reproduction with its exact exit code
# (2 usage, 3 bad input, 4 no solution, 5 I/O), the option or file its message must name, and a
# 10 s bound per case; then the file checks (atomic replacement, nothing overwritten by accident,
# "-" is standard output, escaped SVG).
# Usage: hostile_cli.sh PLATEBALL ISOPARALLEL_SOLVE SOURCE_DIR WORKDIR
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

# Files of the cases.
python3 - "$work" <<'PY'
import sys
w = sys.argv[1]
d = 100000
open(f"{w}/deep.json", "w").write('{"points": [[0,0], ' + "[" * d + "]" * d + "]}")
open(f"{w}/duplicate_key.json", "w").write('{"points": [[0,0],[1,1]], "points": [[0,0],[2,0]]}')
open(f"{w}/long_value.json", "w").write('{"points": [[0,0], [1, "' + "a" * 100000 + '"]]}')
open(f"{w}/ampersand.json", "w").write(
    '{"name": "a & b <c>", "ball": {"lambda": 2}, "initial": {"theta": 1.0471975511965976, "phi": 0, "psi": 0, "mu": 1},'
    ' "reach": {"targets": [[0, 10]], "horizon_periods": 2}}')
PY
cp "$src/problems/simulate_example.json" "$work/input.json"
printf 'not a directory\n' > "$work/plain_file"

# name | expected exit code | text the message must contain | tool | arguments...
cases=(
  "empty --theta|3|--theta|pb|simulate|--theta||--samples|2"
  "empty --mu|3|--mu|pb|simulate|--mu||--samples|2"
  "blank --lambda|3|--lambda|pb|simulate|--lambda|  "
  "non-numeric --mu (plateball)|3|--mu|pb|simulate|--mu|abc"
  "non-numeric --seed (isoparallel_solve)|3|--seed|iso|--seed|abc"
  "zero --impulses (isoparallel_solve)|3|--impulses|iso|--impulses|0"
  "seed 2^64|3|--seed|iso|--seed|18446744073709551616"
  "seed -1|3|--seed|iso|--seed|-1"
  "seed -1 (plateball)|3|--seed|pb|steer|--seed|-1"
  "--t-end beyond 1e12 periods|3|--t-end|pb|simulate|--t-end|5e14|--samples|2"
  "points whose distance overflows|3|--points[1]|pb|roll|--segment|--points|0,0;1e308,0;-1e308,0"
  "samples file nested 1e5 deep|3|nested|pb|roll|--samples-file|$work/deep.json"
  "samples file /dev/zero|3|64 MiB|pb|roll|--samples-file|/dev/zero"
  "samples file with a duplicate key|3|duplicate key|pb|roll|--samples-file|$work/duplicate_key.json"
  "samples file with a long bad value|3|points[1]|pb|roll|--samples-file|$work/long_value.json"
  "--out and --svg the same file|3|--out and --svg|pb|plan|$src/problems/circle.json|--out|$work/x|--svg|$work/x"
  "--out and --svg the same file (isoparallel_solve)|3|--out and --svg|iso|--out|$work/y|--svg|$work/y"
  "--out is the input file|3|--out and PROBLEM.json|pb|simulate|$work/input.json|--out|$work/input.json"
  "--out is the input file (isoparallel_solve)|3|--out and problem file|iso|$src/problems/figure7.json|--out|$src/problems/figure7.json"
  "--svg - with the JSON on standard output|3|--out and --svg|pb|reach|--targets|6,0|--svg|-"
  "--out - (isoparallel_solve: standard output is the report)|3|--out|iso|--out|-"
  "--svg to a missing directory, checked before the solve|5|/nonexistent_dir/f.svg|pb|plan|$src/problems/circle.json|--n|1000000|--svg|/nonexistent_dir/f.svg"
  "--out under a plain file|5|$work/plain_file/a.json|pb|simulate|--out|$work/plain_file/a.json"
  "--svg /dev/full|5|/dev/full|pb|reach|$src/problems/figure8_reach.json|--svg|/dev/full"
)

for entry in "${cases[@]}"; do
  IFS='|' read -r -a f <<< "$entry"
  name="${f[0]}"; want="${f[1]}"; needle="${f[2]}"; which="${f[3]}"; args=("${f[@]:4}")
  tool="$pb"; [[ "$which" == iso ]] && tool="$iso"
  out=$(timeout 10 "$tool" "${args[@]}" 2>&1 >/dev/null)
  code=$?
  problem=""
  [[ $code -eq 124 ]] && problem="took more than 10 s"
  [[ -z "$problem" && $code -ne $want ]] && problem="exit code $code, expected $want"
  [[ -z "$problem" && "$out" != *"$needle"* ]] && problem="message does not name '$needle'"
  [[ -z "$problem" && ${#out} -gt 400 && $want -ne 5 ]] && problem="message of ${#out} characters"
  if [[ -z "$problem" ]]; then ok; else bad "$name: $problem"; echo "  output: ${out:0:300}"; fi
done

# Write errors on standard output: exit 5, not 0.
timeout 10 "$pb" converge "$src/problems/circle.json" --n 16 --format csv > /dev/full 2>/dev/null
code=$?; [[ $code -eq 5 ]] && ok || bad "converge --format csv > /dev/full: exit $code, expected 5"
timeout 10 "$iso" > /dev/full 2>/dev/null
code=$?; [[ $code -eq 5 ]] && ok || bad "isoparallel_solve > /dev/full: exit $code, expected 5"

# The input file is untouched by a refused --out.
cmp -s "$work/input.json" "$src/problems/simulate_example.json" && ok || bad "the input file was changed"

# Atomic replacement: a write cut short (file size limit, as a full disk) exits 5, keeps the
# previous file byte for byte and leaves no temporary file.
"$pb" simulate --samples 2 --out "$work/atomic.json" > /dev/null 2>&1
cp "$work/atomic.json" "$work/atomic_before.json"
(ulimit -f 16; trap '' XFSZ; timeout 10 "$pb" simulate --samples 1000 --out "$work/atomic.json" > /dev/null 2>&1)
code=$?
[[ $code -eq 5 ]] && ok || bad "simulate --out on a full disk: exit $code, expected 5"
cmp -s "$work/atomic.json" "$work/atomic_before.json" && ok || bad "the previous file did not survive a failed write"
leftovers=$(find "$work" -name '.atomic.json.tmp*' | wc -l)
[[ $leftovers -eq 0 ]] && ok || bad "$leftovers temporary file(s) left behind"

# "-" is standard output for --out and --svg alike (no file named "-").
(cd "$work" && timeout 10 "$pb" simulate --samples 2 --out - 2>/dev/null) | grep -q '"command": "simulate"' && ok ||
  bad "simulate --out - did not write standard output"
(cd "$work" && timeout 10 "$pb" reach --targets 0,10 --theta 1.0471975511965976 --out "$work/reach.json" --svg - 2>/dev/null) |
  grep -q '^<svg' && ok || bad "reach --svg - did not write standard output"
[[ ! -e "$work/-" ]] && ok || bad "a file named '-' was written"

# The SVG of a problem named with & and < is well-formed XML and shows the name escaped.
timeout 10 "$pb" reach "$work/ampersand.json" --svg "$work/ampersand.svg" > /dev/null 2>&1
if python3 -c 'import sys, xml.dom.minidom as m; m.parse(sys.argv[1])' "$work/ampersand.svg" 2>/dev/null &&
   grep -q 'a &amp; b &lt;c&gt;' "$work/ampersand.svg"; then ok; else bad "reach --svg of a name with & is not well-formed XML"; fi

# The largest seed is used as given (not clamped to 2^63 - 1).
timeout 20 "$iso" "$src/problems/figure7.json" --seed 18446744073709551615 --out "$work/seed.json" > /dev/null 2>&1
grep -q '"seed": 18446744073709551615' "$work/seed.json" && ok || bad "--seed 18446744073709551615 not used as given"

# Both tools call a seed the same in their help.
"$pb" steer --help | grep -q -- '--seed UINT64' && "$iso" --help | grep -q -- '--seed UINT64' && ok ||
  bad "--seed is not UINT64 in both tools' help"

echo "$passed passed, $failed failed"
[[ $failed -eq 0 ]]
