#!/usr/bin/env bash
# Issue 31's five targets one after the other on this machine (docs/performance.md section 37): the 3D and 2D
# DEM-only settling against LAMMPS (one core each; the 3D run also gives the bytes per sphere), the paper's CFD-DEM
# case over one simulated second (RUNS runs) and the van Wachem bed over VW_END seconds (2 runs), both on THREADS
# threads from their settled beds (settled and cached by a first, untimed run), and the paper's second once on one
# thread (the bounds of section 38 are given for both). VW_RUNS=1 with VW_END=6 runs the van Wachem row whole.
# Usage: [VW_RUNS=2] bash bench/targets.sh [BUILD_DIR] [THREADS=2] [RUNS=3] [VW_END=0.3]
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
build="${1:-$root/build}" threads="${2:-2}" runs="${3:-3}" vw_end="${4:-0.3}"
fluidbed="$build/fluidbed"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# One timed run of CASE to END on THREADS threads from its cached settled bed CACHE, reported as run number R.
timed_run() {
  local case="$1" end="$2" threads="$3" cache="$4" r="$5"
  "$fluidbed" run "$case" --end-time "$end" --set "settle.cache=$cache" --threads "$threads" --out "$work/run" \
    --overwrite --quiet >/dev/null
  echo "run $r $(date -u +%H:%M:%S) loop_wall_s $(tail -1 "$work/run/monitor.csv" | awk -F, '{ print $NF }')" \
    "load $(cut -d' ' -f1 /proc/loadavg)"
}
echo "== start $(date -u +%H:%M:%S) UTC, $(git -C "$root" rev-parse --short HEAD)"
echo "== 3D settling of 100,000 spheres against LAMMPS, one core, 2000 steps, 3 repeats, and the bytes per sphere"
REPEATS=3 bash "$here/peer_lammps_3d.sh" "$build" 2000 2>&1 | grep -v "^#"
echo "== 2D settle-22k against LAMMPS, one core, 5000 steps"
bash "$here/peer_lammps.sh" "$build" 5000 2>&1 | grep -v "^#"
echo "== the paper's case, $threads threads, one simulated second, $runs runs"
"$fluidbed" run "$root/cases/gera1998/dem.toml" --end-time 0.001 --set "settle.cache=$work/paper.csv" \
  --out "$work/warm" --overwrite --quiet --threads "$threads" >/dev/null
for r in $(seq 1 "$runs"); do timed_run "$root/cases/gera1998/dem.toml" 1.0 "$threads" "$work/paper.csv" "$r"; done
echo "== the paper's case, one thread, one simulated second, 1 run"
timed_run "$root/cases/gera1998/dem.toml" 1.0 1 "$work/paper.csv" 1
vw_runs="${VW_RUNS:-2}"
echo "== the van Wachem bed, $threads threads, $vw_end s from the settled bed, $vw_runs runs"
"$fluidbed" run "$root/cases/vanwachem2001/dem.toml" --end-time 0.001 --set "settle.cache=$work/vw.csv" \
  --out "$work/warm" --overwrite --quiet --threads "$threads" >/dev/null
for r in $(seq 1 "$vw_runs"); do
  timed_run "$root/cases/vanwachem2001/dem.toml" "$vw_end" "$threads" "$work/vw.csv" "$r"
done
echo "== end $(date -u +%H:%M:%S) UTC"
