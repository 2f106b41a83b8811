#!/usr/bin/env bash
# A/B of two fluidbed binaries on the 3D DEM-only settling of 100,000 spheres (cases/bench/settle-100k-3d.toml,
# 2,000 steps of 2e-4 s, from the placement bench/lammps/place3d.py writes, the one bench/peer_lammps_3d.sh gives
# both codes), old and new alternating so that the drift of a shared machine hits both alike. Each run reports its
# wall time, its process CPU time, and the final kinetic energy: equal energies are the check that the change kept
# the bits. Prints the medians and the new/old ratio of the medians.
# Usage: bash bench/ab_settle_3d.sh OLD_BINARY NEW_BINARY [PAIRS=3] [THREADS=1] [SKIN_M=0.002]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
old="$1" new="$2" pairs="${3:-3}" threads="${4:-1}" skin="${5:-0.002}"
bed="$root/out/bench/settle-100k-3d"
mkdir -p "$root/out/bench"
[ -f "$bed.csv" ] || python3 "$here/lammps/place3d.py" --count 100000 --width 0.3 --height 0.6 --depth 0.08 \
  --diameter 0.004 --csv "$bed.csv" --data "$bed.data" >&2
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
: >"$work/results"
for p in $(seq 1 "$pairs"); do
  for which in old new; do
    bin="$old"; [ "$which" = new ] && bin="$new"
    OMP_NUM_THREADS="$threads" /usr/bin/time -f "%e %U %S" -o "$work/time" "$bin" run \
      "$root/cases/bench/settle-100k-3d.toml" --threads "$threads" --out "$work/run" --overwrite --quiet \
      --set "dem.skin=$skin" --set output.interval=100 --set output.monitor_interval=0.01 \
      --set output.particles=false --set particles.source=file --set "particles.file=$bed.csv" >/dev/null
    read -r wall user sys <"$work/time"
    energy="$(tail -1 "$work/run/monitor.csv" | cut -d, -f2)"
    rebuilds="$(python3 -c "
import csv; r = list(csv.DictReader(open('$work/run/monitor.csv'))); print(r[-1]['neighbor_rebuilds'])")"
    printf '%s pair %d: wall %s s, cpu %s s, rebuilds %s, kinetic energy %s J\n' "$which" "$p" "$wall" \
      "$(python3 -c "print(round($user + $sys, 2))")" "$rebuilds" "$energy"
    echo "$which $wall $energy" >>"$work/results"
  done
done
python3 "$here/ab_medians.py" "$work/results" wall "final kinetic energy"
