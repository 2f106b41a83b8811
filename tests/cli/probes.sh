#!/usr/bin/env bash
# Probes from the case file (issue 15, item 4): probes.csv with a point, a horizontal line and a pressure drop,
# after every model step (probes.interval = 0) or at its own rate, identical after a restart; bad probe keys are
# exit 2 naming the key. The paper's TFM bed, 0.04 s (well under a second on one core).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

cat "$ROOT/cases/gera1998/tfm.toml" "$ROOT/tests/cli/paper_probes.toml" > "$WORK/p.toml"
opts=(--threads 1 --set output.fields=false --set output.tracers=false)
run_ok "probes: 0 to T" run "$WORK/p.toml" --out "$WORK/full" --end-time 0.04 "${opts[@]}"
check "probes: probes.csv header" bash -c "head -1 '$WORK/full/probes.csv' | grep -qx 'time_s,tap_p_Pa,tap_eps,tap_ug_x_m_s,tap_ug_y_m_s,tap_us_x_m_s,tap_us_y_m_s,h20_p_Pa,h20_eps,h20_ug_x_m_s,h20_ug_y_m_s,h20_us_x_m_s,h20_us_y_m_s,bed_dp_Pa'"
# One row at t = 0 and one after every TFM step: as many rows as steps + 1 (cost.json counts the steps).
check "probes: a row after every step" /usr/bin/python3 - "$WORK/full" <<'PY'
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/probes.csv")))
steps = json.load(open(sys.argv[1] + "/cost.json"))["time_steps"]
assert len(rows) == steps + 1, (len(rows), steps)
t = [float(r["time_s"]) for r in rows]
assert t[0] == 0.0 and all(b > a for a, b in zip(t, t[1:])) and abs(t[-1] - 0.04) < 1e-12, t[-1]
# The bed weighs on the lower tap: a positive pressure drop (during the jet's start-up, 0-0.04 s, it exceeds the
# bed's weight per area while the gas lifts the bed, so only its sign is checked); voidage within (0, 1].
for r in rows:
    assert float(r["bed_dp_Pa"]) > 0.0, r["bed_dp_Pa"]
    assert 0.0 < float(r["tap_eps"]) <= 1.0
PY
run_ok "probes: 0 to T/2" run "$WORK/p.toml" --out "$WORK/split" --end-time 0.02 "${opts[@]}"
run_ok "probes: restart to T" run "$WORK/p.toml" --out "$WORK/split" --end-time 0.04 "${opts[@]}" \
  --restart "$WORK/split/checkpoints/final.h5"
check "probes: probes.csv identical after a restart" cmp "$WORK/full/probes.csv" "$WORK/split/probes.csv"

# Its own rate: rows at k * 0.005 s.
run_ok "probes: interval 0.005" run "$WORK/p.toml" --out "$WORK/rate" --end-time 0.04 "${opts[@]}" \
  --set probes.interval=0.005
check "probes: 9 rows at k * 0.005 s" bash -c \
  "test \"\$(cut -d, -f1 '$WORK/rate/probes.csv' | tail -n +2 | tr '\n' ' ')\" = '0 0.0050000000000000001 0.01 0.014999999999999999 0.02 0.025000000000000001 0.029999999999999999 0.035000000000000003 0.040000000000000001 '"

expect 2 "probe\[1\]\.name.*also probe\[0\]" "probes: a repeated name is refused" "$FLUIDBED" check "$WORK/p.toml" \
  --set 'probe[1].name="tap"'
expect 2 "probe\[0\]\.position.*outside the domain" "probes: a point outside the domain is refused" \
  "$FLUIDBED" check "$WORK/p.toml" --set 'probe[0].position=[0.7, 0.1]'
expect 2 "probe\[2\]\.height_top" "probes: a pressure drop needs its upper tap" "$FLUIDBED" check "$WORK/p.toml" \
  --set 'probe=[{kind="point", position=[0.1,0.1]}, {kind="plane", height=0.1}, {kind="pressure_drop", height=0.1}]'
expect 2 "probe\[0\]\.kind.*particle_top.*two-fluid model has none" "probes: particle_top is refused in a TFM case" \
  "$FLUIDBED" check "$WORK/p.toml" --set 'probe=[{kind="particle_top", name="top"}]'
finish
