#!/usr/bin/env bash
# A/B of two fluidbed binaries on the van Wachem validation bed (cases/vanwachem2001/dem.toml: 17,562 spheres,
# Hertz-Mindlin with Tsuji's damping and constant rolling torque, CFD-DEM in 3D), its first END seconds from the
# cached settled bed (the first run settles and caches it, not timed), old and new alternating. The figure is the
# time loop's wall time ("... steps in X s wall" of the log). The check that the change kept the bits: monitor.csv
# (all but its wall_s column) and probes.csv of the last pair byte-identical.
# Usage: bash bench/ab_vanwachem.sh OLD_BINARY NEW_BINARY [PAIRS=3] [THREADS=1] [END_S=0.02]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
old="$1" new="$2" pairs="${3:-3}" threads="${4:-1}" end="${5:-0.02}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
: >"$work/results"
for p in $(seq 1 "$pairs"); do
  for which in old new; do
    bin="$old"; [ "$which" = new ] && bin="$new"
    OMP_NUM_THREADS="$threads" "$bin" run "$root/cases/vanwachem2001/dem.toml" --threads "$threads" \
      --out "$work/$which" --overwrite --set "case.end_time=$end" >"$work/log" 2>&1
    wall="$(sed -nE 's/.* steps in ([0-9.]+) s wall.*/\1/p' "$work/log")"
    printf '%s pair %d: loop wall %s s\n' "$which" "$p" "$wall"
    echo "$which $wall" >>"$work/results"
  done
done
python3 "$here/ab_medians.py" "$work/results" "loop wall"
same=identical
for w in old new; do cut -d, -f1-19 "$work/$w/monitor.csv" >"$work/$w.monitor"; done
cmp -s "$work/old.monitor" "$work/new.monitor" || same=differ
cmp -s "$work/old/probes.csv" "$work/new/probes.csv" || same=differ
head -1 "$work/old/monitor.csv" | cut -d, -f20 | grep -qx wall_s || same="differ (monitor.csv columns moved)"
echo "monitor.csv and probes.csv: $same"
