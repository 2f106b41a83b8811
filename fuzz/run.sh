#!/usr/bin/env bash
# Build and run the case-loader fuzzer: fuzz/run.sh [SECONDS] [extra libFuzzer options...] (default 600 s).
# Builds with clang++ into build-fuzz/ (sources of src/ with coverage, ASan and UBSan; toml++ header-only so that
# its parser is instrumented too), then fuzzes from a copy of fuzz/corpus/ with the key dictionary.
# Findings (crash-*, timeout-*, oom-*) land in build-fuzz/findings/; reproduce one with
#   build-fuzz/fuzz_case_loader build-fuzz/findings/crash-...
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SECONDS_TO_RUN=${1:-600}
shift || true
BUILD=${FLUIDBED_FUZZ_BUILD:-$ROOT/build-fuzz}
JOBS=${JOBS:-2}
CXX=${CXX:-clang++}
mkdir -p "$BUILD/obj" "$BUILD/findings" "$BUILD/corpus" "$BUILD/work"

CXXFLAGS=(-std=c++20 -O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined
  -fno-sanitize-recover=all -fopenmp -I"$ROOT/src" -isystem /usr/include/eigen3 -isystem /usr/include/hdf5/serial
  -DSPDLOG_COMPILED_LIB -DSPDLOG_FMT_EXTERNAL -DTOML_HEADER_ONLY=1 "-DTOML_ASSERT(expr)=((void)0)")
# toml++ 3.3.0 asserts a precondition in parse_key() that input such as "[\n" violates (fixed upstream,
# marzer/tomlplusplus#301); the parser then reports a normal syntax error, as the release library does. Its
# debug assertions are off here so that the fuzzer looks past that known finding.
# Objects are rebuilt when these flags change.
if [[ "$(cat "$BUILD/flags" 2>/dev/null)" != "${CXXFLAGS[*]}" ]]; then
  rm -f "$BUILD"/obj/*.o
  echo "${CXXFLAGS[*]}" >"$BUILD/flags"
fi

# Compile what changed (the object depends on its source only; `rm -rf build-fuzz` after header edits).
compile() {
  local src=$1 obj=$2
  if [[ ! -e $obj || $src -nt $obj ]]; then
    echo "  compile ${src#"$ROOT"/}"
    if ! "$CXX" "${CXXFLAGS[@]}" -c "$src" -o "$obj" 2>"$obj.log"; then
      # clang 14 lacks some C++20 (structured bindings captured by lambdas): such a file is compiled with g++,
      # uninstrumented. Fine for code the loader never runs (the gas solver); listed so it is not forgotten.
      echo "  WARNING: $CXX cannot compile ${src#"$ROOT"/} ($(grep -m1 'error:' "$obj.log")); using g++, uninstrumented"
      g++ -std=c++20 -O1 -g -fopenmp -I"$ROOT/src" -isystem /usr/include/eigen3 -isystem /usr/include/hdf5/serial \
        -DSPDLOG_COMPILED_LIB -DSPDLOG_FMT_EXTERNAL -DTOML_HEADER_ONLY=1 -c "$src" -o "$obj"
    fi
  fi
}
export -f compile
export CXX ROOT
export CXXFLAGS_STR="${CXXFLAGS[*]}"
mapfile -t sources < <(cd "$ROOT" && find src -name '*.cpp' | sort)
for s in "${sources[@]}"; do
  printf '%s\n%s\n' "$ROOT/$s" "$BUILD/obj/$(echo "${s%.cpp}" | tr / _).o"
done | xargs -d '\n' -n 2 -P "$JOBS" bash -c 'CXXFLAGS=($CXXFLAGS_STR); compile "$0" "$1"'
compile "$ROOT/fuzz/fuzz_case_loader.cpp" "$BUILD/obj/fuzz_case_loader.o"
rm -f "$BUILD/libfluidbed_fuzz.a"
ar rcs "$BUILD/libfluidbed_fuzz.a" $(for s in "${sources[@]}"; do echo "$BUILD/obj/$(echo "${s%.cpp}" | tr / _).o"; done)
"$CXX" -fsanitize=fuzzer,address,undefined -fopenmp "$BUILD/obj/fuzz_case_loader.o" "$BUILD/libfluidbed_fuzz.a" \
  -L/usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5 -lspdlog -lfmt -lz -lpthread -o "$BUILD/fuzz_case_loader"
echo "built $BUILD/fuzz_case_loader"

cp -n "$ROOT"/fuzz/corpus/* "$BUILD/corpus/" 2>/dev/null || true
# Run in an empty folder: a fuzzed case may name a particle file, which is then looked up there.
cd "$BUILD/work"
exec "$BUILD/fuzz_case_loader" "$BUILD/corpus" -dict="$ROOT/fuzz/case_keys.dict" -max_total_time="$SECONDS_TO_RUN" \
  -timeout=10 -rss_limit_mb=2048 -max_len=4096 -artifact_prefix="$BUILD/findings/" -print_final_stats=1 "$@"
