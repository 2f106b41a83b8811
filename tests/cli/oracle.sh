#!/usr/bin/env bash
# The paper's cases, a 3D CFD-DEM and a 3D TFM case against the frozen outputs of tests/oracle/gera1998 (the
# regression oracle of issue 12; the 3D entries of issue 28):
# bubble.csv and monitor.csv (without wall_s) must be identical, byte for byte. A change meant to move them
# regenerates the oracle with tests/oracle/regenerate.sh and says in its commit what moved, by how much and why.
source "$(dirname "$0")/lib.sh"
source "$ROOT/tests/oracle/cases.sh"
for name in "${ORACLE_CASES[@]}"; do
  expect 0 "" "run $name" oracle_run "$FLUIDBED" "$ROOT" "$name" "$WORK/$name"
  for f in bubble.csv monitor.csv; do
    oracle_strip "$WORK/$name/$f" > "$WORK/$name.$f"
    expect 0 "" "$name $f equals the oracle" diff -q "$ROOT/tests/oracle/gera1998/$name.$f" "$WORK/$name.$f"
  done
done
finish
