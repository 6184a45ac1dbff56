#!/usr/bin/env bash
# The long fuzzing run (issue 16): builds the libFuzzer targets with clang in
# BUILD_DIR (default build-fuzz) and runs every one (or those whose ctest name
# matches REGEX, e.g. 'grid|dxf') for RUNS executions (default 1000000) on its
# seed corpus, two at a time, the slowest first, printing one line per target
# as it finishes (executions, coverage) and exiting non-zero when any target
# found something (its input is printed for reproduction). A target's time
# limit grows with RUNS (tests/fuzz/CMakeLists.txt).
# With STRUCTLOC_FUZZ_CORPUS_DIR=DIR each target's corpus is kept in
# DIR/<target> and the next run goes on from it (tests/fuzz/run_fuzzer.sh).
# Usage: tests/fuzz/fuzz_all.sh [BUILD_DIR] [RUNS] [REGEX]
set -euo pipefail
[ -n "${STRUCTLOC_FUZZ_CORPUS_DIR:-}" ] &&
  export STRUCTLOC_FUZZ_CORPUS_DIR="$(realpath -m "$STRUCTLOC_FUZZ_CORPUS_DIR")"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${1:-$root/build-fuzz}"
runs="${2:-1000000}"
only="${3:-.}"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DSTRUCTLOC_FUZZ=ON -DBUILD_TESTING=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTRUCTLOC_FUZZ_RUNS="$runs" >/dev/null
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)" --target structloc_fuzzers
start=$(date +%s)
log="$build/fuzz_all.log"
set +o pipefail
ctest --test-dir "$build" -L fuzz -R "$only" -j 2 --output-on-failure -V 2>&1 | tee "$log" |
  { grep --line-buffered -E ": [0-9?]+ executions|inputs at the start|FINDING|interrupted|Timeout|tests passed," || true; } |
  sed -u 's/^[0-9]*: //'
status=${PIPESTATUS[0]}
set -o pipefail
echo "fuzz_all: $runs executions per target, $(( $(date +%s) - start )) s in all (log: $log)"
exit "$status"
