#!/usr/bin/env bash
# `fluidbed ensemble` (issue 15, item 6): N members of one case differing only in case.seed, J at a time, each a
# plain run folder, listed in ensemble.json; the members' packings differ (so do their results); `fluidbed report`
# of the ensemble folder shows Table 2 as mean +- std over the members and the bands figure. A bad case is exit 2
# before any member starts. The small CFD-DEM bed of the reliability tests, 0.04 s (a few seconds on one core).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

write_cfd_case "$WORK/e.toml" ens
sed -i 's/^case.end_time = 0.02$/case.end_time = 0.04/' "$WORK/e.toml"
run_ok "ensemble: 3 members, 2 at a time" ensemble "$WORK/e.toml" -n 3 --jobs 2 --out "$WORK/ens" \
  --set output.particles=false
check "ensemble: ensemble.json lists seeds 7, 8, 9, all exit 0" /usr/bin/python3 - "$WORK/ens/ensemble.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))["members"]
assert [(x["folder"], x["seed"], x["exit"]) for x in m] == [("seed-7", 7, 0), ("seed-8", 8, 0), ("seed-9", 9, 0)], m
PY
for s in 7 8 9; do
  check "ensemble: seed-$s ran with case.seed = $s" grep -qx "seed = $s" "$WORK/ens/seed-$s/case.toml"
done
check "ensemble: the packings differ (particle frames at t = 0)" bash -c \
  "! cmp -s '$WORK/ens/seed-7/particles/000000.csv' '$WORK/ens/seed-8/particles/000000.csv'"
check "ensemble: a member equals a plain run of its seed" bash -c \
  "'$FLUIDBED' run '$WORK/e.toml' --out '$WORK/plain8' --threads 1 --quiet --set case.seed=8 --set output.particles=false &&
   cmp <(monitor_without_wall '$WORK/plain8/monitor.csv') <(monitor_without_wall '$WORK/ens/seed-8/monitor.csv')"
expect 0 "report written" "ensemble: report of the ensemble folder" "$FLUIDBED" report "$WORK/ens" --out "$WORK/rep"
check "ensemble: summary.md has Table 2 as mean +- std over 3 members" \
  grep -q "^\*\*ens\*\*: 3 members" "$WORK/rep/summary.md"
check "ensemble: ensemble_bands.png written" test -s "$WORK/rep/figures/ensemble_bands.png"
expect 2 "case.seed|unknown key|nonsense" "ensemble: a bad case is refused before any member starts" \
  "$FLUIDBED" ensemble "$WORK/e.toml" -n 2 --out "$WORK/bad" --set nonsense.key=1
check "ensemble: the refused ensemble started no member" test ! -e "$WORK/bad/seed-7"
finish
