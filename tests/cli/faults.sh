#!/usr/bin/env bash
# A run survives its faults (issue 17): kill -9 at random points and during a checkpoint write, a failed write at
# each kind of output (disk full), and corrupted checkpoints. After each, `--restart latest` (or the refusal)
# must be what docs/reliability.md promises: the same final state bit for bit as a run that was never disturbed.
# Failed writes come from tests/cli/faults_shim.c (LD_PRELOAD), built here: no root, nothing in the program.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

SHIM=$WORK/faults_shim.so
if ! "${CC:-cc}" -shared -fPIC -O1 -o "$SHIM" "$ROOT/tests/cli/faults_shim.c" -ldl 2>"$WORK/cc.err"; then
  echo "  FAIL  cannot build the fault shim: $(cat "$WORK/cc.err")"
  exit 1
fi

# The CFD-DEM case of the other reliability tests, denser so it has cell tracers, with a checkpoint every
# 0.01 s (every 50 gas steps); and the TFM paper case on a coarse grid.
write_cfd_case "$WORK/cfd.toml" cfd
sed -i -e 's/^particles.fill_height = 0.1$/particles.fill_height = 0.06/' \
  -e 's/^output.checkpoint_interval = 0.0$/output.checkpoint_interval = 0.01/' "$WORK/cfd.toml"
TFM_SETS=(--set grid.cell_width=0.05 --set grid.cell_height=0.05 --set 'inlet.jet[0].centre=0.325'
  --set 'inlet.jet[0].width=0.05' --set output.interval=0.0025 --set output.checkpoint_interval=0.01)
DEM_T=0.2
TFM_T=0.6

dem() { "$FLUIDBED" run "$WORK/cfd.toml" --end-time "$DEM_T" --quiet "$@"; }
tfm() { "$FLUIDBED" run "$ROOT/cases/gera1998/tfm.toml" --end-time "$TFM_T" --quiet "${TFM_SETS[@]}" "$@"; }

expect 0 "" "dem: uninterrupted reference run" dem --out "$WORK/dem-ref"
expect 0 "" "tfm: uninterrupted reference run" tfm --out "$WORK/tfm-ref"

no_temporaries() {  # no_temporaries LABEL DIR: nothing left under a temporary or partial name
  check "$1: no temporary file left" bash -c "! find '$2' -name '*.tmp.*' | grep ."
}

# ---- kill -9 at random points, then --restart latest -----------------------------------------------------------
# kill_and_resume LABEL MODEL DELAY: start, wait for the first checkpoint, kill -9 after DELAY more seconds,
# restart from the newest valid checkpoint, compare with the reference.
kill_and_resume() {
  local label=$1 model=$2 delay=$3 out=$WORK/$1 pid k
  # The program itself in the background (a backgrounded shell function would be a subshell, and the kill would
  # miss the run).
  case $model in
    dem) "$FLUIDBED" run "$WORK/cfd.toml" --end-time "$DEM_T" --quiet --out "$out" >/dev/null 2>&1 & ;;
    tfm) "$FLUIDBED" run "$ROOT/cases/gera1998/tfm.toml" --end-time "$TFM_T" --quiet "${TFM_SETS[@]}" --out "$out" \
      >/dev/null 2>&1 & ;;
  esac
  pid=$!
  for ((k = 0; k < 600; ++k)); do
    ls "$out"/checkpoints/t*.h5 >/dev/null 2>&1 && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.05
  done
  sleep "$delay"
  kill -KILL "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  if [[ -e $out/checkpoints/final.h5 ]]; then
    echo "  note  $label: the run finished before the kill (${delay} s); resuming is then a no-op"
    same_results "$label" "$WORK/$model-ref" "$out"
    return
  fi
  expect 0 "" "$label: --restart latest after kill -9 at +${delay} s" $model --out "$out" --restart latest
  check "$label: the log says which checkpoint it took" grep -q -- "--restart latest: took .*checkpoints/t" "$out/log.txt"
  no_temporaries "$label" "$out"
  same_results "$label" "$WORK/$model-ref" "$out"
}

# Random delays (RANDOM, printed so a failure can be replayed) within the runs' wall time (1 to 3 s here).
for label in dem-kill1 dem-kill2; do
  kill_and_resume "$label" dem "0.$((RANDOM % 8))$((RANDOM % 10))"
