#!/usr/bin/env bash
# The two-fluid model on 2 ranks against 1 rank (issue 30, item 5), run in turn ROUNDS times so that a shared
# machine's drift hits both alike: the step loop's wall time of each run (the log's "N steps in X s wall"), the
# 2-rank run's communication summary (the log's "decomposition:" line), then the medians and the median of the
# rounds' speed-ups. One thread a rank; the case's own pressure backend must be cg-multigrid (or set it below).
# Usage: bash bench/tfm_ranks.sh BINARY CASE END_TIME ROUNDS [--set KEY=VALUE ...]
set -euo pipefail
bin=$(realpath "$1") case_file=$2 end=$3 rounds=$4
shift 4
extra=("$@")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
loop_wall() { grep -o '[0-9]* steps in [0-9.]* s wall' "$1/log.txt" | tail -1 | awk '{print $4}'; }
for r in $(seq 1 "$rounds"); do
  echo "# round $r, load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%H:%M:%S) UTC"
  "$bin" run "$case_file" --out "$work/one" --end-time "$end" --threads 1 --quiet --overwrite \
    --set output.fields=false "${extra[@]}"
  mpiexec -n 2 --bind-to core "$bin" run "$case_file" --out "$work/two" --end-time "$end" --threads 1 --quiet \
    --overwrite --set output.fields=false "${extra[@]}"
  one=$(loop_wall "$work/one") two=$(loop_wall "$work/two")
  echo "one $one two $two speed-up $(awk -v a="$one" -v b="$two" 'BEGIN { printf "%.3f", a / b }')"
  grep -o 'decomposition: .*' "$work/two/log.txt" | tail -1
done | tee "$work/log"
med() { sort -g | awk '{ x[NR] = $1 } END { print x[int((NR + 1) / 2)] }'; }
echo "medians: one rank $(awk '/^one/ { print $2 }' "$work/log" | med) s, two ranks $(awk '/^one/ { print $4 }' "$work/log" | med) s," \
     "speed-up (median of the rounds) $(awk '/^one/ { print $6 }' "$work/log" | med)"
