#!/usr/bin/env bash
# No function in src/ over 120 lines (issue 28, item 3), counted by universal-ctags from its first to its last line.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"
check "universal-ctags is installed (make deps)" bash -c "ctags --version | grep -q 'Universal Ctags'"
lengths=$(cd "$ROOT" && ctags -R --languages=C++ --kinds-C++=f --fields=+ne --output-format=u-ctags -f - src |
  awk -F'\t' '{b = ""; e = ""; for (i = 4; i <= NF; i++) { if ($i ~ /^line:/) b = substr($i, 6); if ($i ~ /^end:/) e = substr($i, 5) }
               if (b != "" && e != "") print $2 ":" $1 "\t" e - b + 1}')
check "ctags counted the functions of src/" test "$(wc -l <<<"$lengths")" -gt 500
over=""
while IFS=$'\t' read -r fn n; do
  if (( n > 120 )); then over+="$fn: $n lines; "; fi
done <<<"$lengths"
[[ -z $over ]] || echo "  longer than allowed: $over"
check "no function of src/ is longer than 120 lines" test -z "$over"
finish
