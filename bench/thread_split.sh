#!/usr/bin/env bash
# The CPU time of each thread of the paper's DEM case (docs/performance.md section 22), two binaries alternating:
# on a loaded 2-core machine the wall time scatters, but the main thread's CPU time is the length of the run's
# critical path (the serial parts plus the main thread's share of the parallel ones).
# Usage: bash bench/thread_split.sh OLD NEW CACHE.csv [PAIRS=2] [END=0.25]   (2 threads; perf, cpu-clock at 1 kHz)
set -euo pipefail
old="$1" new="$2" cache="$3" pairs="${4:-2}" end="${5:-0.25}"
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for p in $(seq 1 "$pairs"); do
  for which in old new; do
    bin="$old"; [ "$which" = new ] && bin="$new"
    at="$(date -u +%H:%M:%S)"
    perf record -q -F 1000 -e cpu-clock -o "$work/perf.data" "$bin" run "$root/cases/gera1998/dem.toml" \
      --end-time "$end" --set "settle.cache=$cache" --threads 2 --out "$work/run" --overwrite --quiet >/dev/null 2>&1
    # samples per thread (1 ms each), the busiest first: the main thread, then the worker
    split="$(perf report -i "$work/perf.data" --no-children --sort pid --stdio -g none -F sample,pid 2>/dev/null |
      awk '/^ *[0-9]+ / { printf "%s %.2f s  ", $2, $1 / 1000 }')"
    echo "$which $at $split load $(cut -d' ' -f1 /proc/loadavg)"
  done
done
