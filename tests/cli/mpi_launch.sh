#!/usr/bin/env bash
# fluidbed started by an MPI launcher on several processes: refused once, with exit 2, before any output, since this
# version runs a case on one process (each copy would write the same folder). One process under the launcher runs.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
check "mpiexec is installed (make deps)" command -v mpiexec
case_file="$ROOT/cases/tfm3d/slab.toml"
expect 2 "started as 2 processes by an MPI launcher" "two ranks are refused" \
  mpiexec -n 2 --oversubscribe "$FLUIDBED" run "$case_file" --end-time 0.002 --out "$WORK/two" --quiet
check "refused before writing anything" test ! -e "$WORK/two"
out=$(mpiexec -n 2 --oversubscribe "$FLUIDBED" run "$case_file" --out "$WORK/two" 2>&1)
check "the refusal is said once" test "$(grep -c 'started as 2 processes' <<<"$out")" -eq 1
expect 2 "started as 3 processes" "an ensemble on three ranks is refused" \
  mpiexec -n 3 --oversubscribe "$FLUIDBED" ensemble "$case_file" -n 2 --out "$WORK/ens"
expect 0 "" "one rank under the launcher runs" \
  mpiexec -n 1 "$FLUIDBED" run "$case_file" --end-time 0.002 --out "$WORK/one" --quiet
check "and writes its monitor" test -s "$WORK/one/monitor.csv"
# The environment a launcher sets is what is read (Slurm's srun sets these).
expect 2 "started as 4 processes" "srun's four tasks are refused" \
  env SLURM_STEP_NUM_TASKS=4 SLURM_PROCID=0 "$FLUIDBED" run "$case_file" --out "$WORK/srun"
finish