done
kill_and_resume tfm-kill1 tfm "0.$((RANDOM % 5))$((RANDOM % 10))"

# kill -9 in the middle of a checkpoint write (the shim writes half of the call, then kills): the file being
# written is never seen under its name, the previous checkpoint is kept, and the restart ends in the same state.
kill_in_checkpoint() {  # kill_in_checkpoint LABEL MODEL CHECKPOINT WRITE_NUMBER: killed in that write to it
  local label=$1 model=$2 name=$3 n=$4 out=$WORK/$1
  FAULT_PATH=/checkpoints/$name FAULT_AFTER=$n FAULT_ACTION=kill LD_PRELOAD=$SHIM $model --out "$out" >/dev/null 2>&1
  local rc=$?
  check "$label: killed during a checkpoint write (exit $rc)" test "$rc" -eq 137
  check "$label: the killed write left its temporary, not a checkpoint" \
    test -n "$(find "$out/checkpoints" -name '*.h5.tmp.*' | head -1)"
  expect 0 "" "$label: --restart latest" $model --out "$out" --restart latest
  check "$label: the temporary of the killed run is removed" grep -q "removed 1 temporary file" "$out/log.txt"
  no_temporaries "$label" "$out"
  same_results "$label" "$WORK/$model-ref" "$out"
}
kill_in_checkpoint dem-kill-in-checkpoint dem t0.050000 3
kill_in_checkpoint tfm-kill-in-checkpoint tfm t0.030000 5

# ---- a failed write at each kind of output (disk full) -----------------------------------------------------------
# disk_full LABEL PATTERN N [PARTIAL]: the N-th write to a file matching PATTERN fails with ENOSPC (and every
# later one): exit 3, the file and the space named, the last complete checkpoint named and intact (the
# restart from it reaches the reference state), no temporary or partial file left.
disk_full() {
  local label=$1 pattern=$2 n=$3 partial=${4:-0} out=$WORK/$1
  expect 3 "cannot write .*$pattern.*: No space left on device.* free on .*the last complete checkpoint is .*checkpoints/t0\.[0-9]*\.h5; continue with: fluidbed run .* --restart" \
    "$label: exit 3 naming the file, the space and the checkpoint" \
    env FAULT_PATH="$pattern" FAULT_AFTER="$n" FAULT_PARTIAL="$partial" LD_PRELOAD="$SHIM" \
    "$FLUIDBED" run "$WORK/cfd.toml" --end-time "$DEM_T" --quiet --out "$out"
  check "$label: log.txt has the diagnosis" grep -q "the simulation failed: .*No space left on device" "$out/log.txt"
  no_temporaries "$label" "$out"
  check "$label: monitor.csv holds whole rows only" \
    awk -F, 'NR == 1 { n = NF } NF != n { exit 1 }' "$out/monitor.csv"
  check "$label: monitor.csv ends with a whole line" test "$(tail -c 1 "$out/monitor.csv" | od -An -c | tr -d ' ')" = '\n'
  check "$label: no final checkpoint" test ! -e "$out/checkpoints/final.h5"
  local cp
  cp=$(grep -o 'the last complete checkpoint is [^;]*' "$out/log.txt" | tail -1 | awk '{ print $NF }')
  expect 0 "" "$label: the named checkpoint continues the run" dem --out "$out" --restart "$cp"
  same_results "$label" "$WORK/dem-ref" "$out"
}
disk_full disk-full-field-frame fields/000013.vti 1
disk_full disk-full-particle-frame particles/000017.vtu 1
disk_full disk-full-particle-csv particles/000021.csv 1
disk_full disk-full-monitor-row monitor.csv 60 1
disk_full disk-full-checkpoint checkpoints/t0.030000 3
disk_full disk-full-checkpoint-first-write checkpoints/t0.050000 1

