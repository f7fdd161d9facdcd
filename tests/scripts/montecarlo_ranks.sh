#!/usr/bin/env bash
# plateball montecarlo gives one byte-identical summary (JSON and per-trial CSV) for any split of
# its trials: 1 and 2 threads, and, when MPIEXEC is given, 1, 2 and 3 MPI ranks (oversubscribed
# on a 2-core machine). Usage: montecarlo_ranks.sh PLATEBALL [MPIEXEC]
set -euo pipefail
plateball=$1
mpiexec=${2:-}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
args=(montecarlo problems/circle.json --n 16 --trials 7 --strategy open_loop,feedback
      --noise impulse_magnitude=1e-3,observation=1e-5 --noise timing=1e-3 --sweep-n 8 --quiet)
"$plateball" "${args[@]}" --threads 1 --out "$dir/t1.json" --csv "$dir/t1.csv"
"$plateball" "${args[@]}" --threads 2 --out "$dir/t2.json" --csv "$dir/t2.csv"
cmp "$dir/t1.json" "$dir/t2.json"
cmp "$dir/t1.csv" "$dir/t2.csv"
[[ $(wc -l < "$dir/t1.csv") -eq $((1 + 7 * 2 * 2 * 2)) ]]
if [[ -n $mpiexec ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
  for k in 1 2 3; do
    "$mpiexec" --oversubscribe -np "$k" "$plateball" "${args[@]}" --threads 1 --out "$dir/r$k.json" --csv "$dir/r$k.csv"
    cmp "$dir/t1.json" "$dir/r$k.json"
    cmp "$dir/t1.csv" "$dir/r$k.csv"
  done
  echo "montecarlo: identical output for 1 and 2 threads and 1, 2, 3 MPI ranks"
else
  echo "montecarlo: identical output for 1 and 2 threads (no MPI in this build)"
fi
