#!/usr/bin/env bash
# fluidbed started by an MPI launcher: `run` splits a CFD-DEM case over the processes (one log, one progress, rank 0
# writes the folder); what cannot run on several ranks in this version is refused once, with exit 2, before any
# output: an ensemble (its members are processes of their own) and a two-fluid case whose pressure backend runs on one
# process (the TFM on several ranks takes cg-multigrid). One process under the launcher runs as without it.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
check "mpiexec is installed (make deps)" command -v mpiexec
dem_case="$ROOT/tests/oracle/dem3d.toml"
tfm_case="$ROOT/cases/tfm3d/slab.toml"
expect 0 "" "two ranks run a CFD-DEM case" \
  mpiexec -n 2 --oversubscribe "$FLUIDBED" run "$dem_case" --end-time 0.004 --out "$WORK/two" --quiet
check "one log, written by rank 0: the start is logged once" test "$(grep -c 'fluidbed run ' "$WORK/two/log.txt")" -eq 1
check "the log says the ranks" grep -q "2 ranks (MPI) x 1 thread each" "$WORK/two/log.txt"
check "and writes its monitor" test -s "$WORK/two/monitor.csv"
out=$(mpiexec -n 2 --oversubscribe "$FLUIDBED" run "$dem_case" --end-time 0.004 --out "$WORK/chatty" 2>&1)
check "the terminal shows the run's lines once" test "$(grep -c '^done: t = ' <<<"$out")" -eq 1
expect 2 "cg-multigrid" "the TFM on two ranks with a one-process pressure backend (eigen) is refused" \
  mpiexec -n 2 --oversubscribe "$FLUIDBED" run "$tfm_case" --end-time 0.002 --out "$WORK/tfm" --quiet
out=$(mpiexec -n 2 --oversubscribe "$FLUIDBED" run "$tfm_case" --end-time 0.002 --out "$WORK/tfm2" --quiet 2>&1)
check "the refusal is said once" test "$(grep -c 'cg-multigrid' <<<"$out")" -eq 1
expect 0 "" "the TFM on two ranks with cg-multigrid runs" \
  mpiexec -n 2 --oversubscribe "$FLUIDBED" run "$tfm_case" --end-time 0.002 --out "$WORK/tfm3" --quiet \
  --set gas.pressure_solver='"cg-multigrid"'
check "and writes its monitor" test -s "$WORK/tfm3/monitor.csv"
expect 2 "started as 3 processes" "an ensemble on three ranks is refused" \
  mpiexec -n 3 --oversubscribe "$FLUIDBED" ensemble "$tfm_case" -n 2 --out "$WORK/ens"
check "refused before writing anything" test ! -e "$WORK/ens"
expect 0 "" "one rank under the launcher runs" \
  mpiexec -n 1 "$FLUIDBED" run "$tfm_case" --end-time 0.002 --out "$WORK/one" --quiet
check "and writes its monitor" test -s "$WORK/one/monitor.csv"
# A bad case is said once with its exit code, on any number of ranks.
expect 2 "unknown key" "a bad key on three ranks: exit 2" \
  mpiexec -n 3 --oversubscribe "$FLUIDBED" run "$dem_case" --set dem.no_such_key=1 --out "$WORK/bad" --quiet
out=$(mpiexec -n 3 --oversubscribe "$FLUIDBED" run "$dem_case" --set dem.no_such_key=1 --out "$WORK/bad" --quiet 2>&1)
check "the bad key is said once" test "$(grep -c 'no_such_key' <<<"$out")" -eq 1
finish
