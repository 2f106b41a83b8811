#!/usr/bin/env bash
# A/B of two fluidbed binaries on the DEM kernel (docs/performance.md section 18), old and new alternating so that
# the drift of a shared machine hits both alike:
#   settle   cases/bench/settle-22k.toml (DEM only, 5000 steps), THREADS threads
#   paper    cases/gera1998/dem.toml to 0.3 s, THREADS threads, the cached settled bed (not timed); the figure is
#            the loop wall time between the monitor rows at 0.1 and 0.3 s
# Every run also reports its process CPU time (user + sys), the figure to compare on a loaded machine.
# Usage: bash bench/ab_dem.sh OLD_BINARY NEW_BINARY [PAIRS=3] [THREADS=2] [EXTRA --set ARGS...]
# (env: CASES="settle paper" to choose). Each binary runs the case files of this tree.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
old="$1" new="$2" pairs="${3:-3}" threads="${4:-2}"
shift $(($# < 4 ? $# : 4))
extra=("$@")
cases="${CASES:-settle paper}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for which in old new; do  # each binary its own settled-bed cache
  bin="$old"; [ "$which" = new ] && bin="$new"
  case " $cases " in *" paper "*)
    "$bin" run "$root/cases/gera1998/dem.toml" --end-time 0.001 --set "settle.cache=$work/cache-$which.csv" \
      --out "$work/warm" --overwrite --quiet >/dev/null ;;
  esac
done
# loop wall between the monitor rows at 0.1 and 0.3 s (time_s is the first column, wall_s the last)
window() { awk -F, 'NR > 1 && a == "" && $1 >= 0.1 - 1e-9 { a = $NF } { b = $NF } END { printf "%.2f", b - a }' "$1"; }
: >"$work/results"
for name in $cases; do
  for p in $(seq 1 "$pairs"); do
    for which in old new; do
      bin="$old"; [ "$which" = new ] && bin="$new"
      if [ "$name" = settle ]; then
        args=("$root/cases/bench/settle-22k.toml")
      else
        args=("$root/cases/gera1998/dem.toml" --end-time 0.3 --set "settle.cache=$work/cache-$which.csv")
      fi
      at="$(date -u +%H:%M:%S)"
      /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$bin" run "${args[@]}" "${extra[@]}" --threads "$threads" \
        --out "$work/run" --overwrite --quiet >/dev/null
      read -r wall user sys rss <"$work/time"
      cpu="$(awk "BEGIN { printf \"%.2f\", $user + $sys }")"
      if [ "$name" = settle ]; then fig="$(tail -1 "$work/run/monitor.csv" | awk -F, '{print $NF}')"; else fig="$(window "$work/run/monitor.csv")"; fi
      echo "$name $which $at loop $fig cpu $cpu rss_kB $rss load $(cut -d' ' -f1 /proc/loadavg)" | tee -a "$work/results"
    done
  done
done
/usr/bin/python3 - "$work/results" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
for name in dict.fromkeys(r[0] for r in rows):
    med = {}
    for which in ("old", "new"):
        sel = [r for r in rows if r[0] == name and r[1] == which]
        med[which] = (statistics.median(float(r[4]) for r in sel), statistics.median(float(r[6]) for r in sel))
        print(f"{name} {which} median loop {med[which][0]:.2f} s, cpu {med[which][1]:.2f} s ({len(sel)} runs)")
    print(f"{name} new/old loop {med['new'][0] / med['old'][0]:.3f}, cpu {med['new'][1] / med['old'][1]:.3f}")
PY
