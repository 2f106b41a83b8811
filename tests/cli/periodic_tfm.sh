#!/usr/bin/env bash
# The two-fluid model with periodic lateral axes (issue 30, item 1) through the command line: `check` accepts a TFM
# case periodic in x and z and refuses what the solver cannot take (hypre, an axis of 2 cells); the run is the
# same on 1 and 2 threads, after a restart, and with the multigrid CG pressure solve to its tolerance.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

# The case (tests/cli/periodic_tfm.toml): the 3D jet bed of tests/verification/tfm (10 x 20 x 4 cells of 0.02 m),
# periodic in x and z, with its square jet in the corner at the periodic planes, so that the bubble and the solids
# it moves cross both planes.

expect 0 "periodic in x and z" "check accepts a periodic TFM case" "$FLUIDBED" check "$ROOT/tests/cli/periodic_tfm.toml"
expect 2 "gas.pressure_solver.*periodic" "hypre with a periodic axis is refused" "$FLUIDBED" check "$ROOT/tests/cli/periodic_tfm.toml" \
  --set gas.pressure_solver=hypre-pfmg
expect 2 "grid.cell_depth.*at least 3" "a periodic axis of 2 cells is refused" "$FLUIDBED" check "$ROOT/tests/cli/periodic_tfm.toml" \
  --set domain.depth=0.04
run_ok "periodic TFM: 1 thread" run "$ROOT/tests/cli/periodic_tfm.toml" --out "$WORK/one" --threads 1 --set output.checkpoint_interval=0.02
run_ok "periodic TFM: 2 threads" run "$ROOT/tests/cli/periodic_tfm.toml" --out "$WORK/two" --threads 2
same_results "1 vs 2 threads" "$WORK/one" "$WORK/two"
run_ok "periodic TFM: run to 0.02 s" run "$ROOT/tests/cli/periodic_tfm.toml" --out "$WORK/split" --threads 2 --end-time 0.02
run_ok "periodic TFM: restart to 0.04 s" run "$ROOT/tests/cli/periodic_tfm.toml" --out "$WORK/split" --threads 2 \
  --restart "$WORK/split/checkpoints/final.h5"
same_results "restarted" "$WORK/one" "$WORK/split"
# The solids mass of the monitor stays the initial one: nothing leaves through a periodic plane.
check "solids mass kept to 1e-12 (monitor.csv)" \
  awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == "solids_mass_kg") c = k; next }
           c && NR == 2 { m0 = $c } c { d = $c - m0; if (d < 0) d = -d; if (d > 1e-12 * m0) bad = 1 }
           END { exit !(c && !bad) }' "$WORK/one/monitor.csv"
run_ok "periodic TFM, cg-multigrid" run "$ROOT/tests/cli/periodic_tfm.toml" --out "$WORK/mg" --threads 2 \
  --set gas.pressure_solver=cg-multigrid
check "cg-multigrid: the pressure drop of the Cholesky run within 1e-6" \
  awk -F, 'FNR == 1 { for (k = 1; k <= NF; ++k) if ($k == "pressure_drop_Pa") c = k; next }
           FNR == NR { a = $c; next } { b = $c } END { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-6 * a) }' \
  "$WORK/one/monitor.csv" "$WORK/mg/monitor.csv"
finish
