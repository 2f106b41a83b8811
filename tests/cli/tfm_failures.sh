#!/usr/bin/env bash
# Two-fluid runs that go bad end with exit 3 and a diagnosis (time, cell, what, likely cause, remedy) and leave a
# failed-*.h5 checkpoint; `check` and `run` agree on what they refuse (issue 11, items 3 and 15).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"
PAPER=$ROOT/cases/gera1998/tfm.toml

# Nearly elastic particles: check warns ...
expect 0 "note: tfm.restitution = 0.99 is nearly elastic" "restitution 0.99: check notes the risk" \
  "$FLUIDBED" check "$PAPER" --set tfm.restitution=0.99
# ... and in the run the granular temperature runs away within 0.2 s (it used to run on to 1 s at solids
# speeds of thousands of m/s and report "done").
out=$WORK/e099
expect 3 "run went bad at t = .* in cell \([0-9]+, [0-9]+\) at x = .*Likely cause: .*Remedy: lower tfm.restitution" \
  "restitution 0.99: exit 3 and diagnosis" "$FLUIDBED" run "$PAPER" --set tfm.restitution=0.99 --out "$out" --quiet
check "restitution 0.99: log.txt has the diagnosis" grep -q "the simulation failed: tfm: the run went bad" "$out/log.txt"
check "restitution 0.99: last state in checkpoints/failed-*.h5" bash -c "ls '$out'/checkpoints/failed-t*.h5 >/dev/null"
check "restitution 0.99: no final checkpoint" test ! -e "$out/checkpoints/final.h5"

# e = 1: refused by check and by run alike, naming the key, before any step.
expect 2 "tfm.restitution: e = 1 has no granular temperature" "restitution 1: check refuses it" \
  "$FLUIDBED" check "$PAPER" --set tfm.restitution=1.0
expect 2 "tfm.restitution: e = 1 has no granular temperature" "restitution 1: run refuses it" \
  "$FLUIDBED" run "$PAPER" --set tfm.restitution=1.0 --out "$WORK/e1" --quiet
# ... but the Eq. 20 rheologies do not use e.
expect 0 "OK" "restitution 1 with constant viscosity passes" \
  "$FLUIDBED" check "$PAPER" --set tfm.restitution=1.0 --set tfm.rheology=constant_viscosity

# monitor.csv: the contract columns, the per-depth columns shared with the DEM, and the granular temperature of
# the bed (never the diverging dilute-limit value of empty cells).
out=$WORK/paper
run_ok "paper case to 0.05 s" run "$PAPER" --end-time 0.05 --out "$out"
check "monitor.csv has the documented TFM columns" bash -c "head -1 '$out/monitor.csv' | grep -qx \
'time_s,kinetic_energy_J,pressure_drop_Pa,max_overlap_m,gas_mass_residual,solids_mass_kg,solids_mass_per_depth_kg_m,kinetic_energy_per_depth_J_m,time_step_s,min_voidage,max_solids_speed_m_s,granular_temperature_bed_max_m2_s2,granular_temperature_solids_mean_m2_s2,linear_solver_fallbacks,inlet_velocity_m_s,wall_s'"
# Solids mass: 0.6 m x 0.54 m at eps = 0.431, 2700 kg/m^3: 497.76 kg per metre of depth, 1.991 kg in the 4 mm slab.
check "solids mass per depth and per 4 mm slab" /usr/bin/python3 - "$out/monitor.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
m = 0.6 * 0.54 * (1 - 0.431) * 2700
for r in rows:
    assert abs(float(r["solids_mass_per_depth_kg_m"]) / m - 1) < 1e-12, r
    assert abs(float(r["solids_mass_kg"]) / (m * 0.004) - 1) < 1e-12, r
    assert abs(float(r["kinetic_energy_J"]) - 0.004 * float(r["kinetic_energy_per_depth_J_m"])) <= 1e-12 * float(r["kinetic_energy_J"]) + 1e-300, r
    assert float(r["granular_temperature_bed_max_m2_s2"]) < 100, r
    assert r["linear_solver_fallbacks"] == "0", r
PY
finish
