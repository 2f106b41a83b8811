#!/usr/bin/env bash
# Regenerates the frozen outputs (tests/oracle/gera1998/: the paper's cases, a 3D CFD-DEM and a 3D TFM case), the regression oracle that a
# refactor is compared against (issue 12: "freeze today's 2D outputs before changing a type").
# Usage: bash tests/oracle/regenerate.sh [build/fluidbed]
# Only when a change is meant to move the results: say in the commit which numbers moved, by how much and why.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
fluidbed=$(realpath "${1:-$root/build/fluidbed}")
source "$root/tests/oracle/cases.sh"
dest="$root/tests/oracle/gera1998"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$dest"
for name in "${ORACLE_CASES[@]}"; do
  oracle_run "$fluidbed" "$root" "$name" "$work/$name"
  for f in bubble.csv monitor.csv; do oracle_strip "$work/$name/$f" > "$dest/$name.$f"; done
done
{
  echo "# Provenance of the frozen outputs in this folder"
  echo
  echo "- commit: $(git -C "$root" rev-parse HEAD)$(git -C "$root" diff --quiet HEAD -- src apps cases || echo ' (with uncommitted changes)')"
  echo "- made: $(date -u +%Y-%m-%d) by tests/oracle/regenerate.sh on $(uname -m), $(c++ --version | head -n 1)"
  echo "- runs: see tests/oracle/cases.sh (the paper's DEM case to ${ORACLE_DEM_END} s from a bed settled by the run,"
  echo "  the three TFM rheologies to ${ORACLE_TFM_END} s; in 3D tests/oracle/dem3d.toml to ${ORACLE_DEM3D_END} s and"
  echo "  cases/tfm3d/slab.toml to ${ORACLE_TFM3D_END} s); monitor.csv without its wall_s column"
} > "$dest/PROVENANCE.md"
echo "oracle written to $dest"
