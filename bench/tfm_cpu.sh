#!/usr/bin/env bash
# CPU time (user + system, /usr/bin/time) per simulated second of the paper's TFM case, two binaries alternating
# (docs/performance.md section 20): on a shared machine the CPU time drifts less than the wall time. Runs to
# END (0.5 s) with output.fields = false; prints every run and the medians per binary and thread count.
# Usage: bash bench/tfm_cpu.sh OLD_ROOT NEW_ROOT [PAIRS=3] [THREADS="1 2"] [END=0.5]
set -euo pipefail
old="$1" new="$2" pairs="${3:-3}" threads="${4:-1 2}" end="${5:-0.5}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for p in $(seq 1 "$pairs"); do
  echo "# pair $p, load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%H:%M:%S) UTC" >&2
  for t in $threads; do
    for which in old new; do
      root="$old"; [ "$which" = new ] && root="$new"
      /usr/bin/time -f "%U %S %e" -o "$work/time" "$root/build/fluidbed" run "$root/cases/gera1998/tfm.toml" \
        --end-time "$end" --threads "$t" --set output.fields=false --out "$work/tfm" --overwrite --quiet >/dev/null
      read -r u s e < "$work/time"
      echo "$t $which $p $(awk -v u="$u" -v s="$s" -v e="$e" -v t="$end" 'BEGIN { printf "%.3f %.3f", (u + s) / t, e / t }')"
    done
  done
done | tee "$work/results"
echo "medians per simulated s (threads binary cpu wall):"
awk '{ k = $1 " " $2; a[k] = a[k] " " $4; b[k] = b[k] " " $5 } END { for (k in a) print k "|" a[k] "|" b[k] }' "$work/results" |
  sort | while IFS='|' read -r k va vb; do
    med() { printf '%s\n' $1 | sort -g | awk '{ x[NR] = $1 } END { print x[int((NR + 1) / 2)] }'; }
    echo "$k $(med "$va") $(med "$vb")"
  done
