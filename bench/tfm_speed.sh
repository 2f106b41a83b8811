#!/usr/bin/env bash
# Wall time per simulated second of the paper's TFM case (cases/gera1998/tfm.toml, run as a user runs it, to 1 s),
# two binaries alternating so that the drift of a shared machine hits both alike (docs/performance.md section 17).
# Each run gives two figures from its monitor.csv wall_s column: the whole second (wall_s at t = 1 s) and the
# window 0.1-0.5 s ((wall_s(0.5) - wall_s(0.1)) / 0.4), the bubble's formation and rise (issue 16, target 3).
# Prints every run, then the median per binary, thread count and figure, with the load average before each pair.
# Usage: bash bench/tfm_speed.sh OLD_ROOT NEW_ROOT [PAIRS=3] [THREADS="1 2"]   (a ROOT holds build/fluidbed, cases/)
set -euo pipefail
old="$1" new="$2" pairs="${3:-3}" threads="${4:-1 2}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
figures() {  # monitor.csv -> "whole window" in s per simulated s
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "wall_s") w = i; next }
           { t = $1 + 0; if (t0 == "" && t >= 0.1 - 1e-9) t0 = $w; if (t5 == "" && t >= 0.5 - 1e-9) t5 = $w; last = $w; tl = t }
           END { printf "%.3f %.3f\n", last / tl, (t5 - t0) / 0.4 }' "$1"
}
for p in $(seq 1 "$pairs"); do
  echo "# pair $p, load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%H:%M:%S) UTC" >&2
  for t in $threads; do
    for which in old new; do
      root="$old"; [ "$which" = new ] && root="$new"
      "$root/build/fluidbed" run "$root/cases/gera1998/tfm.toml" --threads "$t" --out "$work/tfm" --overwrite --quiet >/dev/null
      echo "$t $which $p $(figures "$work/tfm/monitor.csv")"
    done
  done
done | tee "$work/results"
echo "medians, s of wall per simulated s (threads binary whole-second window-0.1-0.5):"
awk '{ k = $1 " " $2; a[k] = a[k] " " $4; b[k] = b[k] " " $5 } END { for (k in a) print k "|" a[k] "|" b[k] }' "$work/results" |
  sort | while IFS='|' read -r k va vb; do
    med() { printf '%s\n' $1 | sort -g | awk '{ x[NR] = $1 } END { print x[int((NR + 1) / 2)] }'; }
    echo "$k $(med "$va") $(med "$vb")"
  done
