#!/usr/bin/env bash
# Run control and faults on several ranks (issue 29, item 8): a signal to one rank stops every rank at the same
# step with one checkpoint (exit 130), SIGUSR1 to the launcher likewise, the stop file and the wall-time limit too;
# a failure found by all ranks together is said once with its diagnosis and a saved state (exit 3); a rank that
# fails alone stops all with its diagnosis (exit 3), never a hang; a rank killed with SIGKILL makes the others exit
# non-zero within 60 s; and --restart latest on another number of ranks continues each of them to the bits of the
# uninterrupted run.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
export FLUIDBED_FAILURE_WAIT=5  # a lone rank's failure is said after 5 s instead of 30
check "mpiexec is installed (make deps)" command -v mpiexec

# The regression oracle's 3D bed without its jet (quiet: it runs as long as asked), settled once.
case_file="$ROOT/tests/oracle/dem3d.toml"
common=(--set "settle.cache=\"$WORK/bed.csv\"" --set 'inlet.jet=[]' --set output.checkpoint_interval=0.01
        --set output.particles_csv=true --set output.interval=0.01 --threads 1)
run_ok "the uninterrupted run, one process" run "$case_file" --out "$WORK/whole" --end-time 0.3 "${common[@]}"

start_mpi() {  # start_mpi RANKS OUT: a run to 5 s in the background; its launcher's pid in MPI_PID
  mpiexec -n "$1" --oversubscribe "$FLUIDBED" run "$case_file" --out "$2" --end-time 0.3 "${common[@]}" --quiet \
    >"$2.out" 2>&1 &
  MPI_PID=$!
}
ranks_of() { pgrep -P "$1" | sort -n; }
elapsed_since() { echo $(( $(date +%s) - $1 )); }

# SIGTERM to one rank (as a batch system sends it): every rank stops at the same step; continued on 2 ranks.
mkdir -p "$WORK/term"
start_mpi 3 "$WORK/term"
wait_for_stepping "$WORK/term" "$MPI_PID"
sleep 1
kill -TERM "$(ranks_of "$MPI_PID" | tail -1)"
wait "$MPI_PID"
rc=$?
check "SIGTERM to one of 3 ranks: exit 130 (got $rc)" test "$rc" -eq 130
check "SIGTERM: one checkpoint of the stop, said once" test "$(grep -c 'stopped at t = ' "$WORK/term/log.txt")" -eq 1
expect 0 "" "SIGTERM: continued on 2 ranks" mpiexec -n 2 --oversubscribe "$FLUIDBED" run "$case_file" \
  --out "$WORK/term" --end-time 0.3 "${common[@]}" --quiet --restart latest
same_results "SIGTERM on 3 ranks, continued on 2, vs uninterrupted" "$WORK/whole" "$WORK/term"

# SIGUSR1 to the launcher (mpirun forwards it to every rank), continued on one process.
mkdir -p "$WORK/usr1"
start_mpi 2 "$WORK/usr1"
wait_for_stepping "$WORK/usr1" "$MPI_PID"
sleep 1
kill -USR1 "$MPI_PID"
wait "$MPI_PID"
rc=$?
check "SIGUSR1 to mpirun: exit 130 (got $rc)" test "$rc" -eq 130
check "SIGUSR1: the stop is logged" grep -q 'stop asked for (SIGUSR1)' "$WORK/usr1/log.txt"
run_ok "SIGUSR1: continued on one process" run "$case_file" --out "$WORK/usr1" --end-time 0.3 "${common[@]}" --restart latest
same_results "SIGUSR1 on 2 ranks, continued on 1, vs uninterrupted" "$WORK/whole" "$WORK/usr1"

