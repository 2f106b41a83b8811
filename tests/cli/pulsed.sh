#!/usr/bin/env bash
# Time-dependent inlets (issue 14): monitor.csv's inlet_velocity_m_s follows the schedule of cases/pulsed/tfm.toml
# (a sine) and of a small CFD-DEM bed with a table read from a CSV file and a perforated plate; both models take
# the inflow at the step's midpoint, the row's time less half the step (the TFM's steps adapt: time_step_s); bad
# schedules and plates are refused with exit 2 naming the key.
source "$(dirname "$0")/lib.sh"

# Largest |inlet_velocity_m_s - U| over monitor.csv (after t = 0), U an awk expression of t (the row's time) and h
# (its time_step_s, 0 where the file has no such column).
deviation() {  # deviation FILE EXPR
  awk -F, -v OFMT=%.3g "NR == 1 { for (k = 1; k <= NF; ++k) { if (\$k == \"inlet_velocity_m_s\") c = k; if (\$k == \"time_s\") tc = k; if (\$k == \"time_step_s\") hc = k }; next }
       \$tc + 0 == 0 { next }  # no gas step yet
       { t = \$tc; h = hc ? \$hc : 0; d = \$c - ($2); if (d < 0) d = -d; if (d > m) m = d; n++ }
       END { if (n < 5) print \"too few rows\"; else if (m < 1e-9) print \"within\", m; else print \"off by\", m }" "$1"
}

expect 0 "" "pulsed TFM runs" "$FLUIDBED" run "$ROOT/cases/pulsed/tfm.toml" --out "$WORK/tfm" --end-time 0.2 --quiet \
  --set output.fields=false
expect 0 "^within" "TFM inlet_velocity_m_s = 2.7 + 0.9 sin(10 pi (t - dt / 2))" \
  deviation "$WORK/tfm/monitor.csv" "2.7 + 0.9 * sin(2 * 3.141592653589793 * 5 * (t - h / 2))"

# 300 particles in a 0.1 x 0.3 m box on a plate of 5 slots 4 mm wide at 20 mm pitch (20% open) carrying 2 m/s,
# no background, the slots' velocity from a table: 2 m/s until 0.01 s, 6 m/s at 0.03 s, then held. The gas steps
# at dt = 2e-4 s and takes the inflow at the step's midpoint: the monitor shows U at t - 1e-4 s over the bottom,
# 0.2 times the slots' velocity.
cat >"$WORK/table.csv" <<'CSV'
time_s,velocity_m_s
0.0,2.0
0.01,2.0
0.03,6.0
CSV
cat >"$WORK/plate.toml" <<'TOML'
case.name = "plate"
case.end_time = 0.05
case.seed = 7
domain.width = 0.1
domain.height = 0.3
particles.count = 300
particles.fill_height = 0.1
particles.layers = 2
settle.enabled = false
dem.time_step = 2e-4
coupling.dem_substeps = 1
grid.cell_width = 0.01
output.interval = 0.01
output.monitor_interval = 0.002
output.checkpoint_interval = 0.0
output.particles = false
output.fields = false
inlet.velocity = 0.0
[[inlet.plate]]
holes = 5
hole_width = 0.004
pitch = 0.02
centre = 0.05
schedule = "table"
table_file = "table.csv"
TOML
expect 0 "" "CFD-DEM bed on a table-scheduled plate runs" "$FLUIDBED" run "$WORK/plate.toml" --out "$WORK/plate" --quiet
expect 0 "^within" "DEM inlet_velocity_m_s = 0.2 x the table at mid-step" deviation "$WORK/plate/monitor.csv" \
  "0.2 * ((t - 1e-4) <= 0.01 ? 2.0 : (t - 1e-4) >= 0.03 ? 6.0 : 2.0 + 4.0 * ((t - 1e-4) - 0.01) / 0.02)"
expect 0 "5 regions|jet" "check lists the plate's slots" "$FLUIDBED" check "$WORK/plate.toml"

# Refused: each names the key.
expect 2 "table_times" "table times must increase" "$FLUIDBED" check "$WORK/plate.toml" \
  --set 'inlet.plate[0].table_file=""' --set 'inlet.plate[0].table_times=[0.0, 0.0]' \
  --set 'inlet.plate[0].table_velocities=[1.0, 2.0]'
expect 2 "inlet.frequency" "a sine needs its frequency" "$FLUIDBED" check "$WORK/plate.toml" --set 'inlet.schedule="sine"'
expect 2 "inlet.ramp_time" "a start-up ramp only for a constant background" "$FLUIDBED" check "$WORK/plate.toml" \
  --set 'inlet.schedule="sine"' --set inlet.frequency=2 --set inlet.ramp_time=0.1
expect 2 "hole_diameter" "a 2D plate has slots" "$FLUIDBED" check "$WORK/plate.toml" --set 'inlet.plate[0].hole_diameter=0.004'
expect 2 "pitch" "overlapping holes" "$FLUIDBED" check "$WORK/plate.toml" --set 'inlet.plate[0].pitch=0.003'
expect 2 "pitch" "holes outside the bottom" "$FLUIDBED" check "$WORK/plate.toml" --set 'inlet.plate[0].pitch=0.03'
expect 2 "duty" "duty only for a square wave" "$FLUIDBED" check "$WORK/plate.toml" --set 'inlet.plate[0].duty=0.3'
finish
