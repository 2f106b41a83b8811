#!/usr/bin/env bash
# Side by side on one core, in 3D: fluidbed's DEM-only settling of 100,000 spheres (cases/bench/settle-100k-3d.toml)
# against the same bed in LAMMPS (bench/lammps/settle-100k-3d.in, gran/hooke/history), both from one random
# placement (bench/lammps/place3d.py, seed 1998), both STEPS steps of 2e-4 s with the same skin, REPEATS times
# each, alternating; the medians are reported. Then bytes per particle: the peak RSS of a short run of N and of 2N
# spheres (the same packing in a box twice as tall), difference over N, for both codes.
# Usage: bash bench/peer_lammps_3d.sh [BUILD_DIR] [STEPS] [SKIN_M]     (env: REPEATS=3, LAMMPS_ONLY=1)
# Writes bench/log.<date>.settle-100k-3d.<compiler>.1 (LAMMPS naming) and keeps the LAMMPS logs beside it
# (bench/log.<date>.settle-100k-3d.lammps.<n>).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
build="${1:-$root/build}"
steps="${2:-2000}"
skin="${3:-0.002}"
repeats="${REPEATS:-3}"
lammps_only="${LAMMPS_ONLY:-0}"
fluidbed="$build/fluidbed"
case_file="$root/cases/bench/settle-100k-3d.toml"
n=100000
width=0.3 height=0.6 depth=0.08 diameter=0.004
dt=2e-4
export OMP_NUM_THREADS=1

if [ "$lammps_only" != 1 ]; then
  [ -x "$fluidbed" ] || { echo "no $fluidbed: build first (make build)" >&2; exit 2; }
fi
source "$here/lammps/ensure_lammps.sh"
ensure_lammps

# The placements: N spheres in the benchmark box, read by both codes, and 2N in a box twice as tall at the same
# packing, for the memory measurement.
mkdir -p "$root/out/bench"
bed="$root/out/bench/settle-100k-3d"
python3 "$here/lammps/place3d.py" --count "$n" --width "$width" --height "$height" --depth "$depth" \
  --diameter "$diameter" --csv "$bed.csv" --data "$bed.data" >&2
height2="$(python3 -c "print(2 * $height)")"
python3 "$here/lammps/place3d.py" --count "$((2 * n))" --width "$width" --height "$height2" --depth "$depth" \
  --diameter "$diameter" --csv "$bed-2n.csv" --data "$bed-2n.data" >&2

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
end_time="$(python3 -c "print($steps * $dt)")"
common=(--set "dem.skin=$skin" --set output.interval=100 --set output.monitor_interval=0.01 --set output.particles=false
        --set particles.source=file)
sets=("${common[@]}" --set "particles.file=$bed.csv")
sets_2n=("${common[@]}" --set "particles.file=$bed-2n.csv" --set "domain.height=$height2")

if [ "$lammps_only" != 1 ]; then
  # A fluidbed from before issue 12's 3D DEM refuses case.dimension = 3 (or the 3-component gravity): say so plainly.
  if ! check_out="$("$fluidbed" check "$case_file" "${sets[@]}" 2>&1)"; then
    echo "peer_lammps_3d.sh: $fluidbed refuses the 3D case $case_file, so it has no 3D DEM yet" >&2
    echo "(issue 12: case.dimension = 3). Its message:" >&2
    echo "$check_out" | sed 's/^/  /' >&2
    echo "Build a fluidbed with 3D DEM, or run LAMMPS alone: LAMMPS_ONLY=1 bash bench/peer_lammps_3d.sh" >&2
    exit 3
  fi
fi

