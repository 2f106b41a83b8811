#!/usr/bin/env bash
# A run from 0 to T and a run to T/2 continued by --restart to T end in bit-identical states, and the restart
# appends to the output series (issue 6). CFD-DEM, DEM alone, and the TFM once it is wired.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

# restart_case LABEL CASE T: full run, half run + restart into one folder, compare.
restart_case() {
  local label=$1 case=$2 t_end=$3
  shift 3
  local half
  half=$(awk -v t="$t_end" 'BEGIN { printf "%.17g", t / 2 }')
  run_ok "$label: 0 to T" run "$case" --out "$WORK/$label-full" --end-time "$t_end" "$@" \
    --set output.checkpoint_interval="$half"
  run_ok "$label: 0 to T/2" run "$case" --out "$WORK/$label-split" --end-time "$half" "$@"
  check "$label: T/2 run wrote checkpoints/final.h5" test -s "$WORK/$label-split/checkpoints/final.h5"
  local frames_half
  frames_half=$(pvd_entries "$WORK/$label-split/fields.pvd" 2>/dev/null | wc -l)
  run_ok "$label: restart T/2 to T" run "$case" --out "$WORK/$label-split" --end-time "$t_end" "$@" \
    --restart "$WORK/$label-split/checkpoints/final.h5"
  check "$label: log.txt keeps the first run and names the restart" \
    bash -c "grep -c 'fluidbed run' '$WORK/$label-split/log.txt' | grep -qx 2 && grep -q '(restart from' '$WORK/$label-split/log.txt'"
  same_results "$label" "$WORK/$label-full" "$WORK/$label-split"
  if [[ -e $WORK/$label-full/fields.pvd ]]; then
    check "$label: the restart appended to fields.pvd" \
      test "$(pvd_entries "$WORK/$label-split/fields.pvd" | wc -l)" -gt "$frames_half"
  fi
}

# A denser bed than the shared case (0.06 m instead of 0.1 m filled) so that it has a bed surface and with it the
# cell tracers of Fig. 4b/c.
write_cfd_case "$WORK/cfd.toml" cfd
sed -i 's/^particles.fill_height = 0.1$/particles.fill_height = 0.06/' "$WORK/cfd.toml"
restart_case cfd "$WORK/cfd.toml" 0.02
# A half time that the DEM clock (origin + n dt) does not hit exactly: the run to T/2 lands its clock on T/2, and
# the cell tracers must still advance by the step the model took, as in the uninterrupted run.
restart_case cfd-land "$WORK/cfd.toml" 0.06 --set output.interval=0.01

# A restart from an earlier checkpoint into a folder that already holds later outputs replaces them: the series
# are cut at the checkpoint time and rewritten, with no time twice and the same final state. The full run above
# wrote a checkpoint at T/2 (restart_case sets the checkpoint interval of the full run to T/2).
mid=$(ls "$WORK"/cfd-full/checkpoints/t0.0*.h5 2>/dev/null | head -1)
check "cfd: checkpoint at T/2 written by the full run" test -n "$mid"
cp "$mid" "$WORK/mid.h5"
run_ok "cfd: restart from T/2 over the finished run" run "$WORK/cfd.toml" --out "$WORK/cfd-full" \
  --set output.checkpoint_interval=0.01 --restart "$WORK/mid.h5"
same_results "cfd over a finished run" "$WORK/cfd-split" "$WORK/cfd-full"

# The cell tracers (Fig. 4b/c balls) come back from the checkpoint: same_results above compared tracers/*.csv,
# which hold each ball's id, position and layer.
check "cfd: the restarted run wrote tracer frames" test -s "$WORK/cfd-split/tracers/000004.csv"

# A restart continues the same simulation: a case that changes a physical key against its checkpoint is refused
# with exit 2 naming the key, and accepted when the change is asked for (--allow-changed KEY or its section).
expect 2 "mid.h5: the case changes contact.stiffness against the checkpoint .*--allow-changed contact.stiffness" \
  "cfd: restart with another stiffness is refused" "$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/cfd-stiff" --quiet \
  --set contact.stiffness=900 --restart "$WORK/mid.h5"
check "cfd: the refused restart wrote nothing" test ! -e "$WORK/cfd-stiff/case.toml"
expect 2 "mid.h5: the case changes .*species\[0\]\.diameter" \
  "cfd: restart with another particle diameter is refused" "$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/cfd-d" \
  --quiet --set 'species=[{diameter = 0.0035}]' --restart "$WORK/mid.h5"
