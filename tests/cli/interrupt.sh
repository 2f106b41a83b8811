#!/usr/bin/env bash
# SIGINT, SIGTERM, the stop file <out>/STOP and --max-wall-time each stop a run with exit 130 and a checkpoint
# named in the log, and --restart from it runs on to the end with exit 0 (issue 6).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

# Long enough (100 s simulated) to be running whenever the stop comes.
write_cfd_case "$WORK/cfd.toml" cfd
LONG=100

# stop_and_resume LABEL HOW: start a run, stop it by HOW (INT, TERM, STOP, WALL), check, restart to the end.
stop_and_resume() {
  local label=$1 how=$2 out=$WORK/$1 rc pid
  local -a extra=()
  [[ $how == WALL ]] && extra=(--max-wall-time 1)
  "$FLUIDBED" run "$WORK/cfd.toml" --out "$out" --end-time "$LONG" --quiet "${extra[@]}" >"$WORK/$label.stdout" 2>&1 &
  pid=$!
  if ! wait_for_stepping "$out" "$pid"; then
    check "$label: the run started stepping" false
    kill -KILL "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    return
  fi
  sleep 0.5
  if [[ $how == INT ]]; then
    # One run per folder: a second one into it while the first is stepping is refused and changes nothing.
    expect 2 "$out is in use by another fluidbed run \(pid $pid\)" "$label: a second run into the folder is refused" \
      "$FLUIDBED" run "$WORK/cfd.toml" --out "$out" --quiet --restart latest
  fi
  case $how in
    INT | TERM) kill -"$how" "$pid" ;;
    STOP) touch "$out/STOP" ;;
  esac
  # Nothing may hang: give it 60 s to stop, then fail.
  local k
  for ((k = 0; k < 600; ++k)); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if kill -0 "$pid" 2>/dev/null; then
    kill -KILL "$pid"
    check "$label: the run stopped within 60 s" false
  fi
  wait "$pid"
  rc=$?
  check "$label: exit code 130 (got $rc)" test "$rc" -eq 130
  local reason
  case $how in
    INT) reason='interrupted \(SIGINT\)' ;;
    TERM) reason='terminated \(SIGTERM\)' ;;
    STOP) reason='stop file .*STOP found' ;;
    WALL) reason='wall-time limit of 1 s reached' ;;
  esac
  check "$label: the log says why it stopped" grep -Eq "$reason" "$out/log.txt"
  local cp
  cp=$(logged_checkpoint "$out")
  check "$label: the log names the checkpoint to restart from" test -n "$cp"
  check "$label: that checkpoint exists" test -s "$cp"
  check "$label: the log names the checkpoint as written" grep -qF "checkpoint $cp" "$out/log.txt"
  [[ $how == STOP ]] && check "$label: the stop file is removed" test ! -e "$out/STOP"
  check "$label: no temporary file left (the stop comes between steps)" \
    test -z "$(find "$out" -name '*.tmp.*' | head -1)"
  local t_stop t_end
  t_stop=$(grep -o 'stopped at t = [0-9.e+-]*' "$out/log.txt" | tail -1 | awk '{ print $5 }')
  check "$label: stopped before the end (t = $t_stop s)" awk -v t="$t_stop" -v e="$LONG" 'BEGIN { exit !(t > 0 && t < e) }'
  check "$label: the continue command keeps --end-time $LONG" grep -q "continue with: .* --end-time $LONG .*--restart" "$out/log.txt"
  # Past the case's own end time (0.02 s), a restart without --end-time has nothing to run: refused, and it
  # does not overwrite final.h5 with a run of zero steps.
  if awk -v t="$t_stop" 'BEGIN { exit !(t > 0.02) }'; then
    expect 2 "at or past the end time 0.02 s: nothing to run" "$label: restart past the case's end time is refused" \
      "$FLUIDBED" run "$WORK/cfd.toml" --out "$out" --quiet --restart "$cp"
    check "$label: no final.h5 from the refused restart" test ! -e "$out/checkpoints/final.h5"
  fi
  t_end=$(awk -v t="$t_stop" 'BEGIN { printf "%.3f", t + 0.005 }')
  expect 0 "" "$label: --restart runs on to t = $t_end s" "$FLUIDBED" run "$WORK/cfd.toml" --out "$out" \
    --end-time "$t_end" --quiet --restart "$cp"
  check "$label: the restarted run reached the end" grep -q "done: t = " "$out/log.txt"
  check "$label: a final checkpoint" test -s "$out/checkpoints/final.h5"
  echo "$t_end" >"$WORK/$label.end"
}

