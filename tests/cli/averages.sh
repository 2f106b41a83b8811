#!/usr/bin/env bash
# Time-averaged fields from the case's [averages] window (issue 15, item 4): averages.vti, averages.csv and
# averages.json of a CFD-DEM run in 2D and 3D and of a TFM run; the same files byte for byte after a restart in the
# window, with 1 or 2 threads, and with the particles stored in another order; the sample count the window and
# interval give; a bad window is exit 2 naming the key. Small beds, 0.02-0.04 s each (seconds on one core).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

same_averages() {  # same_averages LABEL DIR_A DIR_B
  local f
  for f in averages.csv averages.vti averages.json; do
    check "$1: $f identical" cmp "$2/$f" "$3/$f"
  done
}

# 2D CFD-DEM: window 0.005-0.02 s every 0.001 s, so 16 samples; the run ends at its end.
write_cfd_case "$WORK/c2.toml" avg2 'averages.t_start = 0.005' 'averages.t_end = 0.02' 'averages.interval = 0.001'
run_ok "2D: 0 to T" run "$WORK/c2.toml" --out "$WORK/full" --threads 1
check "2D: the three files" test -s "$WORK/full/averages.csv" -a -s "$WORK/full/averages.vti" -a -s "$WORK/full/averages.json"
check "2D: averages.csv header" bash -c "head -1 '$WORK/full/averages.csv' | grep -qx 'i,j,x_m,y_m,voidage,ug_x_m_s,ug_y_m_s,us_cell_x_m_s,us_cell_y_m_s,us_particle_x_m_s,us_particle_y_m_s,granular_temperature_m2_s2,solids_presence'"
check "2D: one row per cell, 16 samples, the window complete" /usr/bin/python3 - "$WORK/full" <<'PY'
import csv, json, math, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(d + "/averages.csv")))
assert len(rows) == 10 * 20, len(rows)
meta = json.load(open(d + "/averages.json"))
assert meta["samples"] == 16 and meta["window_complete"], meta
assert abs(meta["first_sample_s"] - 0.005) < 1e-12 and abs(meta["last_sample_s"] - 0.02) < 1e-12, meta
eps = [float(r["voidage"]) for r in rows]
assert all(0.2 < e <= 1.0 + 1e-12 for e in eps), (min(eps), max(eps))
# The bed (fill height 0.1 m) holds solids in its bottom row in every sample, the top row never; a temperature
# needs two particle centres in the cell at some sample (the jet's column may have fewer).
bottom = [r for r in rows if r["j"] == "0"]
assert all(float(r["solids_presence"]) == 1.0 for r in bottom)
assert sum(r["granular_temperature_m2_s2"] != "" for r in bottom) >= len(bottom) // 2
top = [r for r in rows if r["j"] == "19"]
assert all(r["us_particle_y_m_s"] == "" and float(r["solids_presence"]) == 0.0 for r in top)
assert all(float(r["granular_temperature_m2_s2"]) >= 0.0 for r in rows if r["granular_temperature_m2_s2"])
PY
check "2D: the VTI holds the six arrays" bash -c "for a in voidage gas_velocity solids_velocity_cell solids_velocity_particle granular_temperature solids_presence; do grep -q \"Name=\\\"\$a\\\"\" '$WORK/full/averages.vti' || exit 1; done"

# A restart inside the window continues the sums from the checkpoint.
run_ok "2D: 0 to T/2 (inside the window)" run "$WORK/c2.toml" --out "$WORK/split" --threads 1 --end-time 0.012
check "2D: a window cut short is written as it stands" \
  bash -c "grep -q '\"window_complete\": false' '$WORK/split/averages.json' && grep -q '\"samples\": 8' '$WORK/split/averages.json'"
run_ok "2D: restart T/2 to T" run "$WORK/c2.toml" --out "$WORK/split" --threads 1 \
  --restart "$WORK/split/checkpoints/final.h5"
same_averages "2D restart" "$WORK/full" "$WORK/split"

# A restart with another window: the saved sums belong to the old one, so the averages start again (with a warning).
run_ok "2D: restart with another window" run "$WORK/c2.toml" --out "$WORK/rewindow" --threads 1 --end-time 0.012
run_ok "2D: ... continued with t_start = 0.008" run "$WORK/c2.toml" --out "$WORK/rewindow" --threads 1 \
  --set averages.t_start=0.008 --restart "$WORK/rewindow/checkpoints/final.h5"
check "2D: the restart says the averages start again" grep -q 'start again at t = 0.012' "$WORK/rewindow/log.txt"
check "2D: ... and counts only its own samples (0.013-0.02 s: 8)" grep -q '"samples": 8,' "$WORK/rewindow/averages.json"

run_ok "2D: 2 threads" run "$WORK/c2.toml" --out "$WORK/threads2" --threads 2
same_averages "2D 1 vs 2 threads" "$WORK/full" "$WORK/threads2"

# The initial particles from a CSV in id order and with its rows shuffled: the same averages.
head -1 "$WORK/full/particles/000000.csv" >"$WORK/shuffled.csv"
tail -n +2 "$WORK/full/particles/000000.csv" | awk 'BEGIN { srand(5) } { printf "%.12f,%s\n", rand(), $0 }' |
  sort -t, -k1,1 | cut -d, -f2- >>"$WORK/shuffled.csv"
