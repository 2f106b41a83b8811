#!/usr/bin/env bash
# Two values of parallel.rebalance_threshold on 2 ranks x 1 thread against 1 rank x 1 thread, run in turn ROUNDS
# times (a shared machine's drift hits each alike): the loop's wall time of each run (the log's "N steps in X s
# wall"), its blocks dealt again and its ranks' compute range, then the medians and each threshold's speed-up, the
# median of the rounds' own ratios (docs/parallel.md, Load balance).
# Usage: bash bench/parallel_threshold.sh BUILD CASE END_TIME ROUNDS THRESHOLD_A THRESHOLD_B [--set KEY=VALUE ...]
set -euo pipefail
build=$1 case_file=$2 end=$3 rounds=$4 ta=$5 tb=$6
shift 6
extra=("$@")
bin=$(realpath "$build/fluidbed")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_WAIT_POLICY=passive
loop_wall() { grep -o '[0-9]* steps in [0-9.]* s wall' "$1/log.txt" | tail -1 | awk '{print $4}'; }
deals() { grep -o 'dealt again [0-9]* times\|compute [0-9.]*-[0-9.]* s per rank' "$1/log.txt" | tail -2 | paste -sd' '; }
run() {  # run LABEL RANKS [THRESHOLD]
  local out="$work/$1"
  if [[ $2 -eq 1 ]]; then
    "$bin" run "$case_file" --out "$out" --end-time "$end" --threads 1 --quiet --overwrite "${extra[@]}"
  else
    mpiexec -n "$2" --bind-to core "$bin" run "$case_file" --out "$out" --end-time "$end" --threads 1 --quiet \
      --overwrite "${extra[@]}" --set "parallel.rebalance_threshold=$3"
  fi
  echo "$1 $(loop_wall "$out") $( [[ $2 -eq 1 ]] || deals "$out")"
}
# Warm-up: settles (and caches) the bed when the case settles, and loads the binary.
"$bin" run "$case_file" --out "$work/warm" --end-time "$end" --threads 2 --quiet --overwrite "${extra[@]}" >/dev/null
for r in $(seq 1 "$rounds"); do
  run r1t1 1
  run "r2-$ta" 2 "$ta"
  run "r2-$tb" 2 "$tb"
done | tee "$work/results"
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
for c in r1t1 "r2-$ta" "r2-$tb"; do
  m=$(awk -v c="$c" '$1 == c {print $2}' "$work/results" | median)
  r=$(awk -v c="$c" '$1 == "r1t1" {b = $2} $1 == c {print b / $2}' "$work/results" | median)
  printf '%s median %.3f s, speed-up over 1 x 1: %.3f median of the rounds\n' "$c" "$m" "$r"
done
