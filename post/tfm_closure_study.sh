#!/usr/bin/env bash
# The TFM's open question on the paper's case (issue 32, item 3; docs/validation.md, "The TFM after the jet
# closes"): after the jet closes the TFM's gas velocity above the nose is about half the CFD-DEM's. Runs the paper's
# TFM case (cases/gera1998/tfm.toml, kinetic theory) changing one thing at a time: the grid (0.02, 0.01, 0.005 m
# cells), the frictional closure, the drag law, the restitution and the packing limit, then tabulates each run's
# Table 2 quantities and bubble events against the 8-packing CFD-DEM ensemble (post/tfm_closure_table.py).
# Usage: bash post/tfm_closure_study.sh [BINARY] [OUT] [JOBS]   (about 10 min on 2 cores, most of it the finest grid)
set -euo pipefail
bin=$(realpath "${1:-build/fluidbed}")
out=${2:-out/tfm-closure-study}
jobs=${3:-2}
cd "$(dirname "$0")/.."
mkdir -p "$out"
runs=(
  "base"
  "grid-0.01 grid.cell_width=0.01 grid.cell_height=0.01"
  "grid-0.005 grid.cell_width=0.005 grid.cell_height=0.005"
  "grid-0.005-cfl-0.25 grid.cell_width=0.005 grid.cell_height=0.005 tfm.cfl=0.25"
  "johnson-jackson tfm.frictional_model=johnson_jackson"
  "johnson-jackson-0.40 tfm.frictional_model=johnson_jackson tfm.max_compaction=0.03"
  "srivastava-sundaresan tfm.frictional_model=srivastava_sundaresan"
  "srivastava-sundaresan-0.40 tfm.frictional_model=srivastava_sundaresan tfm.max_compaction=0.03"
  "srivastava-sundaresan-grid-0.01 tfm.frictional_model=srivastava_sundaresan grid.cell_width=0.01 grid.cell_height=0.01"
  "gidaspow coupling.drag_law=gidaspow"
  "di-felice coupling.drag_law=di-felice"
  "beetstra coupling.drag_law=beetstra"
  "restitution-0.95 tfm.restitution=0.95"
  "restitution-0.97 tfm.restitution=0.97"
  "restitution-0.99 tfm.restitution=0.99"
  "compaction-0.005 tfm.max_compaction=0.005"
  "compaction-0.0075 tfm.max_compaction=0.0075"
  "compaction-0.01 tfm.max_compaction=0.01"
  "compaction-0.005-grid-0.01 tfm.max_compaction=0.005 grid.cell_width=0.01 grid.cell_height=0.01"
  "compaction-0.03 tfm.max_compaction=0.03"
  "eps-star-0.42 tfm.eps_star=0.42"
  "eps-star-0.41 tfm.eps_star=0.41"
)
one() {  # NAME KEY=VALUE...
  local name=$1
  shift
  local sets=()
  for kv in "$@"; do sets+=(--set "$kv"); done
  # A run that stops with a diagnosis (exit 3) is a result too: the table marks it.
  "$bin" run cases/gera1998/tfm.toml --out "$out/$name" --overwrite --end-time 1.0 --threads 1 --quiet \
    --set output.fields=false "${sets[@]}" || echo "$name: stopped with exit $?"
}
export -f one
export bin out
printf '%s\n' "${runs[@]}" | xargs -P "$jobs" -I{} bash -c 'one {}'
names=()
for r in "${runs[@]}"; do names+=("$out/${r%% *}"); done
/usr/bin/python3 post/tfm_closure_table.py "${names[@]}" | tee "$out/table.md"
