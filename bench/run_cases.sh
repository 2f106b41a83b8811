#!/usr/bin/env bash
# Whole-case benchmarks: wall time per simulated second, particle-steps per second and peak memory, the median of
# RUNS runs with THREADS OpenMP threads, read from each run's cost.json and /usr/bin/time -v.
# Usage: bash bench/run_cases.sh [BUILD_DIR] [RUNS] [THREADS] [END_TIME_S]
#   settle-22k  cases/bench/settle-22k.toml, the whole simulated second (DEM only)
#   gera1998    cases/gera1998/dem.toml up to END_TIME_S (default 1 s, the paper's case); the settled bed is cached
#               by a first, untimed run
#   tfm         cases/gera1998/tfm.toml up to END_TIME_S
# Writes the table to stdout and to bench/log.<date>.cases.<compiler>.<threads>.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
build="${1:-$root/build}"
runs="${2:-3}"
threads="${3:-$(nproc)}"
end_time="${4:-1.0}"
fluidbed="$build/fluidbed"
[ -x "$fluidbed" ] || { echo "no $fluidbed: build first (make build)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "/usr/bin/time (Debian package time) is needed for the peak memory" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# name|case file|extra arguments
cases=("settle-22k|$root/cases/bench/settle-22k.toml|--set dem.max_overlap_fraction=0.5 --set output.interval=100"
       "gera1998-dem|$root/cases/gera1998/dem.toml|--end-time $end_time")
[ -f "$root/cases/gera1998/tfm.toml" ] && cases+=("gera1998-tfm|$root/cases/gera1998/tfm.toml|--end-time $end_time")

# The paper's DEM case settles its bed once and caches it: do that outside the timed runs.
"$fluidbed" run "$root/cases/gera1998/dem.toml" --out "$work/warmup" --end-time 0.002 --threads "$threads" --quiet \
  --set dem.max_overlap_fraction=0.5

results="$work/results.txt"
: > "$results"
for entry in "${cases[@]}"; do
  IFS='|' read -r name file extra <<< "$entry"
  for r in $(seq 1 "$runs"); do
    out="$work/$name-$r"
    # A case that fails (e.g. a model still being wired) is reported and skipped, not fatal to the others.
    # shellcheck disable=SC2086
    if ! /usr/bin/time -v -o "$out.time" "$fluidbed" run "$file" --out "$out" --threads "$threads" --quiet $extra \
        2> "$out.err"; then
      echo "$name: run $r failed: $(tail -n 1 "$out.err")" >&2
      break
    fi
    rss_kb="$(awk -F': ' '/Maximum resident set size/ {print $2}' "$out.time")"
    cpu_s="$(awk -F': ' '/User time|System time/ {s += $2} END {print s}' "$out.time")"
    echo "$name $r $rss_kb $cpu_s $(tr -d '\n' < "$out/cost.json")" >> "$results"
  done
done

compiler="$(c++ -v 2>&1 | grep -q '^gcc version' && echo g++ || echo clang++)"
log="$here/log.$(date -u +%d%b%y).cases.$compiler.$threads"
python3 - "$results" "$threads" "$runs" <<'PY' | tee "$log"
import json, statistics, subprocess, sys
rows = {}
for line in open(sys.argv[1]):
    name, run, rss_kb, cpu_s, cost = line.split(" ", 4)
    rows.setdefault(name, []).append((int(rss_kb), json.loads(cost), float(cpu_s)))
load = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
print(f"# fluidbed whole-case benchmarks, {sys.argv[3]} runs each, {sys.argv[2]} threads; {load}")
print("| case | particles | cells | DEM steps | simulated s | loop wall s (median) | wall s per simulated s | particle-steps/s | process CPU s (median) | peak RSS MB | runs (loop wall s) |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for name, rs in rows.items():
    walls = [c["wall_s"] for _, c, _ in rs]
    c = rs[0][1]
    w = statistics.median(walls)
    rss = statistics.median([r for r, _, _ in rs]) / 1024.0
    cpu = statistics.median([x for _, _, x in rs])
    ps = c["particles"] * c["time_steps"] / w if c["particles"] else float("nan")
    print(f"| {name} | {c['particles']} | {c['cells']} | {c['time_steps']} | {c['simulated_s']:.4g} | {w:.3f} | "
          f"{w / c['simulated_s']:.3f} | {ps:.3g} | {cpu:.2f} | {rss:.1f} | {', '.join(f'{x:.2f}' for x in walls)} |")
PY
echo "log: $log"
