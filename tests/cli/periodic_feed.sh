#!/usr/bin/env bash
# Periodic particles, outflow through a declared side and a particle feed (issue 14, Models item 5) through the
# command line: the keys are read and checked, `check` reports them, a periodic DEM run with a feed at the top
# and an outflow bottom closes its mass balance in monitor.csv every row (in counts exactly, in kg to 1e-12),
# and the run is the same on 1 and 3 threads and after a restart (the feed's random stream is in the checkpoint).
# The periodic gas has its own script, periodic_gas.sh.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

column() {  # column FILE NAME
  awk -F, -v name="$2" 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == name) c = k; next } { print $c }' "$1"
}

# 100 particles in a 0.05 x 0.15 m box periodic in x, gravity tilted along x so that the bed drifts across the
# periodic side; particles leave through the bottom and 500 per second are fed in near the top.
cat >"$WORK/feed.toml" <<'TOML'
case.name = "feed"
case.end_time = 0.25
case.seed = 3
domain.width = 0.05
domain.height = 0.15
domain.gravity = [3.0, -9.81]
domain.periodic = ["x"]
domain.particle_outflow = ["bottom"]
domain.particle_top = "wall"
particles.count = 100
particles.fill_height = 0.05
particles.layers = 2
settle.enabled = false
gas.enabled = false
grid.cell_width = 0.01
insertion.rate = 500.0
insertion.region_min = [0.0, 0.11]
insertion.region_max = [0.05, 0.14]
insertion.velocity = [0.0, -0.5]
output.interval = 0.05
output.particles_csv = true
output.monitor_interval = 0.005
output.checkpoint_interval = 0.0
TOML

expect 0 "periodic axes .*x: particles leaving" "check reports the periodic axis" "$FLUIDBED" check "$WORK/feed.toml"
expect 0 "outflow sides \(particles\) .*bottom" "check reports the outflow side" "$FLUIDBED" check "$WORK/feed.toml"
expect 0 "particle feed .*500 particles/s" "check reports the feed" "$FLUIDBED" check "$WORK/feed.toml"
expect 0 "periodic axes .*x: particles leaving" "periodic with gas is accepted (tests/cli/periodic_gas.sh runs it)" \
  "$FLUIDBED" check "$WORK/feed.toml" --set gas.enabled=true
expect 2 "domain.particle_outflow.*periodic" "outflow on a periodic side is refused" "$FLUIDBED" check \
  "$WORK/feed.toml" --set 'domain.particle_outflow=["left"]'
expect 2 "domain.periodic.*not one of" "y cannot be periodic" "$FLUIDBED" check "$WORK/feed.toml" \
  --set 'domain.periodic=["y"]'
expect 2 "insertion.mass_rate.*not both" "rate and mass rate together are refused" "$FLUIDBED" check \
  "$WORK/feed.toml" --set insertion.mass_rate=0.01

run_ok "periodic feed: 1 thread" run "$WORK/feed.toml" --out "$WORK/one" --threads 1
m_p=$(awk 'BEGIN { printf "%.17g", 2700 * atan2(0, -1) / 6 * 0.004^3 }')
paste -d, <(column "$WORK/one/monitor.csv" solids_mass_kg) <(column "$WORK/one/monitor.csv" particles_lost) \
  <(column "$WORK/one/monitor.csv" mass_lost_kg) <(column "$WORK/one/monitor.csv" particles_inserted) \
  <(column "$WORK/one/monitor.csv" mass_inserted_kg) >"$WORK/mass.csv"
check "mass balance: bed = initial + inserted - lost, every row (kg to 1e-12, counts exactly)" \
  awk -F, -v m="$m_p" 'NR == 1 { m0 = $1; n0 = $1 / m }
    { n = $1 / m; if (($1 - (m0 + $5 - $3)) ^ 2 > (1e-12 * m0) ^ 2 || (n - (n0 + $4 - $2)) ^ 2 > 1e-6 ||
          ($5 - $4 * m) ^ 2 > (1e-12 * m0) ^ 2) { print "row " NR ": " $0; bad = 1 } }
    END { exit bad }' "$WORK/mass.csv"
check "the feed delivered floor(500 t) particles by the end, and particles left" \
  awk -F, 'END { exit !($4 == 125 && $2 > 10) }' "$WORK/mass.csv"
check "every particle inside the periodic width [0, 0.05) in the last frame" \
  bash -c "f=\$(ls '$WORK/one/particles/'*.csv | tail -1); awk -F, 'NR > 1 && (\$2 < 0 || \$2 >= 0.05) { bad = 1 } END { exit bad }' \"\$f\""
run_ok "periodic feed: 3 threads" run "$WORK/feed.toml" --out "$WORK/three" --threads 3
same_results "1 vs 3 threads" "$WORK/one" "$WORK/three"
run_ok "periodic feed: run to 0.12 s" run "$WORK/feed.toml" --out "$WORK/split" --threads 2 --end-time 0.12
run_ok "periodic feed: restart to 0.25 s" run "$WORK/feed.toml" --out "$WORK/split" --threads 2 \
  --restart "$WORK/split/checkpoints/final.h5"
same_results "restarted" "$WORK/one" "$WORK/split"

# 3D, periodic in x and z, a feed in kg/s: the same on 1 and 2 threads, every particle inside the periodic box.
cat >"$WORK/feed3d.toml" <<'TOML'
case.name = "feed3d"
case.dimension = 3
case.end_time = 0.05
domain.width = 0.04
domain.height = 0.06
domain.depth = 0.04
domain.gravity = [2.0, -9.81, 1.0]
domain.periodic = ["x", "z"]
particles.count = 150
particles.fill_height = 0.04
settle.enabled = false
gas.enabled = false
grid.cell_width = 0.01
insertion.mass_rate = 0.05
insertion.region_min = [0.0, 0.045, 0.0]
insertion.region_max = [0.04, 0.055, 0.04]
output.interval = 0.025
output.particles_csv = true
output.checkpoint_interval = 0.0
TOML
expect 0 "periodic axes +x and z" "3D: check reports x and z periodic" "$FLUIDBED" check "$WORK/feed3d.toml"
expect 0 "depth, periodic in x and z" "3D: check says both x and z are periodic" "$FLUIDBED" check "$WORK/feed3d.toml"
run_ok "3D periodic feed: 1 thread" run "$WORK/feed3d.toml" --out "$WORK/one3d" --threads 1
run_ok "3D periodic feed: 2 threads" run "$WORK/feed3d.toml" --out "$WORK/two3d" --threads 2
same_results "3D, 1 vs 2 threads" "$WORK/one3d" "$WORK/two3d"
check "3D: the feed placed floor(rate t) particles (rate = 0.05 kg/s over the particle mass)" \
  awk -F, -v m="$m_p" 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == "particles_inserted") c = k; next }
    { n = $c } END { want = int(0.05 / m * 0.05); exit !(n == want) }' "$WORK/one3d/monitor.csv"
check "3D: every particle inside [0, 0.04) in x and z in the last frame" \
  bash -c "f=\$(ls '$WORK/one3d/particles/'*.csv | tail -1); awk -F, 'NR > 1 && (\$2 < 0 || \$2 >= 0.04 || \$4 < 0 || \$4 >= 0.04) { bad = 1 } END { exit bad }' \"\$f\""
finish
