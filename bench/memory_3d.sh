#!/usr/bin/env bash
# Bytes a particle of the 3D settling bed (cases/bench/settle-100k-3d.toml) at a given step, fluidbed beside LAMMPS:
# the marginal resident memory between N and 2N spheres, the 2N bed in a box twice as deep (the same height and
# packing, so both beds fall and settle alike; bench/peer_lammps_3d.sh doubles the height, which leaves its 2N bed
# still falling when the N bed has settled). STEPS = 2000 (the benchmark's whole run) measures the settled bed with
# its contacts; STEPS = 10 the placement, nearly without contacts (the figure bench/peer_lammps_3d.sh reports).
# One core each. Figures a particle, (X_2N - X_N) / N:
#   peak      /usr/bin/time's maximum resident set (fluidbed: the final checkpoint included);
#   stepping  fluidbed only: the largest VmRSS sampled every 10 ms before the final checkpoint is begun.
# Usage: bash bench/memory_3d.sh [BUILD_DIR] [STEPS] [RUNS]   (env: LAMMPS=0 leaves LAMMPS out)
# Writes bench/log.<date>.memory-3d-<STEPS>.<cc>.1
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
build="${1:-$root/build}"
steps="${2:-2000}"
runs="${3:-1}"
with_lammps="${LAMMPS:-1}"
fluidbed="$build/fluidbed"
[ -x "$fluidbed" ] || { echo "no $fluidbed: build first (make build)" >&2; exit 2; }
source "$here/lammps/ensure_lammps.sh"
[ "$with_lammps" != 1 ] || ensure_lammps
export OMP_NUM_THREADS=1
n=100000
width=0.3 height=0.6 depth=0.08 diameter=0.004 skin=0.002 dt=2e-4
depth2="$(python3 -c "print(2 * $depth)")"
mkdir -p "$root/out/bench"
bed="$root/out/bench/memory-3d"
python3 "$here/lammps/place3d.py" --count "$n" --width "$width" --height "$height" --depth "$depth" \
  --diameter "$diameter" --csv "$bed-n.csv" --data "$bed-n.data" >&2
python3 "$here/lammps/place3d.py" --count "$((2 * n))" --width "$width" --height "$height" --depth "$depth2" \
  --diameter "$diameter" --csv "$bed-2n.csv" --data "$bed-2n.data" >&2
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
end_time="$(python3 -c "print($steps * $dt)")"
results="$work/results.txt"
source "$here/rss_plateau.sh"
: > "$results"

# fb NAME CSV DEPTH: one fluidbed run; appends "fluidbed NAME peak_kB stepping_kB"
fb() {
  local name=$1 csv=$2 d=$3 out="$work/out" plateau
  rm -rf "$out"
  /usr/bin/time -f "%M" -o "$work/time" "$fluidbed" run "$root/cases/bench/settle-100k-3d.toml" --out "$out" \
    --end-time "$end_time" --threads 1 --quiet --set "dem.skin=$skin" --set output.particles=false \
    --set particles.source=file --set "particles.file=$csv" --set "domain.depth=$d" &
  local pid=$!
  plateau="$(rss_plateau "$pid" "$out")"
  wait "$pid"
  echo "fluidbed $name $(cat "$work/time") $plateau" >> "$results"
}
# lm NAME DATA DEPTH: one LAMMPS run; appends "lammps NAME peak_kB 0"
lm() {
  (cd "$work" && /usr/bin/time -f "%M" -o "$work/time" lmp -in "$here/lammps/settle-100k-3d.in" -var data "$2" \
    -var steps "$steps" -var skin "$skin" -var depth "$3" -log none -screen none)
  echo "lammps $1 $(cat "$work/time") 0" >> "$results"
}
for r in $(seq 1 "$runs"); do
  fb n "$bed-n.csv" "$depth"
  fb 2n "$bed-2n.csv" "$depth2"
  if [ "$with_lammps" = 1 ]; then
    lm n "$bed-n.data" "$depth"
    lm 2n "$bed-2n.data" "$depth2"
  fi
done

compiler="$(c++ -v 2>&1 | grep -q '^gcc version' && echo g++ || echo clang++)"
log="$here/log.$(date -u +%d%b%y).memory-3d-$steps.$compiler.1"
python3 - "$results" "$n" "$steps" "$fluidbed" <<'PY' | tee "$log"
import statistics, subprocess, sys
rows = {}
for line in open(sys.argv[1]):
    code, name, peak, step = line.split()
    rows.setdefault((code, name), []).append((float(peak), float(step)))
n, steps = int(sys.argv[2]), int(sys.argv[3])
ver = subprocess.run([sys.argv[4], "--version"], capture_output=True, text=True).stdout.strip()
print(f"# 3D settle, bytes a particle at step {steps}: (RSS(2N) - RSS(N)) / N, N = {n}, the 2N bed twice as deep;"
      f" medians of {len(rows[('fluidbed', 'n')])} runs; {sys.argv[4]} ({ver})")
for code in ("fluidbed", "lammps"):
    if (code, "n") not in rows:
        continue
    med = {name: (statistics.median(p for p, _ in rows[(code, name)]),
                  statistics.median(s for _, s in rows[(code, name)])) for name in ("n", "2n")}
    peak = (med["2n"][0] - med["n"][0]) * 1024 / n
    line = f"{code:9s} peak_kB {med['n'][0]:.0f} {med['2n'][0]:.0f}  bytes_a_particle_peak {peak:.0f}"
    if code == "fluidbed":
        line += f"  stepping_kB {med['n'][1]:.0f} {med['2n'][1]:.0f}  bytes_a_particle_stepping {(med['2n'][1] - med['n'][1]) * 1024 / n:.0f}"
    print(line)
PY
