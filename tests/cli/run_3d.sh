#!/usr/bin/env bash
# A tiny 3D CFD-DEM case end to end (issue 12): `fluidbed check` prints the 3D domain, a run writes 3D .vti and
# .vtu frames and bubble.csv with the 3D columns, a restart from a mid-run checkpoint continues bit for bit, and 1
# and 2 threads give identical results.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

# 600 particles settled in a 0.05 x 0.1 x 0.03 m box of 5 x 10 x 3 gas cells (1 cm cubes; a bed 2 cm deep), the
# background inflow and a 2 cm disc jet at the bottom's centre that blows a bubble, so that every part of the 3D
# coupled step and the 3D bubble tracker run. The settled bed is cached in the work folder: the first run settles
# (about 5 s), the others start from the same bed.
cat >"$WORK/c3d.toml" <<'TOML'
case.name = "c3d"
case.dimension = 3
case.end_time = 0.04
case.seed = 7
domain.width = 0.05
domain.height = 0.1
domain.depth = 0.03
domain.gravity = [0.0, -9.81, 0.0]
particles.count = 600
particles.fill_height = 0.06
particles.layers = 2
settle.enabled = true
settle.max_time = 0.5
settle.cache = "settled.csv"
dem.time_step = 1e-4
grid.cell_width = 0.01
grid.cell_height = 0.01
grid.cell_depth = 0.01
coupling.dem_substeps = 2
inlet.velocity = 1.8
bubble.jet_x = 0.025
bubble.jet_width = 0.02
bubble.min_volume = 1e-6
output.interval = 0.005
output.monitor_interval = 0.001
output.checkpoint_interval = 0.0
output.particles_csv = true

[[inlet.jet]]
shape = "disc"
centre = 0.025
centre_z = 0.015
diameter = 0.02
velocity = 30.0
start = 0.0
end = 0.4
TOML

# bubble.csv without a wall_s column (none today; the same rule as monitor.csv should one be added).
same_bubbles() {  # same_bubbles LABEL DIR_A DIR_B
  check "$1: bubble.csv rows identical" cmp <(monitor_without_wall "$2/bubble.csv") <(monitor_without_wall "$3/bubble.csv")
  local f
  for f in bubbles.csv bubble_events.csv bubble_frames.csv; do
    check "$1: $f identical" cmp "$2/$f" "$3/$f"
  done
}

# (d) check: the 3D domain, grid and jet.
expect 0 "0\.05 x 0\.1 x 0\.03 m" "check: prints the 3D domain" "$FLUIDBED" check "$WORK/c3d.toml"
expect 0 "5 x 10 x 3" "check: prints the 3D gas grid" "$FLUIDBED" check "$WORK/c3d.toml"

# (a) a straight run to T with a checkpoint at T/2.
run_ok "3d: 0 to T" run "$WORK/c3d.toml" --out "$WORK/full" --threads 1 --set output.checkpoint_interval=0.02
check "3d: fields/*.vti frames written" test -n "$(ls "$WORK"/full/fields/*.vti 2>/dev/null)"
check "3d: particles/*.vtu frames written" test -n "$(ls "$WORK"/full/particles/*.vtu 2>/dev/null)"
check "3d: the .vti is a 5 x 10 x 3 cell image" grep -q 'WholeExtent="0 5 0 10 0 3"' "$WORK/full/fields/000000.vti"
check "3d: the .vtu points have a z spread (not all 0)" python3 - "$WORK/full/particles/000001.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
zs = [float(r["z"]) for r in rows]
assert len(rows) == 600, len(rows)
assert 0.0 < min(zs) and max(zs) < 0.03 and max(zs) - min(zs) > 0.01, (min(zs), max(zs))
for k in ("vz", "omega_x", "omega_y", "omega_z"):
    assert k in rows[0], f"no {k} column: {list(rows[0])}"
PY
check "3d: bubble.csv has the 3D columns" \
  bash -c "head -1 '$WORK/full/bubble.csv' | grep -q bubble_volume_m3 && head -1 '$WORK/full/bubble.csv' | grep -q nose_z_m && head -1 '$WORK/full/bubble.csv' | grep -q theory_rise_velocity_m_s"
check "3d: bubble.csv has a row per output time" test "$(wc -l <"$WORK/full/bubble.csv")" -ge 9
check "3d: monitor.csv has rows" test "$(wc -l <"$WORK/full/monitor.csv")" -ge 40
mid=$(ls "$WORK"/full/checkpoints/t0.02*.h5 2>/dev/null | head -1)
check "3d: checkpoint at T/2 written" test -n "$mid"
check "3d: bubble.csv tracks a bubble (volume and equivalent diameter given)" python3 - "$WORK/full/bubble.csv" <<'PY'
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["bubble_volume_m3"]]
assert len(rows) >= 3, len(rows)
for r in rows:
    v, d = float(r["bubble_volume_m3"]), float(r["equivalent_diameter_m"])
    assert abs(d - (6 * v / 3.141592653589793) ** (1 / 3)) < 1e-12 * d, (v, d)
    assert 0.0 <= float(r["nose_z_m"]) <= 0.03