median() { python3 -c "import statistics, sys; print(statistics.median(float(v) for v in sys.argv[1:]))" "$@"; }
fb_wall=() fb_cpu=() lm_wall=() lm_cpu=() fb_rebuilds="" lm_rebuilds="" fb_at=() lm_at=() fb_ke="" lm_ke=""
for r in $(seq 1 "$repeats"); do
  if [ "$lammps_only" != 1 ]; then
    fb_at+=("$(date -u +%H:%M:%S)")
    /usr/bin/time -f "%e %U %S" -o "$work/fluidbed.$r.time" \
      "$fluidbed" run "$case_file" --out "$work/fluidbed.$r" --end-time "$end_time" --threads 1 --quiet "${sets[@]}"
    fb_wall+=("$(python3 -c "import json; print(json.load(open('$work/fluidbed.$r/cost.json'))['wall_s'])")")
    fb_cpu+=("$(awk '{print $2 + $3}' "$work/fluidbed.$r.time")")
    fb_rebuilds="$(python3 -c "
import csv; r = list(csv.DictReader(open('$work/fluidbed.$r/monitor.csv'))); print(r[-1].get('neighbor_rebuilds', 'n/a'))")"
    fb_ke="$(python3 -c "
import csv; r = list(csv.DictReader(open('$work/fluidbed.$r/monitor.csv'))); print(r[-1]['time_s'], r[-1]['kinetic_energy_J'])")"
  fi
  lm_at+=("$(date -u +%H:%M:%S)")
  (cd "$work" && /usr/bin/time -f "%e %U %S" -o "$work/lammps.$r.time" lmp -in "$here/lammps/settle-100k-3d.in" \
    -var data "$bed.data" -var steps "$steps" -var skin "$skin" -log "$work/lammps.$r.log" -screen none)
  lm_wall+=("$(awk '/^Loop time of/ {print $4}' "$work/lammps.$r.log")")
  lm_cpu+=("$(awk '{print $2 + $3}' "$work/lammps.$r.time")")
  # Translational plus rotational kinetic energy of the last thermo line (step ke c_rke).
  lm_ke="$(awk '/^ *Step/ {on = 1; next} /^Loop time/ {on = 0} on && NF == 4 {last = $1 " " ($3 + $4)} END {print last}' "$work/lammps.$r.log")"
  lm_rebuilds="$(awk '/^Neighbor list builds/ {print $5}' "$work/lammps.$r.log")"
  echo "repeat $r: fluidbed ${fb_wall[*]: -1} s loop, ${fb_cpu[*]: -1} s CPU; LAMMPS ${lm_wall[*]: -1} s loop, ${lm_cpu[*]: -1} s CPU; load $(uptime | sed 's/.*load average: //')" >&2
done

# Bytes per particle: peak RSS of 10 steps with N and with 2N spheres, (RSS_2N - RSS_N) / N.
peak_kb() {
  "/usr/bin/time" -v -o "$work/rss.time" "$@" >"$work/rss.out" 2>&1 || { echo "memory run failed: $*" >&2; cat "$work/rss.out" >&2; exit 4; }
  awk -F': ' '/Maximum resident set size/ {print $2}' "$work/rss.time"
}
short="$(python3 -c "print(10 * $dt)")"
lm_rss1="$(cd "$work" && peak_kb lmp -in "$here/lammps/settle-100k-3d.in" -var data "$bed.data" -var steps 10 -var skin "$skin" -log none -screen none)"
lm_rss2="$(cd "$work" && peak_kb lmp -in "$here/lammps/settle-100k-3d.in" -var data "$bed-2n.data" -var steps 10 -var skin "$skin" -log none -screen none)"
fb_rss1="" fb_rss2=""
if [ "$lammps_only" != 1 ]; then
  fb_rss1="$(peak_kb "$fluidbed" run "$case_file" --out "$work/rss1" --end-time "$short" --threads 1 --quiet "${sets[@]}")"
  fb_rss2="$(peak_kb "$fluidbed" run "$case_file" --out "$work/rss2" --end-time "$short" --threads 1 --quiet "${sets_2n[@]}")"
fi

