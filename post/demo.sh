#!/usr/bin/env bash
# make demo: the paper's CFD-DEM and two-fluid cases to 1 s, then the side-by-side report.
# The settled bed of the DEM case is cached in out/cache/ and reused by later runs.
set -euo pipefail
BIN=${1:-build/fluidbed}
cd "$(dirname "$0")/.."
"$BIN" run cases/gera1998/dem.toml --out out/gera1998-dem --overwrite
"$BIN" run cases/gera1998/tfm.toml --out out/gera1998-tfm --overwrite
"$BIN" report out/gera1998-dem out/gera1998-tfm --out out/report
echo
echo "Report: $(pwd)/out/report/summary.md (figures in out/report/figures/)"
