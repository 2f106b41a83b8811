#!/usr/bin/env bash
# The two-fluid model with periodic lateral axes (issue 30, item 1) through the command line: `check` accepts a TFM
# case periodic in x and z and refuses what the solver cannot take (hypre, an axis of 2 cells); the run is the
# same on 1 and 2 threads, after a restart, and with the multigrid CG pressure solve to its tolerance.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

# The 3D jet bed of tests/verification/tfm (10 x 20 x 4 cells of 0.02 m), periodic in x and z, with its square
# jet in the corner at the periodic planes, so that the bubble and the solids it moves cross both planes.
cat >"$WORK/ptfm.toml" <<'TOML'
case.name = "ptfm"
case.model = "tfm"
case.dimension = 3
case.end_time = 0.04
domain.width = 0.2
domain.height = 0.4
domain.depth = 0.08
domain.gravity = [0.0, -9.81, 0.0]
domain.periodic = ["x", "z"]
grid.cell_width = 0.02
grid.cell_height = 0.02
grid.cell_depth = 0.02
inlet.velocity = 1.8
[[inlet.jet]]
shape = "rectangle"
centre = 0.03
centre_z = 0.03
width = 0.04
depth = 0.04
velocity = 20.0
start = 0.0
end = 1.0
[tfm]
packed_height = 0.2
[output]
interval = 0.01
monitor_interval = 0.002
checkpoint_interval = 0.0
TOML

expect 0 "periodic in x and z" "check accepts a periodic TFM case" "$FLUIDBED" check "$WORK/ptfm.toml"
expect 2 "gas.pressure_solver.*periodic" "hypre with a periodic axis is refused" "$FLUIDBED" check "$WORK/ptfm.toml" \
  --set gas.pressure_solver=hypre-pfmg
expect 2 "grid.cell_depth.*at least 3" "a periodic axis of 2 cells is refused" "$FLUIDBED" check "$WORK/ptfm.toml" \
  --set domain.depth=0.04
run_ok "periodic TFM: 1 thread" run "$WORK/ptfm.toml" --out "$WORK/one" --threads 1 --set output.checkpoint_interval=0.02
run_ok "periodic TFM: 2 threads" run "$WORK/ptfm.toml" --out "$WORK/two" --threads 2
same_results "1 vs 2 threads" "$WORK/one" "$WORK/two"
run_ok "periodic TFM: run to 0.02 s" run "$WORK/ptfm.toml" --out "$WORK/split" --threads 2 --end-time 0.02
run_ok "periodic TFM: restart to 0.04 s" run "$WORK/ptfm.toml" --out "$WORK/split" --threads 2 \
  --restart "$WORK/split/checkpoints/final.h5"
same_results "restarted" "$WORK/one" "$WORK/split"
# The solids mass of the monitor stays the initial one: nothing leaves through a periodic plane.
check "solids mass kept to 1e-12 (monitor.csv)" \
  awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == "solids_mass_kg") c = k; next }
           c && NR == 2 { m0 = $c } c { d = $c - m0; if (d < 0) d = -d; if (d > 1e-12 * m0) bad = 1 }
           END { exit !(c && !bad) }' "$WORK/one/monitor.csv"
run_ok "periodic TFM, cg-multigrid" run "$WORK/ptfm.toml" --out "$WORK/mg" --threads 2 \
  --set gas.pressure_solver=cg-multigrid
check "cg-multigrid: the pressure drop of the Cholesky run within 1e-6" \
  awk -F, 'FNR == 1 { for (k = 1; k <= NF; ++k) if ($k == "pressure_drop_Pa") c = k; next }
           FNR == NR { a = $c; next } { b = $c } END { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-6 * a) }' \
  "$WORK/one/monitor.csv" "$WORK/mg/monitor.csv"
finish