compiler="$(c++ -v 2>&1 | grep -q '^gcc version' && echo g++ || echo clang++)"
tag=settle-100k-3d; [ "$lammps_only" != 1 ] || tag=settle-100k-3d-lammps-only
stem="$here/log.$(date -u +%d%b%y).$tag"
log="$stem.$compiler.1"
for r in $(seq 1 "$repeats"); do cp "$work/lammps.$r.log" "$stem.lammps.$r"; done
{
  echo "# settle-100k-3d side by side, $(date -u +%Y-%m-%dT%H:%M:%SZ), $(uname -n), $(nproc --all) cores, load: $(uptime | sed 's/.*load average: //')"
  echo "# $steps steps of $dt s, $n spheres in $width x $height x $depth m, skin $skin m, 1 thread / 1 MPI rank each, $repeats repeats (medians)"
  echo "# LAMMPS: $(head -1 "$work/lammps.1.log")$([ "$lammps_only" = 1 ] && echo ", LAMMPS only (LAMMPS_ONLY=1)")"
  if [ "$lammps_only" != 1 ]; then
    printf "fluidbed_loop_wall_s %s  (runs: %s; started %s UTC)\nfluidbed_cpu_s %s  (runs: %s; user + sys)\nfluidbed_neighbor_rebuilds %s\nfluidbed_final_time_s_kinetic_energy_J %s  (translation + rotation)\n" \
      "$(median "${fb_wall[@]}")" "${fb_wall[*]}" "${fb_at[*]}" "$(median "${fb_cpu[@]}")" "${fb_cpu[*]}" "$fb_rebuilds" "$fb_ke"
  fi
  printf "lammps_loop_wall_s %s  (runs: %s; started %s UTC)\nlammps_cpu_s %s  (runs: %s; user + sys)\nlammps_neighbor_rebuilds %s\nlammps_final_step_kinetic_energy_J %s  (ke + erotate/sphere)\n" \
    "$(median "${lm_wall[@]}")" "${lm_wall[*]}" "${lm_at[*]}" "$(median "${lm_cpu[@]}")" "${lm_cpu[*]}" "$lm_rebuilds" "$lm_ke"
  python3 - "$n" "$steps" "$(median "${lm_wall[@]}")" "$(median "${lm_cpu[@]}")" "$lm_rss1" "$lm_rss2" \
    "$([ "$lammps_only" != 1 ] && median "${fb_wall[@]}")" "$([ "$lammps_only" != 1 ] && median "${fb_cpu[@]}")" \
    "$fb_rss1" "$fb_rss2" <<'PY'
import sys
n, steps = int(sys.argv[1]), int(sys.argv[2])
lm, lm_cpu, lm_r1, lm_r2 = (float(v) for v in sys.argv[3:7])
fb, fb_cpu, fb_r1, fb_r2 = sys.argv[7:11]
print(f"lammps_particle_steps_per_s {n * steps / lm:.4g}  (loop wall)")
print(f"lammps_particle_steps_per_cpu_s {n * steps / lm_cpu:.4g}")
print(f"lammps_peak_rss_kb_N_2N {lm_r1:.0f} {lm_r2:.0f}")
print(f"lammps_bytes_per_particle {(lm_r2 - lm_r1) * 1024 / n:.0f}  (peak RSS difference, 2N - N, over N)")
if fb:
    fb, fb_cpu, fb_r1, fb_r2 = float(fb), float(fb_cpu), float(fb_r1), float(fb_r2)
    print(f"fluidbed_particle_steps_per_s {n * steps / fb:.4g}  (loop wall)")
    print(f"fluidbed_particle_steps_per_cpu_s {n * steps / fb_cpu:.4g}")
    print(f"lammps_over_fluidbed {lm / fb:.3f}  (loop wall times)")
    print(f"lammps_over_fluidbed_cpu {lm_cpu / fb_cpu:.3f}  (whole-process CPU times: robust on a shared machine)")
    print(f"fluidbed_peak_rss_kb_N_2N {fb_r1:.0f} {fb_r2:.0f}")
    print(f"fluidbed_bytes_per_particle {(fb_r2 - fb_r1) * 1024 / n:.0f}  (peak RSS difference, 2N - N, over N)")
PY
  echo "# LAMMPS timing breakdown (repeat 1):"
  sed -n '/^Section |/,/^Total wall/p' "$work/lammps.1.log" | sed 's/^/#   /'
} | tee "$log"
echo "log: $log; LAMMPS logs: $stem.lammps.*"
