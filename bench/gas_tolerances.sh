#!/usr/bin/env bash
# Gas solver cost on the paper's DEM case over 0.1-0.3 s (docs/performance.md, "Gas solver tolerances"):
# CPU time of the whole run and of the gas solver per gas step (perf samples every 1 ms of task-clock in the gas
# solver's and Eigen's symbols, not the interpolation to particles) and SIMPLE iterations per gas step
# (monitor.csv, every 10th step), for 1 and 2 threads, REPS runs each restarted from one 0.1 s checkpoint.
# Usage: bench/gas_tolerances.sh FLUIDBED [WORKDIR] [REPS] [extra --set options...]
set -euo pipefail
bin=$(realpath "$1"); work=${2:-/tmp/gasbench}; reps=${3:-3}; shift $(( $# < 3 ? $# : 3 )) || true
case_file=$(realpath "$(dirname "$0")/../cases/gera1998/dem.toml")
mkdir -p "$work"
if [ ! -f "$work/base/checkpoints/final.h5" ]; then
  "$bin" run "$case_file" --end-time 0.1 --threads 2 --out "$work/base" --quiet --overwrite "$@"
fi
for th in 1 2; do
  for r in $(seq "$reps"); do
    d="$work/run-t$th-$r"; rm -rf "$d"; cp -r "$work/base" "$d"
    perf record -q -e task-clock -c 1000000 -o "$d/perf.data" -- "$bin" run "$case_file" --restart latest --allow-changed gas --end-time 0.3 \
      --threads "$th" --out "$d" --quiet "$@" >/dev/null 2>&1
    perf report -i "$d/perf.data" --stdio --sort sym 2>/dev/null > "$d/perf.txt"
    /usr/bin/python3 - "$d" "$th" <<'PY'
import csv, re, sys
d, th = sys.argv[1], sys.argv[2]
gas_re = re.compile(r"GasSolver<\d>::(Impl|advance)|Eigen::|StencilMatrix|CheckedSparse|StructuredSolver|"
                    r"fill_\w*ghosts|fix_wall|fill_wall|inlet_superficial|load_cells|cells_to_faces|high_order_correction")
totals, gas, event = {}, {}, None
for line in open(f"{d}/perf.txt"):
    m = re.match(r"# Samples: (\S+)\s+of event '([^']+)'", line)
    if m:
        event = m.group(2); totals[event] = 0.0; gas[event] = 0.0
        continue
    m = re.match(r"\s+([0-9.]+)%\s+\[\.\]\s+(.*)", line)
    if m and event:
        totals[event] += float(m.group(1))
        if gas_re.search(m.group(2)): gas[event] += float(m.group(1))
def count(ev):  # the event's total in ms (task-clock counts ns)
    lines = open(f"{d}/perf.txt").read().split(f"of event '{ev}'")[1]
    return float(re.search(r"# Event count \(approx\.\): (\d+)", lines).group(1)) * 1e-6
rows = [r for r in csv.DictReader(open(f"{d}/monitor.csv")) if float(r["time_s"]) > 0.1 + 1e-9]
it = sum(int(r["simple_iterations"]) for r in rows) / len(rows)
steps = 1000  # gas steps of 2e-4 s in 0.2 s
tc = "task-clock"
cpu = count(tc) * 1e-3
print(f"threads {th} cpu_s {cpu:.2f} gas_cpu_ms_per_step {count(tc) * gas[tc] / totals[tc] / steps:.3f} "
      f"simple_iterations {it:.2f}")
PY
  done
done
