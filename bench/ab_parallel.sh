#!/usr/bin/env bash
# A/B of two fluidbed binaries on 2 ranks x 1 thread, against 1 rank x 1 thread of the new one, run in turn ROUNDS
# times so that a shared machine's drift hits each alike: the loop's wall time of each run (the log's "N steps in X
# s wall"), its blocks dealt again and its ranks' compute range, then the medians and each binary's 2-rank
# speed-up, the median of the rounds' own ratios (docs/parallel.md). Each binary runs the case files of this tree.
# Usage: bash bench/ab_parallel.sh OLD_BINARY NEW_BINARY CASE END_TIME ROUNDS [--set KEY=VALUE ...]
# OLD_ARGS / NEW_ARGS (environment, words) go to that side's runs only: one binary against itself with an option
# off and on, e.g. OLD_ARGS="--set parallel.forces_ahead=false" and the same binary twice.
set -euo pipefail
old=$(realpath "$1") new=$(realpath "$2") case_file=$3 end=$4 rounds=$5
shift 5
extra=("$@")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_WAIT_POLICY=passive
loop_wall() { grep -o '[0-9]* steps in [0-9.]* s wall' "$1/log.txt" | tail -1 | awk '{print $4}'; }
deals() { grep -o 'dealt again [0-9]* times\|compute [0-9.]*-[0-9.]* s per rank' "$1/log.txt" | tail -2 | paste -sd' '; }
read -r -a old_args <<< "${OLD_ARGS:-}"
read -r -a new_args <<< "${NEW_ARGS:-}"
run() {  # run LABEL BINARY RANKS [ARGS ...]
  local out="$work/$1" label=$1 bin=$2 ranks=$3
  shift 3
  if [[ $ranks -eq 1 ]]; then
    "$bin" run "$case_file" --out "$out" --end-time "$end" --threads 1 --quiet --overwrite "${extra[@]}" "$@"
  else
    mpiexec -n "$ranks" --bind-to core "$bin" run "$case_file" --out "$out" --end-time "$end" --threads 1 --quiet \
      --overwrite "${extra[@]}" "$@"
  fi
  set -- "$label" "$bin" "$ranks"
  echo "$1 $(loop_wall "$out") $( [[ $3 -eq 1 ]] || deals "$out")"
}
# Warm-up: settles (and caches) the bed when the case settles, and loads the binaries.
"$new" run "$case_file" --out "$work/warm" --end-time "$end" --threads 2 --quiet --overwrite "${extra[@]}" >/dev/null
for r in $(seq 1 "$rounds"); do
  run r1t1 "$new" 1 "${new_args[@]}"
  run old-r2 "$old" 2 "${old_args[@]}"
  run new-r2 "$new" 2 "${new_args[@]}"
done | tee "$work/results"
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
for c in r1t1 old-r2 new-r2; do
  m=$(awk -v c="$c" '$1 == c {print $2}' "$work/results" | median)
  r=$(awk -v c="$c" '$1 == "r1t1" {b = $2} $1 == c {print b / $2}' "$work/results" | median)
  printf '%s median %.3f s, speed-up over 1 x 1: %.3f median of the rounds\n' "$c" "$m" "$r"
done
r=$(awk '$1 == "old-r2" {o = $2} $1 == "new-r2" {print o / $2}' "$work/results" | median)
printf 'new over old (2 ranks): %.3f median of the rounds\n' "$r"
