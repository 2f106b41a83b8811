#!/usr/bin/env bash
# A failing simulation ends with exit 3, a diagnosis on stderr and in log.txt (time, what, where, likely cause,
# remedy) and a last checkpoint checkpoints/failed-*.h5; nothing is silently dropped or clamped (issue 6).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

# failed LABEL REGEX CASE [args]: exit 3 with REGEX on stderr, the error in log.txt, a failed-*.h5 checkpoint.
failed() {
  local label=$1 regex=$2 case=$3
  shift 3
  local out=$WORK/$label
  expect 3 "$regex" "$label: exit 3 and diagnosis" "$FLUIDBED" run "$case" --out "$out" --quiet "$@"
  check "$label: log.txt has the diagnosis" grep -Eq "the simulation failed.*($regex)" "$out/log.txt"
  check "$label: last state in checkpoints/failed-*.h5" bash -c "ls '$out'/checkpoints/failed-t*.h5 >/dev/null"
  check "$label: log.txt names that checkpoint" grep -q "last state saved to .*checkpoints/failed-t.*\.h5" "$out/log.txt"
  check "$label: no final checkpoint" test ! -e "$out/checkpoints/final.h5"
}

# DEM alone from a particle file: 0.1 x 0.2 m, open top, default 2e-4 s steps.
dem_case() {  # dem_case NAME CSV-ROWS...
  local name=$1
  shift
  printf 'id,x,y,vx,vy,omega,species\n' >"$WORK/$name.csv"
  printf '%s\n' "$@" >>"$WORK/$name.csv"
  cat >"$WORK/$name.toml" <<TOML
case.name = "$name"
case.end_time = 0.01
domain.width = 0.1
domain.height = 0.2
settle.enabled = false
gas.enabled = false
grid.cell_width = 0.01
particles.source = "file"
particles.file = "$name.csv"
output.interval = 0.005
output.checkpoint_interval = 0.0
TOML
}

# 1. A particle at 1000 m/s towards the open top leaves in the first step (0.2 m per step): its id, position and
#    velocity are named, with the cause and the remedy.
dem_case escape '3,0.02,0.01,0,0,0,0' '7,0.05,0.15,0,1000,0,0'
failed escape 't = [0-9.e-]+ s: particle 7 left .*(domain|top).*velocity \(0, 999\.9[0-9]*\) m/s.*[Ll]ikely cause.*remedy' \
  "$WORK/escape.toml"

# 2. Two 4 mm particles placed 3.2 mm apart overlap by 20% of the diameter, above the 10% limit: the overlap, the
#    limit, the pair (ids 3 and 4) and the remedy are named.
dem_case overlap '3,0.05,0.05,0,0,0,0' '4,0.0532,0.05,0,0,0,0' '5,0.02,0.01,0,0,0,0'
failed overlap 't = [0-9.e-]+ s: a contact overlaps by 0\.0008 m, .*more than .*10%.*Likely cause.*remedy' \
  "$WORK/overlap.toml"
check "overlap: the pair is named (particles 3 and 4)" grep -Eq 'particles? 3( \(d = [^)]*\))? and 4' "$WORK/overlap/log.txt"

# 3. The gas: SIMPLE that cannot converge in 30 iterations once a 300 m/s jet opens at t = 1 ms. The remedy must
#    name a key that exists (gas.max_iterations). The fixed tolerances alone: under the coupling bound this jet's
#    steps end on the bound in 6 iterations and the bed fails later, on a contact's overlap.
write_cfd_case "$WORK/simple.toml" simple 'gas.max_iterations = 30' 'gas.coupling_tolerance = 0'
sed -i -e 's/^velocity = 20.0/velocity = 300.0/' -e 's/^start = 0.0/start = 0.001/' "$WORK/simple.toml"
failed simple 'gas: SIMPLE did not converge at t = [0-9.e-]+ s.*residual.*gas\.max_iterations' "$WORK/simple.toml"
check "simple: it failed after the jet opened, not before" grep -Eq 'converge at t = 0\.001[0-9]* s' "$WORK/simple/log.txt"
# Under the bound, a SIMPLE stopped short of both says so: the last move, the step's change, the contraction.
write_cfd_case "$WORK/bound.toml" bound 'gas.max_iterations = 3'
expect 3 'SIMPLE did not converge at t = 0 s.*nor the coupling bound \(last move [0-9.e+-]+ of a step.s change [0-9.e+-]+, contraction [0-9.]+, gas\.coupling_tolerance = 0\.01\)' \
  "bound: the diagnosis names the coupling bound" "$FLUIDBED" run "$WORK/bound.toml" --out "$WORK/bound" --quiet

# 4. An absurd jet (1e6 m/s) makes the momentum solve produce NaN: the diagnosis must say when and what to do.
write_cfd_case "$WORK/absurd.toml" absurd
sed -i -e 's/^velocity = 20.0/velocity = 1e6/' -e 's/^start = 0.0/start = 0.001/' "$WORK/absurd.toml"
failed absurd 'gas.*(t = [0-9.e-]+ s).*(remedy|reduce|lower)' "$WORK/absurd.toml"

# 5. A gas failure in the initial gas solve at t = 0 (one SIMPLE iteration, tolerance 1e-12): exit 3 and the
#    diagnosis, in log.txt too. No checkpoint: nothing has happened yet, the case itself reproduces that state.
write_cfd_case "$WORK/initial.toml" initial 'gas.max_iterations = 1' 'gas.mass_tolerance = 1e-12'
expect 3 'SIMPLE did not converge at t = 0 s.*gas\.max_iterations' "initial: exit 3 and diagnosis" \
  "$FLUIDBED" run "$WORK/initial.toml" --out "$WORK/initial" --quiet
check "initial: log.txt has the diagnosis" grep -Eq "the simulation failed.*SIMPLE did not converge" "$WORK/initial/log.txt"

# Non-finite or outside input is bad input (exit 2), never clamped: a NaN velocity, an infinite spin, a particle
# outside the domain, a NaN or infinite case value.
dem_case nan_velocity '0,0.05,0.05,nan,0,0,0'
expect 2 'nan_velocity.csv: row 2, column (4|vx).*not finite' "particle CSV with a NaN velocity" \
  "$FLUIDBED" check "$WORK/nan_velocity.toml"
dem_case inf_spin '0,0.05,0.05,0,0,inf,0'
expect 2 'inf_spin.csv: row 2, column (6|omega).*not finite' "particle CSV with an infinite spin" \
  "$FLUIDBED" check "$WORK/inf_spin.toml"
dem_case outside '0,0.05,0.05,0,0,0,0' '1,0.15,0.05,0,0,0,0'
expect 2 'outside.csv: row 3, columns x,y: particle 1 at \(0\.15, 0\.05\) m is not inside' \
  "particle CSV with a particle outside" "$FLUIDBED" check "$WORK/outside.toml"
write_cfd_case "$WORK/nan.toml" nan
expect 2 'inlet.velocity: nan is out of range: must be finite' "inlet.velocity = nan" \
  "$FLUIDBED" check "$WORK/nan.toml" --set inlet.velocity=nan
expect 2 'gas.top_pressure: inf is out of range: must be finite' "gas.top_pressure = inf" \
  "$FLUIDBED" check "$WORK/nan.toml" --set gas.top_pressure=inf
expect 2 'inlet.jet\[0\].velocity: -?nan is out of range: must be finite' "inlet.jet[0].velocity = nan" \
  "$FLUIDBED" check "$WORK/nan.toml" --set 'inlet.jet[0].velocity=nan'

finish
