#!/usr/bin/env bash
# Cost per particle-step against N: the settle-22k bed and its widened copies (cases/bench/scale-*.toml: 100,000,
# 300,000 and 1,000,000 particles at the same area fraction), each 250 steps of 2e-4 s from the random placement.
# Usage: bash bench/scaling.sh [BUILD_DIR] [THREADS] [RUNS]
# Prints, per N, the median loop wall time, ns per particle-step (wall and whole-process CPU), peak RSS and
# bytes per particle; the marginal memory (RSS difference between the two largest beds over their N difference)
# is the per-particle cost without the program's fixed footprint. Writes bench/log.<date>.scaling.<compiler>.<threads>.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
build="${1:-$root/build}"
threads="${2:-$(nproc)}"
runs="${3:-3}"
fluidbed="$build/fluidbed"
[ -x "$fluidbed" ] || { echo "no $fluidbed: build first (make build)" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
results="$work/results.txt"
: > "$results"
# Each bed runs 250 steps and, to take out the fixed costs (placement, first frame, final checkpoint), 1 step:
# the CPU time of the 249 extra steps over N x 249 is the CPU cost per particle-step, which a loaded shared
# machine does not distort the way it distorts wall times.
for name in settle-22k scale-100k scale-300k scale-1m; do
  for r in $(seq 1 "$runs"); do
    for end in 0.05 0.0002; do
      out="$work/$name-$r-$end"
      /usr/bin/time -f "%e %U %S %M" -o "$out.time" "$fluidbed" run "$root/cases/bench/$name.toml" --out "$out" \
        --end-time "$end" --threads "$threads" --quiet --set dem.max_overlap_fraction=0.5 --set output.interval=100
      echo "$name $end $(cat "$out.time") $(tr -d '\n' < "$out/cost.json")" >> "$results"
      rm -rf "$out"
    done
  done
done
compiler="$(c++ -v 2>&1 | grep -q '^gcc version' && echo g++ || echo clang++)"
log="$here/log.$(date -u +%d%b%y).scaling.$compiler.$threads"
python3 - "$results" "$threads" "$runs" <<'PY' | tee "$log"
import json, statistics, subprocess, sys
rows = {}
for line in open(sys.argv[1]):
    name, end, wall, user, sys_s, rss_kb, cost = line.split(" ", 6)
    rows.setdefault(name, {}).setdefault(end, []).append((float(user) + float(sys_s), int(rss_kb), json.loads(cost)))
load = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
print(f"# cost per particle-step against N, 250 steps from the random placement, {sys.argv[2]} threads, median of {sys.argv[3]}; {load}")
print("| N | steps | loop wall s | ns per particle-step (loop wall) | ns CPU per particle-step (250 - 1 step runs) | peak RSS MB | RSS bytes per particle |")
print("|---|---|---|---|---|---|---|")
table = []
for name, ends in rows.items():
    full, one = ends["0.05"], ends["0.0002"]
    c = full[0][2]
    n, steps = c["particles"], c["time_steps"]
    w = statistics.median([x[2]["wall_s"] for x in full])
    cpu = statistics.median([x[0] for x in full]) - statistics.median([x[0] for x in one])
    rss = statistics.median([x[1] for x in full]) * 1024.0
    table.append((n, rss))
    print(f"| {n} | {steps} | {w:.3f} | {1e9 * w / (n * steps):.1f} | {1e9 * cpu / (n * (steps - 1)):.1f} | {rss / 2**20:.1f} | {rss / n:.0f} |")
if len(table) >= 2:
    (n1, r1), (n2, r2) = sorted(table)[-2:]
    print(f"\nmarginal memory: {(r2 - r1) / (n2 - n1):.0f} bytes per particle (between N = {n1} and {n2})")
PY
echo "log: $log"
