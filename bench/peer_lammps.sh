#!/usr/bin/env bash
# Side by side on one core: fluidbed's DEM-only settling of the paper's 22,000-particle bed
# (cases/bench/settle-22k.toml) against the same bed in LAMMPS (bench/lammps/settle-22k.in, gran/hooke/history),
# both starting from fluidbed's random placement, both 5000 steps of 2e-4 s with the same skin.
# Usage: bash bench/peer_lammps.sh [BUILD_DIR] [STEPS] [SKIN_M]
# Prints both loop wall times and their ratio; writes bench/log.<date>.settle-22k.<compiler>.1 (LAMMPS naming).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
build="${1:-$root/build}"
steps="${2:-5000}"
skin="${3:-0.002}"
fluidbed="$build/fluidbed"
case_file="$root/cases/bench/settle-22k.toml"
[ -x "$fluidbed" ] || { echo "no $fluidbed: build first (make build)" >&2; exit 2; }
source "$here/lammps/ensure_lammps.sh"
ensure_lammps

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
dt=2e-4
end_time="$(python3 -c "print($steps * $dt)")"
# Particles land on the floor at up to 4.4 m/s, overlapping by up to 0.37 d with k = 800 N/m: the run-time
# overlap guard (10% of d by default) is a safety check of fluidized runs, not of this drop test.
sets=(--set dem.max_overlap_fraction=0.5 --set "dem.skin=$skin" --set output.interval=100 --set output.monitor_interval=0.1)

# fluidbed's placement (seed 1998) as the LAMMPS data file.
"$fluidbed" run "$case_file" --out "$work/init" --end-time "$dt" --threads 1 --quiet "${sets[@]}" \
  --set output.particles_csv=true
python3 "$here/lammps/csv_to_data.py" "$work/init/particles/000000.csv" "$work/settle-22k.data" 0.6 1.0 0.004

export OMP_NUM_THREADS=1
/usr/bin/time -f "%e %U" -o "$work/fluidbed.time" \
  "$fluidbed" run "$case_file" --out "$work/fluidbed" --end-time "$end_time" --threads 1 --quiet "${sets[@]}"
fb_wall="$(python3 -c "import json; print(json.load(open('$work/fluidbed/cost.json'))['wall_s'])")"
fb_rebuilds="$(python3 -c "
import csv; r = list(csv.DictReader(open('$work/fluidbed/monitor.csv'))); print(r[-1]['neighbor_rebuilds'])")"

(cd "$work" && /usr/bin/time -f "%e %U" -o "$work/lammps.time" lmp -in "$here/lammps/settle-22k.in" -var data "$work/settle-22k.data" -var steps "$steps" \
  -var skin "$skin" -log "$work/lammps.log" -screen none)
lmp_wall="$(awk '/^Loop time of/ {print $4}' "$work/lammps.log")"
lmp_rebuilds="$(awk '/^Neighbor list builds/ {print $5}' "$work/lammps.log")"

compiler="$(c++ -v 2>&1 | grep -q '^gcc version' && echo g++ || echo clang++)"
log="$here/log.$(date -u +%d%b%y).settle-22k.$compiler.1"
{
  echo "# settle-22k side by side, $(date -u +%Y-%m-%dT%H:%M:%SZ), $(uname -n), $(nproc --all) cores, load: $(uptime | sed 's/.*load average: //')"
  echo "# $steps steps of $dt s, 22000 particles, skin $skin m, 1 thread / 1 MPI rank each"
  echo "# LAMMPS: $(head -1 "$work/lammps.log")"
  printf "fluidbed_loop_wall_s %s\nfluidbed_neighbor_rebuilds %s\n" "$fb_wall" "$fb_rebuilds"
  printf "lammps_loop_wall_s %s\nlammps_neighbor_rebuilds %s\n" "$lmp_wall" "$lmp_rebuilds"
  printf "fluidbed_process_wall_s_and_cpu_s %s\nlammps_process_wall_s_and_cpu_s %s\n" "$(cat "$work/fluidbed.time")" "$(cat "$work/lammps.time")"
  python3 -c "
fb, lm = $fb_wall, $lmp_wall
fb_cpu, lm_cpu = $(awk '{print $2}' "$work/fluidbed.time"), $(awk '{print $2}' "$work/lammps.time")
print(f'lammps_over_fluidbed {lm / fb:.3f}  (loop wall times)')
print(f'lammps_over_fluidbed_cpu {lm_cpu / fb_cpu:.3f}  (whole-process CPU times: robust on a shared machine)')
print(f'fluidbed_particle_steps_per_s {22000 * $steps / fb:.4g}')
print(f'lammps_particle_steps_per_s {22000 * $steps / lm:.4g}')"
  echo "# LAMMPS timing breakdown:"
  sed -n '/^Section |/,/^Total wall/p' "$work/lammps.log" | sed 's/^/#   /'
} | tee "$log"
echo "log: $log"
