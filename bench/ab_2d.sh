#!/usr/bin/env bash
# A/B of two fluidbed binaries on the 2D cases, one thread, alternating A and B so that the drift of a shared
# machine hits both alike: the paper's DEM case (cases/gera1998/dem.toml, 0.2 simulated seconds, settling
# included) and the DEM-only settle-22k (cases/bench/settle-22k.toml, 5000 steps). Issue 12, acceptance 1:
# the dimension-generic code runs the 2D paper case as fast as the code before the refactor.
# Usage: bash bench/ab_2d.sh OLD_BINARY NEW_BINARY [PAIRS=3]     (env: CACHE=settled-bed.csv)
# Each binary gets its own settle.cache, so that the timed runs do not settle: a copy of CACHE (with its .record)
# when given, both then starting from the same bed, else the one its own untimed first run writes.
# Prints one line per run (case, binary, start time, process wall, user + sys CPU, loop wall of cost.json) and the
# medians; the process CPU time is the figure to compare on a loaded machine.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
old="$1" new="$2" pairs="${3:-3}"
export OMP_NUM_THREADS=1
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

for which in old new; do
  if [ -n "${CACHE:-}" ]; then
    cp "$CACHE" "$work/cache-$which.csv"; cp "$CACHE.record" "$work/cache-$which.csv.record"
  else
    bin="$old"; [ "$which" = new ] && bin="$new"
    "$bin" run "$root/cases/gera1998/dem.toml" --set case.end_time=0.001 --set "settle.cache=$work/cache-$which.csv" \
      --threads 1 --out "$work/warm" --overwrite --quiet >/dev/null
  fi
done

declare -A args
args[paper]="$root/cases/gera1998/dem.toml --set case.end_time=0.2 --set settle.cache=$work/cache-@.csv"
args[settle22k]="$root/cases/bench/settle-22k.toml"
results="$work/results"
: >"$results"
for name in paper settle22k; do
  for p in $(seq 1 "$pairs"); do
    for which in old new; do
      bin="$old"; [ "$which" = new ] && bin="$new"
      at="$(date -u +%H:%M:%S)"
      # shellcheck disable=SC2086
      /usr/bin/time -f "%e %U %S" -o "$work/time" "$bin" run ${args[$name]//@/$which} --threads 1 --out "$work/run" \
        --overwrite --quiet >/dev/null
      loop="$(python3 -c "import json; print(json.load(open('$work/run/cost.json'))['wall_s'])")"
      read -r wall user sys <"$work/time"
      cpu="$(python3 -c "print(round($user + $sys, 2))")"
      echo "$name $which $at wall $wall cpu $cpu loop $loop load $(cut -d' ' -f1 /proc/loadavg)" | tee -a "$results"
    done
  done
done
python3 - "$results" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
for name in dict.fromkeys(r[0] for r in rows):
    med = {}
    for which in ("old", "new"):
        sel = [r for r in rows if r[0] == name and r[1] == which]
        med[which] = (statistics.median(float(r[6]) for r in sel), statistics.median(float(r[8]) for r in sel))
        print(f"{name} {which} median cpu {med[which][0]:.2f} s, loop wall {med[which][1]:.2f} s ({len(sel)} runs)")
    print(f"{name} new/old cpu {med['new'][0] / med['old'][0]:.3f}, loop wall {med['new'][1] / med['old'][1]:.3f}")
PY
