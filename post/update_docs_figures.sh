#!/usr/bin/env bash
# Copy the main figures of a `make demo` report into docs/figures/ (small PNGs shown by the README and
# docs/validation.md). Run after `make demo`.
set -euo pipefail
cd "$(dirname "$0")/.."
src=${1:-out/report}
mkdir -p docs/figures
for f in voidage layers_particles species_particles layers_tracers nose_height rise_velocity throughflow_ratio pressure_drop rise_vs_correlation mixing_index; do
  [ -f "$src/figures/$f.png" ] && cp "$src/figures/$f.png" docs/figures/
done
cp "$src/summary.md" docs/figures/summary.md
echo "docs/figures updated from $src"
