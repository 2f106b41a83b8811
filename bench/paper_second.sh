#!/usr/bin/env bash
# The paper's DEM case over the whole simulated second (docs/performance.md section 22), two binaries alternating,
# both from one settled bed (CACHE; made by the first run if it does not exist, not timed).
# Usage: bash bench/paper_second.sh OLD NEW CACHE.csv [PAIRS=2] [THREADS=2] [END=1.0]
# Figures per run: the loop wall (monitor wall_s at the last row), the process wall, and CPU (user + sys).
set -euo pipefail
old="$1" new="$2" cache="$3" pairs="${4:-2}" threads="${5:-2}" end="${6:-1.0}"
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
[ -f "$cache" ] || "$old" run "$root/cases/gera1998/dem.toml" --end-time 0.001 --set "settle.cache=$cache" \
  --out "$work/warm" --overwrite --quiet >/dev/null
for p in $(seq 1 "$pairs"); do
  for which in old new; do
    bin="$old"; [ "$which" = new ] && bin="$new"
    at="$(date -u +%H:%M:%S)"
    /usr/bin/time -f "%e %U %S" -o "$work/time" "$bin" run "$root/cases/gera1998/dem.toml" --end-time "$end" \
      --set "settle.cache=$cache" --threads "$threads" --out "$work/run-$which" --overwrite --quiet >/dev/null
    read -r wall user sys <"$work/time"
    loop="$(tail -1 "$work/run-$which/monitor.csv" | awk -F, '{print $NF}')"
    echo "$which $at loop $loop wall $wall cpu $(awk "BEGIN { printf \"%.2f\", $user + $sys }") load $(cut -d' ' -f1 /proc/loadavg)"
  done
  # the same results from both binaries (every column of monitor.csv but the wall time)
  if cmp -s <(cut -d, -f1-19 "$work/run-old/monitor.csv") <(cut -d, -f1-19 "$work/run-new/monitor.csv") &&
     cmp -s "$work/run-old/bubble.csv" "$work/run-new/bubble.csv"; then echo "pair $p: monitor and bubble identical"
  else echo "pair $p: RESULTS DIFFER"; fi
done