# The stop file, seen by rank 0, stops all; the wall-time limit likewise.
mkdir -p "$WORK/stop"
start_mpi 4 "$WORK/stop"
wait_for_stepping "$WORK/stop" "$MPI_PID"
touch "$WORK/stop/STOP"
wait "$MPI_PID"
rc=$?
check "stop file on 4 ranks: exit 130 (got $rc)" test "$rc" -eq 130
check "stop file: logged" grep -q 'stop file .* found' "$WORK/stop/log.txt"
expect 130 "" "wall-time limit on 2 ranks: exit 130" mpiexec -n 2 --oversubscribe "$FLUIDBED" run "$case_file" \
  --out "$WORK/wall" --end-time 0.3 "${common[@]}" --quiet --max-wall-time 0.5
check "wall-time limit: logged" grep -q 'wall-time limit of 0.5 s reached' "$WORK/wall/log.txt"

# A failure all ranks find together (the overlap test is a reduction over them): said once, state saved, exit 3.
out=$(mpiexec -n 3 --oversubscribe "$FLUIDBED" run "$case_file" --out "$WORK/overlap" --end-time 0.3 "${common[@]}" \
  --quiet --set dem.max_overlap_fraction=0.001 2>&1)
rc=$?
check "collective failure: exit 3 (got $rc)" test "$rc" -eq 3
check "collective failure: the diagnosis once" test "$(grep -c 'a contact overlaps by' <<<"$out")" -eq 1
check "collective failure: the state is saved" bash -c "ls '$WORK/overlap/checkpoints/' | grep -q '^failed-t'"

# A failure of one rank alone (FLUIDBED_FAULT injects one where no other rank can see it): that rank says it and
# ends every rank, within the verdict's wait.
t0=$(date +%s)
out=$(FLUIDBED_FAULT="throw 1 20" mpiexec -n 3 --oversubscribe -x FLUIDBED_FAULT "$FLUIDBED" run "$case_file" \
  --out "$WORK/alone" --end-time 0.3 "${common[@]}" --quiet 2>&1)
rc=$?
check "one rank fails alone: exit 3 (got $rc)" test "$rc" -eq 3
check "one rank fails alone: its diagnosis, with its rank" grep -q 'rank 1: t = .* a failure injected on rank 1' <<<"$out"
check "one rank fails alone: the run ends within 60 s ($(elapsed_since "$t0") s)" test "$(elapsed_since "$t0")" -lt 60

# A rank killed with SIGKILL: the launcher ends the others within 60 s, non-zero; the last periodic checkpoint
# continues on 2 ranks to the uninterrupted bits.
mkdir -p "$WORK/kill"
start_mpi 3 "$WORK/kill"
wait_for_stepping "$WORK/kill" "$MPI_PID"
for ((k = 0; k < 200; ++k)); do
  ls "$WORK/kill/checkpoints/" 2>/dev/null | grep -q '^t0.02' && break
  sleep 0.1
done
t0=$(date +%s)
ranks=$(ranks_of "$MPI_PID")
kill -KILL "$(head -2 <<<"$ranks" | tail -1)"
wait "$MPI_PID"
rc=$?
check "SIGKILL of one rank: the others exit non-zero (got $rc)" test "$rc" -ne 0
check "SIGKILL of one rank: ended within 60 s ($(elapsed_since "$t0") s)" test "$(elapsed_since "$t0")" -lt 60
alive() {  # alive PID...: some PID still runs (a zombie whose parent is gone has ended)
  local r st
  for r in "$@"; do
    st=$(ps -o stat= -p "$r" 2>/dev/null) || continue
    [[ $st == Z* ]] || return 0
  done
  return 1
}
check "SIGKILL of one rank: no rank is left" bash -c "$(declare -f alive); ! alive $(tr '\n' ' ' <<<"$ranks")"
expect 0 "" "SIGKILL: continued on 2 ranks from the latest checkpoint" mpiexec -n 2 --oversubscribe "$FLUIDBED" run \
  "$case_file" --out "$WORK/kill" --end-time 0.3 "${common[@]}" --quiet --restart latest
same_results "SIGKILL on 3 ranks, continued on 2, vs uninterrupted" "$WORK/whole" "$WORK/kill"
finish
