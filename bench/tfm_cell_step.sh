#!/usr/bin/env bash
# Cost of the two-fluid model per simulated second and per cell-step (issue 13, acceptance 4): the paper's 2D case
# and the two 3D cases of cases/tfm3d, each run REPEATS times in turn (so that a drift of the machine's speed
# touches every case alike), with output.fields = false. Prints every run and the median per case of the CPU time
# (user + system) and wall time per simulated second and the CPU time per cell-step (from the run's cost.json).
# Usage: bash bench/tfm_cell_step.sh ROOT [REPEATS=3] [THREADS=1] [END=1.0]
set -euo pipefail
root="$1" repeats="${2:-3}" threads="${3:-1}" end="${4:-1.0}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cases=(gera1998/tfm tfm3d/slab tfm3d/column)
echo "# $(date -u +%Y-%m-%dT%H:%M) UTC, $(nproc) cores, threads $threads, end $end s, commit $(git -C "$root" rev-parse --short HEAD)"
echo "# case run cells steps_per_s cpu_s_per_s wall_s_per_s us_cpu_per_cell_step load"
for r in $(seq 1 "$repeats"); do
  for c in "${cases[@]}"; do
    load="$(cut -d' ' -f1 /proc/loadavg)"
    /usr/bin/time -f "%U %S %e" -o "$work/time" "$root/build/fluidbed" run "$root/cases/$c.toml" --end-time "$end" \
      --threads "$threads" --set output.fields=false --out "$work/out" --overwrite --quiet >/dev/null
    read -r u s e < "$work/time"
    python3 - "$work/out/cost.json" "$c" "$r" "$u" "$s" "$e" "$end" "$load" <<'PY'
import json, sys
cost = json.load(open(sys.argv[1]))
case, run, u, s, e, end, load = sys.argv[2], sys.argv[3], *map(float, sys.argv[4:9])
cpu = u + s
print(f"{case} {run} {cost['cells']} {cost['time_steps'] / end:.0f} {cpu / end:.2f} {e / end:.2f} "
      f"{1e6 * cpu / (cost['time_steps'] * cost['cells']):.3f} {load:.2f}")
PY
  done
done | tee "$work/results"
echo "# medians: case cpu_s_per_s wall_s_per_s us_cpu_per_cell_step"
for c in "${cases[@]}"; do
  awk -v c="$c" '$1 == c { print $5, $6, $7 }' "$work/results" | python3 -c "
import sys, statistics as st
rows = [list(map(float, l.split())) for l in sys.stdin]
print('$c', *(f'{st.median(col):.3f}' for col in zip(*rows)))"
done
