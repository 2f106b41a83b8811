#!/usr/bin/env bash
# Speed of a case on this machine over ranks and threads (docs/parallel.md): 1 rank x 1 thread, 2 ranks x 1
# thread and 1 rank x 2 threads, run in turn ROUNDS times so that a shared machine's drift hits each alike; the
# figure is the wall time of the run's loop (the log's "N steps in X s wall", without start-up, settling and the
# final checkpoint). Prints each run, the medians, the speed-ups over 1 x 1, and the last 2-rank run's
# decomposition and communication line.
# Usage: bash bench/parallel.sh BUILD CASE END_TIME [ROUNDS=3] [--set KEY=VALUE ...]
# (a settled bed is cached beside the case's outputs: give settle.cache when the case settles)
set -euo pipefail
build=$1 case_file=$2 end=$3 rounds=${4:-3}
shift 3
[[ $# -gt 0 && $1 != --* ]] && shift
extra=("$@")
bin=$(realpath "$build/fluidbed")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_WAIT_POLICY=passive
loop_wall() { grep -o '[0-9]* steps in [0-9.]* s wall' "$1/log.txt" | tail -1 | awk '{print $4}'; }
run() {  # run LABEL RANKS THREADS
  local out="$work/$1"
  if [[ $2 -eq 1 ]]; then
    "$bin" run "$case_file" --out "$out" --end-time "$end" --threads "$3" --quiet --overwrite "${extra[@]}"
  else
    mpiexec -n "$2" --bind-to core "$bin" run "$case_file" --out "$out" --end-time "$end" --threads "$3" --quiet \
      --overwrite "${extra[@]}"
  fi
  echo "$1 $(loop_wall "$out")"
}
# Warm-up: settles (and caches) the bed when the case settles, and loads the binary.
"$bin" run "$case_file" --out "$work/warm" --end-time "$end" --threads 2 --quiet --overwrite "${extra[@]}" >/dev/null
for r in $(seq 1 "$rounds"); do
  run r1t1 1 1
  run r2t1 2 1
  run r1t2 1 2
done | tee "$work/results"
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
base=$(awk '$1 == "r1t1" {print $2}' "$work/results" | median)
for c in r1t1 r2t1 r1t2; do
  m=$(awk -v c="$c" '$1 == c {print $2}' "$work/results" | median)
  # The speed-up of each round (its own 1 x 1 over its run, minutes apart), then their median: a shared
  # machine's drift between rounds cancels.
  r=$(awk -v c="$c" '$1 == "r1t1" {b = $2} $1 == c {print b / $2}' "$work/results" | median)
  printf '%s median %.3f s, speed-up over 1 x 1: %.3f of the medians, %.3f median of the rounds\n' "$c" "$m" \
    "$(awk -v b="$base" -v m="$m" 'BEGIN {print b / m}')" "$r"
done
grep -o 'decomposition: .*' "$work/r2t1/log.txt" | tail -1
