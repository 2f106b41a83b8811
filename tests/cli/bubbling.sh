#!/usr/bin/env bash
# A freely bubbling bed survives (issue 11, item 10): the top boundary choices for particles (open, wall, outflow
# that removes and counts them in monitor.csv), the failure message naming them, and a short run of
# cases/bubbling/dem.toml (no jet, inflow ramped from U_mf to 2 U_mf).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

# Column NAME of monitor.csv, one value per row.
column() {  # column FILE NAME
  awk -F, -v name="$2" 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == name) c = k; next } { print $c }' "$1"
}

# 200 particles in a 0.1 x 0.2 m box, no gas, gravity pointing up: every particle reaches the top, the last one
# (from y = 2 mm) after sqrt(2 * 0.198 / 9.81) = 0.20 s.
cat >"$WORK/up.toml" <<'TOML'
case.name = "up"
case.end_time = 0.3
case.seed = 7
domain.width = 0.1
domain.height = 0.2
dem.gravity = [0.0, 9.81]
particles.count = 200
particles.fill_height = 0.1
particles.layers = 2
settle.enabled = false
gas.enabled = false
grid.cell_width = 0.01
output.interval = 0.01
output.monitor_interval = 0.002
output.checkpoint_interval = 0.0
output.particles_csv = true
TOML

expect 3 'left through the open top.*domain.particle_top = "outflow".*domain.particle_top = "wall"' \
  "open top: a particle crossing it fails, naming the choices" "$FLUIDBED" run "$WORK/up.toml" --out "$WORK/open" --quiet

run_ok "outflow top: the run goes on" run "$WORK/up.toml" --out "$WORK/outflow" --set domain.particle_top=outflow
m_p=$(awk 'BEGIN { printf "%.17g", 2700 * atan2(0, -1) / 6 * 0.004^3 }')
paste -d, <(column "$WORK/outflow/monitor.csv" solids_mass_kg) <(column "$WORK/outflow/monitor.csv" particles_lost) \
  <(column "$WORK/outflow/monitor.csv" mass_lost_kg) >"$WORK/mass.csv"
# Every row: mass lost = particles removed x particle mass, and with the mass still in the box makes up the start.
check "outflow: mass lost = particles removed x mass, remaining + lost = initial, every row" \
  awk -F, -v m="$m_p" 'NR == 1 { m0 = $1 }
    { if (($3 - $2 * m) ^ 2 > (1e-12 * m0) ^ 2 || ($1 + $3 - m0) ^ 2 > (1e-12 * m0) ^ 2) { print "row " NR ": " $0; bad = 1 } }
    END { exit bad }' "$WORK/mass.csv"
check "outflow: all 200 particles left by the end, none at the start" \
  bash -c "test \"\$(head -1 '$WORK/mass.csv' | cut -d, -f2)\" = 0 && test \"\$(tail -1 '$WORK/mass.csv' | cut -d, -f2)\" = 200"
check "outflow: some rows with particles both in the box and lost" \
  awk -F, '$2 > 0 && $2 < 200 { n++ } END { exit !(n > 3) }' "$WORK/mass.csv"

check "outflow: log.txt says when particles start to leave and when half the bed is gone" \
  bash -c "grep -q '1 particle (.*) left through the outflow top' '$WORK/outflow/log.txt' && grep -q '% of the bed.s mass) left' '$WORK/outflow/log.txt'"

# The count survives a restart: 0 to 0.16 s (some particles out), then on to 0.3 s, as the uninterrupted run.
run_ok "outflow: run to 0.16 s" run "$WORK/up.toml" --out "$WORK/split" --set domain.particle_top=outflow --end-time 0.16
run_ok "outflow: restart to 0.3 s" run "$WORK/up.toml" --out "$WORK/split" --set domain.particle_top=outflow \
  --restart "$WORK/split/checkpoints/final.h5"
same_results "outflow restarted" "$WORK/outflow" "$WORK/split"

# A top wall keeps them in (the lid is hit at 1.4 m/s: the soft spring of the paper overlaps deeper than 10%).
run_ok "wall top: the particles stay" run "$WORK/up.toml" --out "$WORK/wall" --set domain.particle_top=wall \
  --set dem.max_overlap_fraction=0.5
check "wall top: nothing lost" test "$(column "$WORK/wall/monitor.csv" particles_lost | tail -1)" = 0

# The bubbling case itself: checked, and a few gas steps of it (the bed unsettled, so the test needs no settling).
bubbling=$ROOT/cases/bubbling/dem.toml
expect 0 "OK" "cases/bubbling/dem.toml passes check" "$FLUIDBED" check "$bubbling"
# 0.0101 s is 50.5 gas steps of 2e-4 s: the last step is shortened to land on the end time (item 8).
run_ok "cases/bubbling/dem.toml: 0.0101 s" run "$bubbling" --out "$WORK/bubbling" --end-time 0.0101 --threads 2 \
  --set settle.enabled=false --set output.interval=0.005
check "bubbling: monitor.csv counts the particles lost" \
  bash -c "head -1 '$WORK/bubbling/monitor.csv' | grep -q 'particles_lost,mass_lost_kg'"
check "bubbling: the run ended on 0.0101 s, not a gas step short" grep -q 'done: t = 0.0101 s' "$WORK/bubbling/log.txt"

# `check` shows the choices that make this bed (the ramp, the distributor noise, the particle top).
expect 0 "ramped from 1.8 m/s over 0 <= t < 0.5 s" "check prints the inlet ramp" "$FLUIDBED" check "$ROOT/cases/bubbling/dem.toml"
expect 0 "distributor non-uniformity +\+-10%" "check prints the distributor noise" "$FLUIDBED" check "$ROOT/cases/bubbling/dem.toml"
expect 0 "top of the domain \(particles\) +outflow" "check prints the particle top" "$FLUIDBED" check "$ROOT/cases/bubbling/dem.toml"
# A bed without a jet has no detachment to report, only eruptions (the log said "detachment 1.180 s" before).
expect 0 "" "a short run of a bed without a jet" \
  "$FLUIDBED" run "$ROOT/cases/bubbling/tfm.toml" --quiet --out "$WORK/nojet" --end-time 0.02
expect 0 "bubble: first eruption none \(no jet" "log.txt has it" cat "$WORK/nojet/log.txt"
finish
