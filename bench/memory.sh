#!/usr/bin/env bash
# Bytes per particle: the marginal resident memory between two bed sizes (the program's fixed footprint drops out).
# 2D: cases/bench/scale-100k.toml and scale-300k.toml; 3D: settle-100k-3d.toml at 100,000 and, three times as deep,
# 300,000 spheres. Each bed runs STEPS steps of 2e-4 s from the random placement, 2 threads, fields off.
# Three figures per bed (median of RUNS):
#   peak            /usr/bin/time %M of the run with its first particle frame (.vtu) and the final checkpoint;
#   peak, no frame  the same with output.particles = false (then the peak is the stepping or the checkpoint);
#   stepping        the largest VmRSS sampled every 10 ms after the first frame is on disk and before the final
#                   checkpoint appears (the plateau of the time loop).
# Usage: bash bench/memory.sh [BUILD_DIR] [RUNS] [STEPS]; prints a table and writes bench/log.<date>.memory.<cc>.2
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
build="${1:-$root/build}"
runs="${2:-3}"
steps="${3:-25}"
fluidbed="$build/fluidbed"
[ -x "$fluidbed" ] || { echo "no $fluidbed: build first" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
results="$work/results.txt"
source "$here/rss_plateau.sh"
: > "$results"
end=$(python3 -c "print($steps * 2e-4)")

# run NAME CASE VARIANT [--set ...]: one run, appends "NAME VARIANT peak_kB plateau_kB"
run() {
  local name=$1 case=$2 variant=$3; shift 3
  local out="$work/out"
  rm -rf "$out"
  /usr/bin/time -f "%M" -o "$work/time" "$fluidbed" run "$case" --out "$out" --end-time "$end" --threads 2 --quiet \
    --set output.fields=false --set output.interval=100 --set dem.max_overlap_fraction=0.5 "$@" &
  local pid=$! frames=1 plateau
  [ "$variant" != noframe ] || frames=0
  plateau="$(rss_plateau "$pid" "$out" "$frames")"
  wait "$pid"
  echo "$name $variant $(cat "$work/time") $plateau" >> "$results"
}

for r in $(seq 1 "$runs"); do
  run 2d-100000 "$root/cases/bench/scale-100k.toml" frame
  run 2d-300000 "$root/cases/bench/scale-300k.toml" frame
  run 2d-100000 "$root/cases/bench/scale-100k.toml" noframe --set output.particles=false
  run 2d-300000 "$root/cases/bench/scale-300k.toml" noframe --set output.particles=false
  run 3d-100000 "$root/cases/bench/settle-100k-3d.toml" frame
  run 3d-300000 "$root/cases/bench/settle-100k-3d.toml" frame --set particles.count=300000 --set domain.depth=0.24
done

compiler="$(c++ -v 2>&1 | grep -q '^gcc version' && echo g++ || echo clang++)"
log="$here/log.$(date -u +%d%b%y).memory.$compiler.2"
python3 - "$results" "$runs" "$steps" "$fluidbed" <<'PY' | tee "$log"
import statistics, subprocess, sys
rows = {}
for line in open(sys.argv[1]):
    name, variant, peak, plateau = line.split()
    rows.setdefault((name, variant), []).append((int(peak) * 1024, int(plateau) * 1024))
med = {k: (statistics.median(p for p, _ in v), statistics.median(q for _, q in v)) for k, v in rows.items()}
load = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
print(f"# {sys.argv[4]}: {sys.argv[3]} steps, 2 threads, median of {sys.argv[2]}; {load}")
print("| bed | peak MB (100k / 300k) | peak B/particle (marginal) | stepping MB (100k / 300k) | stepping B/particle (marginal) |")
print("|---|---|---|---|---|")
for dim, variant, label in (("2d", "frame", "2D, with the frame"), ("2d", "noframe", "2D, output.particles = false"),
                            ("3d", "frame", "3D, with the frame")):
    a, b = med.get((f"{dim}-100000", variant)), med.get((f"{dim}-300000", variant))
    if not a or not b:
        continue
    print(f"| {label} | {a[0] / 2**20:.1f} / {b[0] / 2**20:.1f} | {(b[0] - a[0]) / 200000:.0f} | "
          f"{a[1] / 2**20:.1f} / {b[1] / 2**20:.1f} | {(b[1] - a[1]) / 200000:.0f} |")
PY
echo "log: $log"