expect 2 "changes inlet.jet\[0\].velocity" "cfd: restart with another jet is refused" "$FLUIDBED" run \
  "$WORK/cfd.toml" --out "$WORK/cfd-jet" --quiet --set 'inlet.jet[0].velocity=25' --restart "$WORK/mid.h5"
expect 2 "changes dem.time_step" "cfd: restart with another time step is refused" "$FLUIDBED" run \
  "$WORK/cfd.toml" --out "$WORK/cfd-dt" --quiet --set dem.time_step=5e-5 --restart "$WORK/mid.h5"
# Accepted, another time step continues the clock from the checkpoint's time: it used to count the saved steps
# with the new step, so the clock jumped back and the run stopped with "the model did not advance".
expect 0 "" "cfd: --allow-changed dem.time_step continues" "$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/cfd-dt" \
  --quiet --set dem.time_step=5e-5 --allow-changed dem.time_step --restart "$WORK/mid.h5"
check "cfd: after another time step the monitor's clock rises from T/2 to T" python3 - "$WORK/cfd-dt/monitor.csv" \
  "$WORK/mid.h5" 0.02 <<'PY'
import sys
rows = [float(l.split(",")[0]) for l in open(sys.argv[1]).read().splitlines()[1:]]
assert all(b > a for a, b in zip(rows, rows[1:])), "the clock went back"
assert abs(rows[-1] - float(sys.argv[3])) < 1e-12, f"ended at {rows[-1]}"
PY
expect 0 "" "cfd: --allow-changed contact.stiffness continues anyway" "$FLUIDBED" run "$WORK/cfd.toml" \
  --out "$WORK/cfd-stiff" --quiet --set contact.stiffness=900 --allow-changed contact.stiffness --restart "$WORK/mid.h5"
expect 0 "" "cfd: --allow-changed inlet (a whole section)" "$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/cfd-jet" \
  --quiet --set 'inlet.jet[0].velocity=25' --allow-changed inlet --restart "$WORK/mid.h5"
# Output, analysis and run-control keys may change freely (the split run above restarted with another
# checkpoint interval).

# A checkpoint that does not fit the case is bad input (exit 2), never read half-way: another gas grid (refused as
# a change, and when allowed, by the array sizes), or gas fields missing from a DEM-alone checkpoint.
expect 2 "mid.h5: the case changes grid.cell_(width|height)" "cfd: restart on another grid" \
  "$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/cfd-grid" --quiet --set grid.cell_width=0.005 --restart "$WORK/mid.h5"
expect 2 "gas/. has [0-9]+ values, the case's grid needs [0-9]+" "cfd: restart on another grid, allowed" \
  "$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/cfd-grid" --quiet --set grid.cell_width=0.005 --allow-changed grid \
  --restart "$WORK/mid.h5"

# The run goes on until the model lands on the end time, also one the gas step (2e-4 s) does not divide: the last
# step is shortened (the DEM's part is ModelRun::advance(t_end)); it used to stop at 0.01 s.
run_ok "cfd: --end-time 0.0101" run "$WORK/cfd.toml" --out "$WORK/cfd-0101" --end-time 0.0101
check "cfd: the run ended at t = 0.0101 s" grep -q "done: t = 0.0101 s" "$WORK/cfd-0101/log.txt"

# A new run into a folder that holds results does not delete them: exit 2 naming the folder, unless --overwrite.
cp "$WORK/cfd-full/monitor.csv" "$WORK/monitor-before.csv"
expect 2 "cfd-full holds the results of an earlier run \(monitor.csv.*checkpoints/.*--overwrite" \
  "cfd: a new run into a folder with results is refused" "$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/cfd-full" --quiet
check "cfd: the refused run left the results as they were" cmp "$WORK/monitor-before.csv" "$WORK/cfd-full/monitor.csv"
expect 0 "" "cfd: --overwrite replaces them" "$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/cfd-full" --quiet --overwrite
check "cfd: the log says they were replaced" grep -q -- "--overwrite: replaced the earlier results" "$WORK/cfd-full/log.txt"
check "cfd: no checkpoint of the replaced run is left" test -z "$(ls "$WORK"/cfd-full/checkpoints/t*.h5 2>/dev/null)"

# A checkpoint at or past the end time has nothing to run: refused (exit 2), final.h5 left as it was.
cp "$WORK/cfd-split/checkpoints/final.h5" "$WORK/final-before.h5"
expect 2 "final.h5: the checkpoint is at t = 0.02 s, at or past the end time 0.02 s: nothing to run" \
  "cfd: restart at the end time is refused" "$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/cfd-split" --quiet \
  --restart "$WORK/cfd-split/checkpoints/final.h5"
