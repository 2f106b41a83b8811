#!/usr/bin/env bash
# Settling (issue 11). The settle cache stands only for the bed it was settled as: a run with other particles, contact law,
# time step or placement settles anew and replaces it, a run with the same bed reuses it and equals a run that
# settled its own bed, bit for bit.
source "$(dirname "$0")/lib.sh"

cat > "$WORK/c.toml" <<TOML
case.name = "cache"
case.end_time = 0.004
domain.width = 0.06
domain.height = 0.2
particles.count = 120
particles.fill_height = 0.2
species = [{diameter = 0.004, density = 2700.0}]
dem.time_step = 1e-4
gas.enabled = false
settle.max_time = 0.3
settle.cache = "$WORK/cache/bed.csv"
output.interval = 0.002
output.checkpoint_interval = 0.0
output.particles_csv = true
TOML
run() { "$FLUIDBED" run "$WORK/c.toml" --quiet --threads 1 --overwrite "$@"; }

expect 0 "" "first run settles and writes the cache" run --out "$WORK/a"
expect 0 "" "the cache has its record" test -s "$WORK/cache/bed.csv.record"
expect 0 "saved the settled bed" "the first run saved the cache" cat "$WORK/a/log.txt"
expect 0 "" "same bed: rerun" run --out "$WORK/b"
expect 0 "reusing the settled bed" "the same bed reuses the cache" cat "$WORK/b/log.txt"
expect 0 "" "reused bed equals the settled one" diff "$WORK/a/particles/000002.csv" "$WORK/b/particles/000002.csv"

# Another diameter: the cache must not stand for it (before: silently reused, 4 mm positions for 3 mm discs).
expect 0 "note: settle.cache .*will not be reused \((particles.gap|species\[0\]\.diameter) = " "check names a stale key" \
  "$FLUIDBED" check "$WORK/c.toml" --set 'species[0].diameter=0.003'
expect 0 "" "another diameter runs" run --out "$WORK/c" --set 'species[0].diameter=0.003'
expect 0 "not reusing the settled bed .*settled with other parameters" "the log says why it settles anew" cat "$WORK/c/log.txt"
expect 0 "" "a fresh settle of 3 mm equals it" \
  "$FLUIDBED" run "$WORK/c.toml" --quiet --threads 1 --out "$WORK/d" --set 'species[0].diameter=0.003' --set 'settle.cache=""'
expect 0 "" "cache-replaced run equals the uncached run" diff "$WORK/c/particles/000002.csv" "$WORK/d/particles/000002.csv"
# The cache now holds the 3 mm bed; the 4 mm case settles anew again and gets its own result back.
expect 0 "" "back to 4 mm" run --out "$WORK/e"
expect 0 "not reusing the settled bed .*settled with other parameters" "4 mm is not served the 3 mm bed" cat "$WORK/e/log.txt"
expect 0 "" "and equals the first run" diff "$WORK/a/particles/000002.csv" "$WORK/e/particles/000002.csv"

# A 3D bed depends on its depth (before: the record had no depth, and a deeper box was served the shallower bed).
cat > "$WORK/c3.toml" <<TOML
case.name = "cache3d"
case.dimension = 3
case.end_time = 0.002
domain.width = 0.04
domain.height = 0.1
domain.depth = 0.012
particles.count = 120
particles.fill_height = 0.1
species = [{diameter = 0.004, density = 2700.0}]
dem.time_step = 1e-4
gas.enabled = false
settle.max_time = 0.2
settle.cache = "$WORK/cache/bed3.csv"
output.interval = 0.002
output.checkpoint_interval = 0.0
TOML
run3() { "$FLUIDBED" run "$WORK/c3.toml" --quiet --threads 1 --overwrite "$@"; }
expect 0 "" "a 3D bed settles and writes the cache" run3 --out "$WORK/f"
expect 0 "" "same 3D bed: rerun" run3 --out "$WORK/g"
expect 0 "reusing the settled bed" "the same 3D bed reuses the cache" cat "$WORK/g/log.txt"
expect 0 "" "a deeper 3D box runs" run3 --out "$WORK/h" --set domain.depth=0.016
expect 0 "not reusing the settled bed .*domain.depth = 0.016" "a deeper box is not served the shallower bed" \
  cat "$WORK/h/log.txt"

# A binary bed placed up to the top: 2 mm particles rebound off the pile above the fill height. Settling happens
# under a lid (before: exit 3, "particle 1171 left through the open top" at t = 0.47 s of settling).
cat > "$WORK/lid.toml" <<TOML
case.name = "lid"
case.end_time = 0.0002
domain.width = 0.1
domain.height = 0.6
species = [{diameter = 0.004, fraction = 0.5}, {diameter = 0.002, fraction = 0.5}]
particles.count = 1300
dem.time_step = 5e-5
gas.enabled = false
settle.max_time = 1.0
output.checkpoint_interval = 0.0
TOML
expect 0 "" "a binary bed settles under a lid" "$FLUIDBED" run "$WORK/lid.toml" --quiet --threads 1 --out "$WORK/lid"
expect 0 "settled in vacuum" "its log says it settled" cat "$WORK/lid/log.txt"
finish
