# Helpers of the reliability tests (restart, threads, interrupt, failures): sourced after lib.sh.
# Named .bash, not .sh, because ctest runs every tests/cli/*.sh as a test.

check() {  # check NAME COMMAND...: passes when the command succeeds
  local name=$1
  shift
  if "$@" >"$WORK/check.out" 2>&1; then
    PASS=$((PASS + 1))
    printf '  ok    %s\n' "$name"
  else
    FAIL=$((FAIL + 1))
    printf '  FAIL  %s\n' "$name"
    sed 's/^/        /' "$WORK/check.out" | head -20
  fi
}

run_ok() {  # run_ok NAME fluidbed-arguments...: a run that must exit 0
  local name=$1
  shift
  expect 0 "" "$name" "$FLUIDBED" "$@" --quiet
}

# A small CFD-DEM case: 200 particles dropped into a 0.1 x 0.2 m bed of 10 x 20 gas cells, with the background
# inflow and a one-cell jet, so that every part of the coupled step (drag, voidage, SIMPLE, inlet) runs.
# Particle CSVs are on so the state can be compared at full precision.
write_cfd_case() {  # write_cfd_case FILE NAME [extra 'key = value' lines before the jet table]
  local file=$1 name=$2
  shift 2
  {
    printf 'case.name = "%s"\n' "$name"
    cat <<'TOML'
case.end_time = 0.02
case.seed = 7
domain.width = 0.1
domain.height = 0.2
particles.count = 200
particles.fill_height = 0.1
particles.layers = 2
settle.enabled = false
dem.time_step = 1e-4
grid.cell_width = 0.01
coupling.dem_substeps = 2
inlet.velocity = 1.8
output.interval = 0.005
output.monitor_interval = 0.001
output.checkpoint_interval = 0.0
output.particles_csv = true
TOML
    local kv
    for kv in "$@"; do printf '%s\n' "$kv"; done
    cat <<'TOML'
[[inlet.jet]]
centre = 0.055
width = 0.01
velocity = 20.0
start = 0.0
end = 0.4
TOML
  } >"$file"
}

# monitor.csv without its wall_s column (the only column that may differ between equal runs).
monitor_without_wall() {
  awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == "wall_s") w = k }
           { line = ""; for (k = 1; k <= NF; ++k) if (k != w) line = line (line == "" ? "" : ",") $k; print line }' "$1"
}

# The (time, file) entries of a .pvd collection, one per line.
pvd_entries() {
  grep -o 'timestep="[^"]*"[^>]*file="[^"]*"' "$1" | sed -E 's/timestep="([^"]*)".*file="([^"]*)"/\1 \2/'
}

# Frame files NNNNNN.csv/.vtu/.vti (not the NAME.tmp.<pid> a hard kill may leave behind).
frame_count() {
  find "$1/fields" "$1/particles" "$1/tracers" -regextype posix-extended -regex '.*/[0-9]{6}\.(csv|vtu|vti)' 2>/dev/null | wc -l
}

# Two run folders hold the same results: particle CSVs, .vti and .vtu frames and the cell tracers (ids,
# positions and layers of the balls) byte for byte, monitor.csv without wall_s, the same .pvd entries, none twice.
same_results() {  # same_results LABEL DIR_A DIR_B
  local label=$1 a=$2 b=$3 f rel
  local -a frames=()
  for f in "$a"/particles/*.csv "$a"/particles/*.vtu "$a"/fields/*.vti "$a"/tracers/*.csv; do
    [[ -e $f ]] && frames+=("${f#"$a"/}")
  done
  check "$label: output frames exist" test "${#frames[@]}" -gt 0
  for rel in "${frames[@]}"; do
    check "$label: $rel identical" cmp "$a/$rel" "$b/$rel"
  done
  check "$label: same number of frames" test "$(frame_count "$a")" = "$(frame_count "$b")"
  check "$label: monitor.csv rows identical (without wall_s)" \
    cmp <(monitor_without_wall "$a/monitor.csv") <(monitor_without_wall "$b/monitor.csv")
  for f in fields.pvd particles.pvd; do
    [[ -e $a/$f || -e $b/$f ]] || continue
    check "$label: $f entries identical" cmp <(pvd_entries "$a/$f") <(pvd_entries "$b/$f")
    check "$label: $f has no time twice" test -z "$(pvd_entries "$b/$f" | cut -d' ' -f1 | sort | uniq -d)"
  done
  # The bubble series: the jet bubble and every bubble (ids, events and velocities continue across a restart);
  # the probes.
  for f in bubble.csv bubbles.csv bubble_events.csv bubble_frames.csv probes.csv; do
    [[ -e $a/$f || -e $b/$f ]] || continue
    check "$label: $f identical" cmp "$a/$f" "$b/$f"
  done
}

# Wait until a background run has started stepping (its log names the time range), at most 60 s.
wait_for_stepping() {  # wait_for_stepping OUT_DIR PID
  local k
  for ((k = 0; k < 600; ++k)); do
    grep -q ' to .* s$' "$1/log.txt" 2>/dev/null && return 0
    kill -0 "$2" 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}

# The checkpoint the log tells the user to restart from.
logged_checkpoint() {
  grep -o -- '--restart [^ ]*' "$1/log.txt" | tail -1 | cut -d' ' -f2
}