PY

# Issue 27 item 7: 3D runs write the layer tracer balls (ball_id,x,y,z,layer), one per cell under the bed surface.
check "3d: tracers/*.csv frames with the 3D header" python3 - "$WORK/full/tracers" <<'PY'
import csv, os, sys
files = sorted(os.listdir(sys.argv[1]))
assert len(files) == 9, files
rows = list(csv.reader(open(os.path.join(sys.argv[1], files[0]))))
assert rows[0] == ["ball_id", "x", "y", "z", "layer"], rows[0]
balls = [[float(v) for v in r] for r in rows[1:]]
assert len(balls) % 15 == 0 and len(balls) >= 15, len(balls)  # whole layers of 5 x 3 cells
assert all(0 < b[3] < 0.03 for b in balls) and {int(b[4]) for b in balls} == {0, 1}
PY
# Issue 27 item 17: the t = 0 row's inflow is U(0), the jet open from t = 0 (before: the initial solve's, 1.8 m/s):
# 1.8 m/s outside the 2 cm disc, 30 m/s over it, pi (0.01)^2 of the 0.05 x 0.03 m bottom.
check "3d: inlet_velocity_m_s at t = 0 is the schedules' U(0)" python3 - "$WORK/full/monitor.csv" <<'PY'
import csv, math, sys
row = next(csv.DictReader(open(sys.argv[1])))
u = 1.8 + (30.0 - 1.8) * math.pi * 0.01 ** 2 / (0.05 * 0.03)
assert float(row["time_s"]) == 0.0 and abs(float(row["inlet_velocity_m_s"]) - u) < 1e-9 * u, (row["inlet_velocity_m_s"], u)
PY

# (b) a restart from the mid-run checkpoint into a fresh folder ends in the same state as the straight run.
run_ok "3d: restart T/2 to T" run "$WORK/c3d.toml" --out "$WORK/restart" --threads 1 --restart "$mid"
check "3d: the restart's log names it" grep -q '(restart from' "$WORK/restart/log.txt"
for f in particles/000008.csv particles/000008.vtu fields/000008.vti tracers/000008.csv; do
  check "3d restart: $f identical" cmp "$WORK/full/$f" "$WORK/restart/$f"
done
# The rows the restarted run wrote (t > T/2) equal the straight run's.
after_mid() { monitor_without_wall "$1" | awk -F, 'NR == 1 || $1 + 0 > 0.02'; }
check "3d restart: monitor.csv rows after T/2 identical (without wall_s)" \
  cmp <(after_mid "$WORK/full/monitor.csv") <(after_mid "$WORK/restart/monitor.csv")
check "3d restart: bubble.csv rows after T/2 identical" \
  cmp <(after_mid "$WORK/full/bubble.csv") <(after_mid "$WORK/restart/bubble.csv")
# Every bubble: the population (ids, velocities) continues from the checkpoint, so the rows after T/2 are the same.
for f in bubbles.csv bubble_events.csv bubble_frames.csv; do
  check "3d restart: $f rows after T/2 identical" cmp <(after_mid "$WORK/full/$f") <(after_mid "$WORK/restart/$f")
done
check "3d: bubbles.csv has a bubble on both sides of T/2 with centroid velocities after it" \
  bash -c "awk -F, 'NR > 1 && \$1 + 0 <= 0.02' '$WORK/full/bubbles.csv' | grep -q . &&
           awk -F, 'NR > 1 && \$1 + 0 > 0.02 && \$13 != \"\"' '$WORK/full/bubbles.csv' | grep -q ."
check "3d restart: it wrote rows after T/2" test "$(after_mid "$WORK/restart/monitor.csv" | wc -l)" -ge 10
# And the split run (0 to T/2, then --restart final.h5 in the same folder) equals the straight run in every file.
run_ok "3d: 0 to T/2" run "$WORK/c3d.toml" --out "$WORK/split" --threads 1 --end-time 0.02
run_ok "3d: restart final.h5 to T" run "$WORK/c3d.toml" --out "$WORK/split" --threads 1 \
  --restart "$WORK/split/checkpoints/final.h5"
same_results "3d split" "$WORK/full" "$WORK/split"
same_bubbles "3d split" "$WORK/full" "$WORK/split"

# (c) two threads: the same bits.
run_ok "3d: --threads 2" run "$WORK/c3d.toml" --out "$WORK/t2" --threads 2 --set output.checkpoint_interval=0.02
check "3d: the log names 2 threads" grep -q '; 2 threads;' "$WORK/t2/log.txt"
same_results "3d 1 vs 2 threads" "$WORK/full" "$WORK/t2"
same_bubbles "3d 1 vs 2 threads" "$WORK/full" "$WORK/t2"

finish