stop_and_resume sigint INT
stop_and_resume sigterm TERM
stop_and_resume stopfile STOP
stop_and_resume walltime WALL

# The command the log prints reproduces the interrupted run exactly: the same --set overrides and --end-time.
# Following it literally ends in the state of a run with those settings that was never interrupted.
CONT_ARGS=(--end-time 0.3 --set inlet.velocity=2.0 --set 'inlet.jet[0].velocity=25' --quiet)
"$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/cont" "${CONT_ARGS[@]}" >/dev/null 2>&1 &
pid=$!
if wait_for_stepping "$WORK/cont" "$pid"; then
  sleep 0.3
  kill -INT "$pid"
fi
wait "$pid"
rc=$?
check "continue: stopped by SIGINT (exit $rc)" test "$rc" -eq 130
cont=$(grep -o 'continue with: fluidbed run .*' "$WORK/cont/log.txt" | tail -1 | sed 's/^continue with: fluidbed //')
check "continue: the command keeps the overrides and the end time" \
  grep -q -- "--end-time 0.3 --set inlet.velocity=2.0 --set 'inlet.jet\[0\].velocity=25' --quiet --restart" <<<"$cont"
expect 0 "" "continue: the logged command, as printed" eval "\"\$FLUIDBED\" $cont"
run_ok "continue: the same run uninterrupted" run "$WORK/cfd.toml" --out "$WORK/cont-ref" "${CONT_ARGS[@]}"
same_results "continue: logged command vs uninterrupted" "$WORK/cont-ref" "$WORK/cont"

# A stop file left in the folder before a run starts belongs to an earlier run: cleared, not obeyed.
mkdir -p "$WORK/stale"
touch "$WORK/stale/STOP"
expect 0 "" "stale STOP: the run is not stopped by it" "$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/stale" --quiet
check "stale STOP: the log says it was removed" grep -q "removed the stop file .*STOP left from an earlier run" "$WORK/stale/log.txt"
check "stale STOP: it is gone" test ! -e "$WORK/stale/STOP"

# The interrupted and resumed run equals one that was never interrupted.
t_end=$(cat "$WORK/sigint.end")
run_ok "uninterrupted run to t = $t_end s" run "$WORK/cfd.toml" --out "$WORK/straight" --end-time "$t_end"
same_results "SIGINT + restart vs uninterrupted" "$WORK/straight" "$WORK/sigint"

# A hard kill (SIGKILL: no handler runs) loses nothing but the steps after the last periodic checkpoint: a
# restart from it cuts the series back to its time and continues to the same state as an uninterrupted run.
# The first periodic checkpoint comes after the first step, so wait for three.
"$FLUIDBED" run "$WORK/cfd.toml" --out "$WORK/killed" --end-time "$LONG" --quiet \
  --set output.checkpoint_interval=0.002 >/dev/null 2>&1 &
pid=$!
if wait_for_stepping "$WORK/killed" "$pid"; then
  for ((k = 0; k < 600; ++k)); do
    [[ $(ls "$WORK"/killed/checkpoints/t*.h5 2>/dev/null | wc -l) -ge 3 ]] && break
    sleep 0.1
  done
fi
kill -KILL "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
last=$(ls "$WORK"/killed/checkpoints/t*.h5 2>/dev/null | sort | tail -1)
check "SIGKILL: periodic checkpoints were written before the kill" test -n "$last"
if [[ -n $last ]]; then
  t_cp=$(basename "$last" .h5)
  t_end=$(awk -v t="${t_cp#t}" 'BEGIN { printf "%.3f", t + 0.005 }')
  expect 0 "" "SIGKILL: --restart from $(basename "$last") to t = $t_end s" "$FLUIDBED" run "$WORK/cfd.toml" \
    --out "$WORK/killed" --end-time "$t_end" --quiet --set output.checkpoint_interval=0.002 --restart "$last"
  run_ok "SIGKILL: uninterrupted run to t = $t_end s" run "$WORK/cfd.toml" --out "$WORK/unkilled" --end-time "$t_end" \
    --set output.checkpoint_interval=0.002
  same_results "SIGKILL + restart vs uninterrupted" "$WORK/unkilled" "$WORK/killed"
fi

finish
