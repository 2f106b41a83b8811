#!/usr/bin/env bash
# docs/case-format.md lists exactly the keys the program reads (the part after the marker is `fluidbed keys`),
# and every case under cases/ passes `fluidbed check`.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"
sed -n '/<!-- fluidbed keys -->/,$p' "$ROOT/docs/case-format.md" | tail -n +2 > "$WORK/doc.md"
"$FLUIDBED" keys > "$WORK/keys.md"
expect 0 "" "docs/case-format.md matches fluidbed keys" diff "$WORK/doc.md" "$WORK/keys.md"
for c in "$ROOT"/cases/*/*.toml; do
  expect 0 "OK" "check ${c#$ROOT/}" "$FLUIDBED" check "$c"
done
# The cell arrays a CFD-DEM frame holds are the ones docs/output-format.md gives a CFD-DEM run (issue 27, item 17:
# solids_velocity was written but documented for two-fluid runs only).
cat > "$WORK/frame.toml" <<'TOML'
case.name = "frame"
case.end_time = 0.002
particles.count = 30
settle.enabled = false
dem.time_step = 1e-4
output.interval = 0.001
output.checkpoint_interval = 0.0
TOML
expect 0 "" "a CFD-DEM run writes frames" "$FLUIDBED" run "$WORK/frame.toml" --quiet --out "$WORK/frame"
arrays=$(grep -ao '<DataArray[^>]*Name="[a-z_]*"' "$WORK/frame/fields/000001.vti" | sed 's/.*Name="//; s/"//' | grep -v TimeValue)
paragraph=$(sed -n '/^### fields\/NNNNNN.vti/,/^### /p' "$ROOT/docs/output-format.md")
for a in $arrays; do
  check "docs/output-format.md gives the CFD-DEM frame array $a" \
    bash -c "grep -q '\`$a\`' <<<\"\$1\" && { [[ $a != solids_velocity ]] || grep -q 'in a CFD-DEM run the volume-weighted mean velocity' <<<\"\$1\"; }" _ "$paragraph"
done
finish
