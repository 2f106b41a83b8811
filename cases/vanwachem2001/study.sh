#!/usr/bin/env bash
# The runs of issue 32's study of the van Wachem bed (README.md, "Issue 32, item 1"): dem.toml as it is, with the
# probes of every bed-height definition, and for a factor run one change given with --set.
#   height-definitions   0-4 s, a particle frame every 0.01 s (height_definitions.py reads them)
#   factor               0-3 s (1-3 s analysed), particle frames every 0.5 s only
# Usage: bash cases/vanwachem2001/study.sh BINARY OUT {height-definitions|factor} [fluidbed run options...]
# e.g.   bash cases/vanwachem2001/study.sh build/fluidbed out/vw-rolling-none factor \
#            --set 'contact.rolling="none"' --set contact.rolling_friction=0 --set contact.wall_rolling_friction=0
set -euo pipefail
bin=$1 out=$2 kind=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
# The case's four probes (dem.toml), then the bed height where the cross-section mean solids fraction falls to
# 0.05 and 0.1, and the 99th and 95th percentiles of the particles' tops (kind = "particle_top").
probes='probe=[{kind="pressure_drop", name="rel45", height=0.045, height_top=0.54},
 {kind="point", name="tap45", position=[0.045, 0.045, 0.004]},
 {kind="plane", name="plane45", height=0.045},
 {kind="bed_height", name="bed", solids_fraction=0.3},
 {kind="bed_height", name="bed05", solids_fraction=0.05},
 {kind="bed_height", name="bed10", solids_fraction=0.1},
 {kind="particle_top", name="top99", percentile=99.0},
 {kind="particle_top", name="top95", percentile=95.0}]'
case $kind in
  height-definitions) opts=(--end-time 4.0 --set output.particle_interval=0.01) ;;
  factor) opts=(--end-time 3.0 --set output.particle_interval=0.5) ;;
  *) echo "study.sh: unknown run kind '$kind' (height-definitions or factor)" >&2; exit 2 ;;
esac
exec "$bin" run "$here/dem.toml" --out "$out" --threads 2 --set "${probes//$'\n'/}" "${opts[@]}" "$@"