# ---- corrupted checkpoints ---------------------------------------------------------------------------------------
# A copy of the reference's last periodic checkpoint, damaged four ways; each restart from it is refused with
# exit 2 naming the file (and the dataset or attribute where the damage is found), before the folder changes.
good=$(ls "$WORK"/dem-ref/checkpoints/t*.h5 | sort | tail -1)
corrupt() {  # corrupt LABEL REGEX PYTHON-EXPRESSION-OF-data: write the damaged copy, expect the refusal
  local label=$1 regex=$2 expr=$3 bad=$WORK/$1.h5
  if ! python3 - "$good" "$bad" "$expr" <<'PY'
import struct, sys
src, dst, expr = sys.argv[1:]
data = bytearray(open(src, "rb").read())
def flip(at, n=1):
    for k in range(at, at + n):
        data[k] ^= 0xFF
exec(expr)
open(dst, "wb").write(data)
PY
  then
    check "$label: the damage could be placed" false
    return
  fi
  expect 2 "$bad: .*$regex" "$label: refused" dem --out "$WORK/$label-out" --restart "$bad"
  check "$label: nothing written into the output folder" test ! -e "$WORK/$label-out/case.toml"
}
corrupt truncated "." 'del data[len(data) // 2:]'
corrupt header-flipped "." 'flip(20, 4)'
# A dataset: the x coordinate of particle 0 at the checkpoint's time, found by its bit pattern (the particle
# CSV of the same instant holds it at full precision).
t_good=$(basename "$good" .h5)
frame=$(awk -v t="${t_good#t}" '$1 + 0 == t + 0 { print $2 }' <(pvd_entries "$WORK/dem-ref/particles.pvd") | head -1)
x0=$(awk -F, 'NR == 2 { print $2 }' "$WORK/dem-ref/${frame%.vtu}.csv")
corrupt dataset-flipped "corrupt: dataset 'dem/[a-z_]+' fails its checksum" \
  "at = data.find(struct.pack('<d', float('$x0'))); assert at > 0; flip(at + 3)"
# An attribute: one byte of the case record (the resolved case.toml kept in the checkpoint).
corrupt attribute-flipped "." "at = data.find(b'fill_height'); assert at > 0; flip(at + 2)"

# A sweep of one flipped byte every 1/24 of the file (the issue's report: bytes flipped in the middle of a checkpoint
# were loaded and failed the run later). Each damaged copy is refused, or the byte was one no object uses (HDF5
# leaves a few such gaps) and the run from it ends in the reference state bit for bit: never a silently changed state.
size=$(stat -c %s "$good")
frame_end=$(pvd_entries "$WORK/dem-ref/particles.pvd" | tail -1 | cut -d' ' -f2)
for ((k = 1; k < 24; ++k)); do
  at=$((size * k / 24))
  python3 -c "import sys; d = bytearray(open(sys.argv[1], 'rb').read()); d[int(sys.argv[3])] ^= 0xFF; open(sys.argv[2], 'wb').write(d)" \
    "$good" "$WORK/sweep.h5" "$at"
  rm -rf "$WORK/sweep"
  dem --out "$WORK/sweep" --restart "$WORK/sweep.h5" >"$WORK/sweep.err" 2>&1
  rc=$?
  if [[ $rc -eq 2 ]]; then
    check "byte $at of $size flipped: refused ($(grep -o 'corrupt: [a-z]* .[^ ]*' "$WORK/sweep.err" | head -1))" \
      grep -q "$WORK/sweep.h5: " "$WORK/sweep.err"
  else
    check "byte $at of $size flipped: accepted (exit $rc), so the final state must be the reference's" \
      cmp "$WORK/dem-ref/${frame_end%.vtu}.csv" "$WORK/sweep/${frame_end%.vtu}.csv"
  fi
done

# --restart latest skips a damaged newest checkpoint, says so, and continues from the one before: same state.
expect 130 "" "latest-skip: a run stopped by the wall-time limit" dem --out "$WORK/latest-skip" --max-wall-time 0.5
newest=$(ls -t "$WORK"/latest-skip/checkpoints/t*.h5 | head -1)
python3 -c "import sys; p = sys.argv[1]; d = bytearray(open(p, 'rb').read()); d[len(d) // 2] ^= 0xFF; open(p, 'wb').write(d)" "$newest"
expect 0 "" "latest-skip: --restart latest with the newest checkpoint damaged" dem --out "$WORK/latest-skip" --restart latest
check "latest-skip: the log names the skipped checkpoint and why" \
  grep -q -- "--restart latest: skipped $newest: corrupt" "$WORK/latest-skip/log.txt"
same_results "latest-skip" "$WORK/dem-ref" "$WORK/latest-skip"

finish