for v in in-order shuffled; do
  file="$WORK/shuffled.csv"
  [[ $v == in-order ]] && file="$WORK/full/particles/000000.csv"
  run_ok "2D: particles from the $v CSV" run "$WORK/c2.toml" --out "$WORK/file-$v" --threads 1 \
    --set particles.source=file --set particles.file="$file"
done
same_averages "2D CSV in id order vs shuffled" "$WORK/file-in-order" "$WORK/file-shuffled"

# interval = 0: a sample after every gas step in the window (0.005-0.02 s of 2e-4 s steps: 76).
run_ok "2D: every step" run "$WORK/c2.toml" --out "$WORK/every" --threads 1 --set averages.interval=0
check "2D: every gas step sampled" grep -q '"samples": 76,' "$WORK/every/averages.json"

# A window whose end is not on the sampling schedule: the last sample is the last due one, the window complete.
run_ok "2D: t_end off the schedule" run "$WORK/c2.toml" --out "$WORK/offgrid" --threads 1 --set averages.t_end=0.0195
check "2D: ... 15 samples, complete" bash -c "grep -q '\"samples\": 15,' '$WORK/offgrid/averages.json' &&
  grep -q '\"last_sample_s\": 0.019,' '$WORK/offgrid/averages.json' && grep -q '\"window_complete\": true' '$WORK/offgrid/averages.json'"

# A window that is not a window: bad input naming the key.
expect 2 "averages.t_end" "bad window: t_end before t_start" "$FLUIDBED" check "$WORK/c2.toml" \
  --set averages.t_end=0.002
expect 0 "OK" "no [averages]: the case checks" "$FLUIDBED" check "$WORK/c2.toml" --set averages.t_end=0

# 3D CFD-DEM: 600 particles placed at random (no settling) in 5 x 10 x 3 cells.
cat >"$WORK/c3.toml" <<'TOML'
case.name = "avg3"
case.dimension = 3
case.end_time = 0.02
case.seed = 7
domain.width = 0.05
domain.height = 0.1
domain.depth = 0.03
domain.gravity = [0.0, -9.81, 0.0]
particles.count = 600
particles.fill_height = 0.06
particles.layers = 2
settle.enabled = false
dem.time_step = 1e-4
grid.cell_width = 0.01
grid.cell_height = 0.01
grid.cell_depth = 0.01
coupling.dem_substeps = 2
inlet.velocity = 1.8
output.interval = 0.005
output.checkpoint_interval = 0.0
averages.t_start = 0.004
averages.t_end = 0.02
averages.interval = 0.002
TOML
run_ok "3D: 0 to T" run "$WORK/c3.toml" --out "$WORK/full3" --threads 1
check "3D: averages.csv has k and z, one row per cell, 9 samples" /usr/bin/python3 - "$WORK/full3" <<'PY'
import csv, json, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(d + "/averages.csv")))
assert len(rows) == 5 * 10 * 3, len(rows)
for c in ("k", "z_m", "ug_z_m_s", "us_cell_z_m_s", "us_particle_z_m_s"):
    assert c in rows[0], c
assert json.load(open(d + "/averages.json"))["samples"] == 9
assert any(r["granular_temperature_m2_s2"] for r in rows)
PY
run_ok "3D: 0 to T/2" run "$WORK/c3.toml" --out "$WORK/split3" --threads 1 --end-time 0.011
run_ok "3D: restart T/2 to T" run "$WORK/c3.toml" --out "$WORK/split3" --threads 1 \
  --restart "$WORK/split3/checkpoints/final.h5"
same_averages "3D restart" "$WORK/full3" "$WORK/split3"
run_ok "3D: 2 threads" run "$WORK/c3.toml" --out "$WORK/threads3" --threads 2
same_averages "3D 1 vs 2 threads" "$WORK/full3" "$WORK/threads3"

# TFM (the paper's bed, kinetic theory): its Theta averaged, restart and threads as above.
cp "$ROOT/cases/gera1998/tfm.toml" "$WORK/t.toml"
topts=(--set output.fields=false --set output.tracers=false --set averages.t_start=0.01 --set averages.t_end=0.04
       --set averages.interval=0.005)
run_ok "TFM: 0 to T" run "$WORK/t.toml" --out "$WORK/tfm" --end-time 0.04 --threads 1 "${topts[@]}"
check "TFM: 7 samples, a temperature wherever there are solids" /usr/bin/python3 - "$WORK/tfm" <<'PY'
import csv, json, sys
d = sys.argv[1]
assert json.load(open(d + "/averages.json"))["samples"] == 7
rows = list(csv.DictReader(open(d + "/averages.csv")))
assert all(r["granular_temperature_m2_s2"] != "" for r in rows if float(r["voidage"]) < 0.99)
PY
run_ok "TFM: 0 to T/2" run "$WORK/t.toml" --out "$WORK/tfm-split" --end-time 0.02 --threads 1 "${topts[@]}"
run_ok "TFM: restart T/2 to T" run "$WORK/t.toml" --out "$WORK/tfm-split" --end-time 0.04 --threads 1 "${topts[@]}" \
  --restart "$WORK/tfm-split/checkpoints/final.h5"
same_averages "TFM restart" "$WORK/tfm" "$WORK/tfm-split"
run_ok "TFM: 2 threads" run "$WORK/t.toml" --out "$WORK/tfm2" --end-time 0.04 --threads 2 "${topts[@]}"
same_averages "TFM 1 vs 2 threads" "$WORK/tfm" "$WORK/tfm2"

finish
