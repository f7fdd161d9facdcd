#!/usr/bin/env bash
# Runs a command-line tool and checks its exact exit code and numbers in its JSON output.
#
#   check_cli.sh EXIT_CODE [CHECK...] -- COMMAND [ARGS...]
#
# CHECKs (every occurrence of "KEY" in the output must match; at least one must exist):
#   --number KEY VALUE TOL          |value - VALUE| <= TOL
#   --vector KEY "V1,V2,..." TOL    element-wise, for a flat array [v1, v2, ...]
#   --at PATH VALUE TOL             the one number at PATH (e.g. arrival.position_error,
#                                   pareto[1].total_time) of the first JSON document in the output
#   --cat FILE                      append FILE (e.g. an --out file) to the output before checking
# The command's standard output and error are printed, so ctest's PASS_REGULAR_EXPRESSION can
# check messages too. Exits 0 when everything matches, 1 otherwise.
set -u
if [[ $# -lt 3 ]]; then
  echo "usage: $0 EXIT_CODE [CHECK...] -- COMMAND [ARGS...]" >&2
  exit 1
fi
expected_exit=$1
shift
checks=()
cat_files=()
while [[ $# -gt 0 && $1 != "--" ]]; do
  case $1 in
    --number | --vector | --at) checks+=("$1" "$2" "$3" "$4"); shift 4 ;;
    --cat) cat_files+=("$2"); shift 2 ;;
    *) echo "check_cli.sh: unknown check $1" >&2; exit 1 ;;
  esac
done
shift  # the "--"
output=$("$@" 2>&1)
code=$?
for f in "${cat_files[@]+"${cat_files[@]}"}"; do
  if [[ -f $f ]]; then output+=$'\n'$(cat "$f"); else output+=$'\n'"check_cli.sh: no file $f"; fi
done
printf '%s\n' "$output"
status=0
if [[ $code -ne $expected_exit ]]; then
  echo "check_cli.sh: FAIL: exit code $code, expected $expected_exit" >&2
  status=1
fi
compact=$(printf '%s' "$output" | tr -d ' \n\t')
number='-?[0-9][0-9.eE+-]*'
i=0
while [[ $i -lt ${#checks[@]} ]]; do
  kind=${checks[$i]} key=${checks[$((i + 1))]} want=${checks[$((i + 2))]} tol=${checks[$((i + 3))]}
  i=$((i + 4))
  if [[ $kind == --at ]]; then
    found=$(printf '%s' "$output" | python3 -c '
import json, re, sys
text = sys.stdin.read()
try:
    doc, _ = json.JSONDecoder().raw_decode(text[text.index("{"):])
    for part in re.findall(r"[^.\[\]]+|\[\d+\]", sys.argv[1]):
        doc = doc[int(part[1:-1])] if part.startswith("[") else doc[part]
    print(repr(float(doc)) if isinstance(doc, (int, float)) and not isinstance(doc, bool) else "")
except (ValueError, KeyError, IndexError, TypeError):
    print("")' "$key")
  elif [[ $kind == --number ]]; then
    found=$(printf '%s' "$compact" | grep -oE "\"$key\":$number" | sed "s/^\"$key\"://")
  else
    found=$(printf '%s' "$compact" | grep -oE "\"$key\":\[$number(,$number)*\]" | sed "s/^\"$key\":\[//; s/\]$//")
  fi
  if [[ -z $found ]]; then
    echo "check_cli.sh: FAIL: no \"$key\" in the output" >&2
    status=1
    continue
  fi
  while IFS= read -r got; do
    if ! awk -v got="$got" -v want="$want" -v tol="$tol" 'BEGIN {
           n = split(got, g, ","); m = split(want, w, ",");
           if (n != m) exit 1;
           for (k = 1; k <= n; ++k) { d = g[k] - w[k]; if (d < 0) d = -d; if (!(d <= tol)) exit 1 }
           exit 0 }'; then
      echo "check_cli.sh: FAIL: \"$key\" = $got, expected $want within $tol" >&2
      status=1
    else
      echo "check_cli.sh: ok: \"$key\" = $got (expected $want within $tol)"
    fi
  done <<< "$found"
done
exit $status
