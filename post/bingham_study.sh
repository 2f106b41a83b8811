#!/usr/bin/env bash
# The paper's Bingham claim tested (issue 34; docs/validation.md, "The Bingham plastic the paper anticipates"): the
# jet bed of cases/gera1998 with Bingham solids over a sweep of the yield stress and of the regularisation (m and
# the viscosity cap), beside the kinetic-theory TFM and one CFD-DEM run, then the report (Table 2 layout, events,
# voidage maps), post/bubble_reach.py (bubble size, aspect ratio, how far the bed is pushed aside), and the
# 8-packing CFD-DEM ensemble to 0.3 s for the shape and push measures (post/bubble_reach.py --ensemble).
# Usage: bash post/bingham_study.sh [BINARY] [OUT]   (about 1 min of TFM runs; the DEM runs settle their beds first,
# some minutes each the first time)
set -euo pipefail
bin=$(realpath "${1:-build/fluidbed}")
out=${2:-out/bingham-study}
cd "$(dirname "$0")/.."
mkdir -p "$out"
py=/usr/bin/python3  # Debian's, with numpy and vtk (a python3 earlier on PATH may lack them)
tfm() {  # NAME KEY=VALUE...
  local name=$1
  shift
  local sets=()
  for kv in "$@"; do sets+=(--set "$kv"); done
  "$bin" run cases/gera1998/tfm-bingham.toml --out "$out/$name" --overwrite --end-time 1.0 --quiet "${sets[@]}"
  echo "$name: $(grep -o 'bubble: .*' "$out/$name/log.txt")"
}
"$bin" run cases/gera1998/dem.toml --out "$out/dem" --overwrite --end-time 0.5 --quiet
"$bin" run cases/gera1998/tfm.toml --out "$out/kt" --overwrite --end-time 1.0 --quiet
for tau in 0 10 30 50 100 200 300 1000; do tfm "tau$tau" "tfm.yield_stress=$tau"; done
for m in 0.1 1 1000; do tfm "m$m" "tfm.yield_regularisation=$m"; done
for cap in 300 1000; do tfm "cap$cap" "tfm.max_solids_viscosity=$cap"; done
PATH=/usr/bin:$PATH "$bin" report --out "$out/report" --label DEM --label TFM-KT --label bingham-0 --label bingham-50 \
  --label bingham-100 --label bingham-200 "$out/dem" "$out/kt" "$out/tau0" "$out/tau50" "$out/tau100" "$out/tau200"
runs=("$out/dem" "$out/kt")
for r in tau0 tau10 tau30 tau50 tau100 tau200 tau300 tau1000 m0.1 m1 m1000 cap300 cap1000; do runs+=("$out/$r"); done
"$py" post/bubble_reach.py "${runs[@]}" --times 0.1 0.2 0.3 --csv "$out/reach.csv" | tee "$out/reach.md"
"$bin" ensemble cases/gera1998/dem.toml -n 8 --jobs 2 --threads 1 --end-time 0.3 --out "$out/dem-ensemble" --overwrite \
  --quiet
"$py" post/bubble_reach.py "$out"/dem-ensemble/seed-* --times 0.1 0.2 0.3 --ensemble | tee "$out/reach-dem-ensemble.md"
