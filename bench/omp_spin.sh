#!/usr/bin/env bash
# The paper's DEM case with several OpenMP spin counts, alternating (docs/performance.md section 22): libgomp's
# GOMP_SPINCOUNT under OMP_WAIT_POLICY=passive decides how long a worker spins before it sleeps on a futex.
# Usage: bash bench/omp_spin.sh FLUIDBED CACHE.csv [ROUNDS=3] [THREADS=2] [END=0.15] [SPINS="0 10000 100000"]
# The figure: loop wall from the monitor row at 0.05 s to the end, and the process CPU time (user + sys).
set -euo pipefail
bin="$1" cache="$2" rounds="${3:-3}" threads="${4:-2}" end="${5:-0.15}" spins="${6:-0 10000 100000}"
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for r in $(seq 1 "$rounds"); do
  for s in $spins; do
    at="$(date -u +%H:%M:%S)"
    OMP_WAIT_POLICY=passive GOMP_SPINCOUNT="$s" /usr/bin/time -f "%e %U %S" -o "$work/time" "$bin" run \
      "$root/cases/gera1998/dem.toml" --end-time "$end" --set "settle.cache=$cache" --threads "$threads" \
      --out "$work/run" --overwrite --quiet >/dev/null
    read -r wall user sys <"$work/time"
    loop="$(awk -F, 'NR > 1 && a == "" && $1 >= 0.05 - 1e-9 { a = $NF } { b = $NF } END { printf "%.2f", b - a }' "$work/run/monitor.csv")"
    echo "spin $s $at loop $loop wall $wall cpu $(awk "BEGIN { printf \"%.2f\", $user + $sys }") load $(cut -d' ' -f1 /proc/loadavg)"
  done
done
