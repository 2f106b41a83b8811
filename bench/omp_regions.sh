#!/usr/bin/env bash
# The OpenMP parallel regions of a gas step of the paper's CFD-DEM case (issue 31 item 4, docs/performance.md
# section 34): how many a gas step opens, where (the outlined function, named by nm), how many an `if` clause ran on
# one thread, and the wall time inside them; the rest of the wall time is what ran on the main thread alone.
# Two runs from the cached settled bed, to FROM and to TO; their difference is the window, free of start-up.
# Usage: bash bench/omp_regions.sh BINARY CACHE.csv [THREADS=2] [FROM=0.1] [TO=0.3]   (needs cc and nm)
set -euo pipefail
bin="$1" cache="$2" threads="${3:-2}" from="${4:-0.1}" to="${5:-0.3}"
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cc -O2 -shared -fPIC -o "$work/shim.so" "$root/bench/omp_regions.c" -ldl -lpthread
case_file="$root/cases/gera1998/dem.toml"
gas_dt="$("$bin" check "$case_file" | awk '$1 == "gas" && $2 == "time" { print $4 }')"
for end in "$from" "$to"; do
  OMP_REGIONS_OUT="$work/regions.$end" LD_PRELOAD="$work/shim.so" "$bin" run "$case_file" --end-time "$end" \
    --set "settle.cache=$cache" --threads "$threads" --out "$work/run" --overwrite --quiet >/dev/null
done
nm -C --defined-only "$bin" | awk '{ addr = $1; $1 = ""; $2 = ""; sub(/^  /, ""); print addr "\t" $0 }' >"$work/symbols"
echo "$(basename "$bin"), $threads threads, window $from-$to s, gas step $gas_dt s, $(date -u +%H:%M:%S) UTC"
python3 - "$work/regions.$from" "$work/regions.$to" "$work/symbols" "$from" "$to" "$gas_dt" "$threads" \
  "$root/bench" <<'PY'
import re, sys
sys.path.insert(0, sys.argv[8])
from profile_split import without_templates
a_path, b_path, sym_path, t0, t1, dt, threads = sys.argv[1:8]
def load(path):
    wall, rows = 0.0, {}
    for line in open(path):
        f = line.split()
        if f[0] == "wall_s":
            wall = float(f[1])
        else:
            rows[int(f[0], 16)] = [int(x) for x in f[1:4]] + [float(x) for x in f[4:7]]
    return wall, rows
wa, ra = load(a_path)
wb, rb = load(b_path)
names = {}
for line in open(sym_path):
    addr, _, name = line.rstrip("\n").partition("\t")
    names[int(addr, 16)] = name
steps = (float(t1) - float(t0)) / float(dt)
def short(name):
    # the enclosing function of an outlined body, without its template arguments and parameters
    name = without_templates(re.sub(r" \[clone \._omp_fn\.(\d+)\]$", r" #\1", name))
    name = re.sub(r"\([^()]*\)", "", name).replace("fluidbed::", "").replace("::operator const", "")
    return re.sub(r"^(void|double|auto|int) ", "", name)
rows = []
for fn, now in rb.items():
    was = ra.get(fn, [0, 0, 0, 0.0, 0.0, 0.0])
    d = [x - y for x, y in zip(now, was)]
    if d[0] > 0:
        rows.append((d[3] + d[5], d, short(names.get(fn, hex(fn)))))
rows.sort(key=lambda r: -r[0])
team = int(threads)
ms = lambda s: 1e3 * s / steps
print(f"{'on a team':>9} {'use':>5} {'alone':>6} | {'regions':>7} {'1-thread':>8} {'nested':>6}  "
      "(ms or count a gas step) outlined body of")
par = busy = alone = 0.0
for _, d, name in rows:
    calls, single, nested, sec, b, al = d
    par, busy, alone = par + sec, busy + b, alone + al
    use = f"{b / (team * sec):5.2f}" if sec > 0 else f"{'':5}"
    print(f"{ms(sec):9.3f} {use} {ms(al):6.3f} | {calls / steps:7.2f} {single / steps:8.2f} {nested / steps:6.2f}  {name}")
wall = wb - wa
n = sum(r[1][0] for r in rows) / steps
n1 = sum(r[1][1] for r in rows) / steps
nn = sum(r[1][2] for r in rows) / steps
print(f"{ms(par):9.3f} {busy / (team * par):5.2f} {ms(alone):6.3f} | {n:7.2f} {n1:8.2f} {nn:6.2f}  all regions")
print(f"wall {ms(wall):.3f} ms a gas step ({steps:.0f} steps): on a team {ms(par):.3f} ({par / wall:.1%}, the team "
      f"busy {busy / (team * par):.1%} of it), on the main thread alone {ms(wall - par):.3f} ({(wall - par) / wall:.1%}; "
      f"{ms(alone):.3f} of it in regions on one thread)")
PY
