# Shared helpers of the CLI tests: expect EXIT REGEX -- command...
FLUIDBED=${1:?fluidbed binary}
ROOT=${2:?repository root}
WORK=$(mktemp -d "${TMPDIR:-/tmp}/fluidbed-cli.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
PASS=0
FAIL=0

expect() {
  local want_rc=$1 regex=$2 name=$3
  shift 3
  local out rc
  out=$("$@" 2>&1)
  rc=$?
  if [[ $rc -eq $want_rc ]] && grep -Eq -- "$regex" <<<"$out"; then
    PASS=$((PASS + 1))
    printf '  ok    %-40s exit %d\n' "$name" "$rc"
  else
    FAIL=$((FAIL + 1))
    printf '  FAIL  %-40s exit %d (want %d, /%s/)\n%s\n' "$name" "$rc" "$want_rc" "$regex" "$out"
  fi
}

finish() {
  echo "$PASS passed, $FAIL failed"
  [[ $FAIL -eq 0 ]]
}
