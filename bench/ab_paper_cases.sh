#!/usr/bin/env bash
# A/B of two fluidbed binaries on the paper's two cases as a user runs them, old and new alternating so that the
# drift of a shared machine hits both alike (docs/performance.md section 16):
#   dem   cases/gera1998/dem.toml to 0.3 s, 2 threads, the cached settled bed (not timed)
#   tfm2  cases/gera1998/tfm.toml to 1 s, 2 threads
#   tfm1  cases/gera1998/tfm.toml to 1 s, 1 thread
# The figure is wall_s of the last monitor.csv row (the run's loop, without settling). Each binary runs the cases
# of its own source tree (its defaults).
# Usage: bash bench/ab_paper_cases.sh OLD_ROOT NEW_ROOT [PAIRS=3]   (a ROOT holds build/fluidbed and cases/)
set -euo pipefail
old="$1" new="$2" pairs="${3:-3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
last_wall() { tail -1 "$1/monitor.csv" | awk -F, '{print $NF}'; }
for which in old new; do  # warm each tree's settled-bed cache
  root="$old"; [ "$which" = new ] && root="$new"
  "$root/build/fluidbed" run "$root/cases/gera1998/dem.toml" --end-time 0.001 --out "$work/warm" --overwrite --quiet >/dev/null
done
for p in $(seq 1 "$pairs"); do
  for which in old new; do
    root="$old"; [ "$which" = new ] && root="$new"
    bin="$root/build/fluidbed"
    "$bin" run "$root/cases/gera1998/dem.toml" --end-time 0.3 --threads 2 --out "$work/dem" --quiet >/dev/null
    echo "dem  $which $p $(last_wall "$work/dem")"
    for t in 2 1; do
      "$bin" run "$root/cases/gera1998/tfm.toml" --threads "$t" --out "$work/tfm" --overwrite --quiet >/dev/null
      echo "tfm$t $which $p $(last_wall "$work/tfm")"
    done
    rm -rf "$work/dem" "$work/tfm"
  done
done | tee "$work/results"
echo "medians (s):"
awk '{ v[$1" "$2] = v[$1" "$2] " " $4 } END { for (k in v) print k, v[k] }' "$work/results" | sort |
  while read -r c w vals; do
    printf '%-5s %-4s %s\n' "$c" "$w" "$(printf '%s\n' $vals | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')"
  done
