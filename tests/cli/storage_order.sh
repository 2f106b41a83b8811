#!/usr/bin/env bash
# Results do not depend on how the particles were stored when the run began (issue 11, item 5): a case run on a
# fresh machine (it settles its bed, writes the settle cache, then runs) equals the same case run again (it reads
# the cached bed) bit for bit, and a particle CSV with its rows shuffled gives the same run as the CSV in order.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"

# 300 particles placed at random, settled in vacuum, then fluidised by the background inflow and a jet.
write_cfd_case "$WORK/settle.toml" settle 'settle.max_time = 0.3' 'settle.kinetic_energy_per_particle = 1e-9' \
  "settle.cache = \"$WORK/cache/settled.csv\""
sed -i -e '/^settle.enabled = false$/d' -e 's/^particles.count = 200$/particles.count = 300/' "$WORK/settle.toml"

run_ok "first run: settles and writes the cache" run "$WORK/settle.toml" --out "$WORK/first"
check "the first run settled the bed" grep -q 'settled in vacuum' "$WORK/first/log.txt"
check "the settle cache was written" test -s "$WORK/cache/settled.csv"
run_ok "rerun: reads the cached bed" run "$WORK/settle.toml" --out "$WORK/rerun"
check "the rerun reused the cache" grep -q 'reusing the settled bed' "$WORK/rerun/log.txt"
same_results "first run vs rerun" "$WORK/first" "$WORK/rerun"

# The settled bed as a particle CSV, once in id order and once with its rows shuffled (a fixed permutation).
head -1 "$WORK/first/settled.csv" >"$WORK/shuffled.csv"
tail -n +2 "$WORK/first/settled.csv" | awk 'BEGIN { srand(11) } { printf "%.12f,%s\n", rand(), $0 }' | sort -t, -k1,1 |
  cut -d, -f2- >>"$WORK/shuffled.csv"
check "the shuffled CSV holds the same rows in another order" \
  bash -c "test -s '$WORK/shuffled.csv' && ! cmp -s '$WORK/first/settled.csv' '$WORK/shuffled.csv' && cmp <(sort '$WORK/first/settled.csv') <(sort '$WORK/shuffled.csv')"
for v in first/settled shuffled; do
  name=${v//\//-}
  run_ok "particles from $v.csv" run "$WORK/settle.toml" --out "$WORK/file-$name" \
    --set particles.source=file --set particles.file="$WORK/$v.csv"
done
same_results "CSV in id order vs shuffled" "$WORK/file-first-settled" "$WORK/file-shuffled"

# Ids are the canonical order: a CSV that gives one id twice is bad input, for `check` as for `run`.
{ cat "$WORK/shuffled.csv"; sed -n 2p "$WORK/shuffled.csv"; } >"$WORK/twice.csv"
expect 2 "duplicate id [0-9]+" "check: an id given twice" \
  "$FLUIDBED" check "$WORK/settle.toml" --set particles.source=file --set particles.file="$WORK/twice.csv"

finish
