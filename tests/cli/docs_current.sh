#!/usr/bin/env bash
# docs/case-format.md lists exactly the keys the program reads (the part after the marker is `fluidbed keys`),
# and every case under cases/ passes `fluidbed check`.
source "$(dirname "$0")/lib.sh"
sed -n '/<!-- fluidbed keys -->/,$p' "$ROOT/docs/case-format.md" | tail -n +2 > "$WORK/doc.md"
"$FLUIDBED" keys > "$WORK/keys.md"
expect 0 "" "docs/case-format.md matches fluidbed keys" diff "$WORK/doc.md" "$WORK/keys.md"
for c in "$ROOT"/cases/*/*.toml; do
  expect 0 "OK" "check ${c#$ROOT/}" "$FLUIDBED" check "$c"
done
finish