check "cfd: final.h5 not overwritten" cmp "$WORK/final-before.h5" "$WORK/cfd-split/checkpoints/final.h5"

# Particles of their own sizes (issue 14): a log-normal species and a fixed lighter one; the sizes travel in the
# checkpoint (dem/diameter) and the particle CSVs (diameter column), and the restart is bit-identical.
write_cfd_case "$WORK/poly.toml" poly \
  'species = [{size_distribution = "log-normal", median = 0.0035, sigma = 0.1}, {diameter = 0.004, density = 1500.0}]'
restart_case poly "$WORK/poly.toml" 0.02
check "poly: particles CSVs carry the diameter column" grep -q ',species,diameter$' "$WORK/poly-split/particles/000004.csv"

# DEM alone (no gas: no fields, particles only); 400 steps of the default 2e-4 s.
cat >"$WORK/dem.toml" <<'TOML'
case.name = "dem"
case.seed = 11
domain.width = 0.1
domain.height = 0.2
particles.count = 150
particles.layers = 3
settle.enabled = false
gas.enabled = false
grid.cell_width = 0.01
output.interval = 0.02
output.monitor_interval = 0.002
output.checkpoint_interval = 0.0
output.particles_csv = true
TOML
restart_case dem "$WORK/dem.toml" 0.08
# The composed contact laws carry more history: Hertz-Mindlin with the elastic-plastic rolling spring (its springs
# id-keyed in the neighbour list and per wall in the particle store, both in the checkpoint). A soft material
# (E = 10 MPa) keeps t_c / 20 near 2e-5 s.
restart_case dem-rolling "$WORK/dem.toml" 0.04 --set contact.normal=hertz --set 'species=[{youngs_modulus = 1e7}]' \
  --set contact.wall_youngs_modulus=1e7 --set contact.rolling=epsd --set contact.rolling_friction=0.1
# Output times are the scheduled instants k * interval exactly, not a sum of 2e-4 s steps (0.019000000000000003):
# every monitor row and every .pvd entry, in the straight run and in the restarted one.
for d in dem-full dem-split; do
  check "dem: $d: monitor.csv times and particles.pvd times are exact multiples of their intervals" python3 - \
    "$WORK/$d" 0.002 0.02 <<'PY'
import re, sys
out, monitor, frames = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
def exact(t, interval):
    return t == round(t / interval) * interval
rows = [float(l.split(",")[0]) for l in open(out + "/monitor.csv").read().splitlines()[1:]]
bad = [t for t in rows if not exact(t, monitor)]
pvd = [float(t) for t in re.findall(r'timestep="([^"]+)"', open(out + "/particles.pvd").read())]
bad += [t for t in pvd if not exact(t, frames)]
assert rows and pvd and not bad, f"{len(rows)} rows, {len(pvd)} frames; not k * interval: {bad[:5]}"
PY
done
expect 2 "dem-full/checkpoints/final.h5.*gas.enabled" "dem: a DEM-alone checkpoint cannot start a run with gas" \
  "$FLUIDBED" run "$WORK/dem.toml" --out "$WORK/dem-gas" --quiet --set gas.enabled=true \
  --restart "$WORK/dem-full/checkpoints/final.h5"

# The two-fluid model: runs once the lead has wired it (a tfm case that `fluidbed check` accepts).
tfm_case=$ROOT/cases/gera1998/tfm.toml
if [[ -f $tfm_case ]] && "$FLUIDBED" check "$tfm_case" >/dev/null 2>&1; then
  # Coarse grid, the jet widened to one coarse cell, a few steps only.
  restart_case tfm "$tfm_case" 0.01 --set grid.cell_width=0.05 --set grid.cell_height=0.05 \
    --set 'inlet.jet[0].centre=0.325' --set 'inlet.jet[0].width=0.05' --set output.interval=0.0025
  check "tfm: the restarted run wrote tracer frames" test -s "$WORK/tfm-split/tracers/000004.csv"
  # A checkpoint of the other model is named as such.
  expect 2 "final.h5: a checkpoint of the two-fluid model \(TFM\), but .*cfd.toml runs the discrete-particle model" \
    "a TFM checkpoint given to a CFD-DEM case" "$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/cfd-tfm" --quiet \
    --restart "$WORK/tfm-split/checkpoints/final.h5"
else
  echo "  SKIP  tfm restart: $tfm_case is missing or not accepted by fluidbed check (TFM not wired yet)"
fi

finish
