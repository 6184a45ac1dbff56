#!/usr/bin/env bash
# The long fuzzing run (issue 16): builds the libFuzzer targets with clang in
# BUILD_DIR (default build-fuzz) and runs every one for RUNS executions
# (default 1000000) on its seed corpus, two at a time, printing one line per
# target (executions, coverage, time) and exiting non-zero when any target
# found something (its input is printed for reproduction).
# Usage: tests/fuzz/fuzz_all.sh [BUILD_DIR] [RUNS]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${1:-$root/build-fuzz}"
runs="${2:-1000000}"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DSTRUCTLOC_FUZZ=ON -DBUILD_TESTING=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTRUCTLOC_FUZZ_RUNS="$runs" >/dev/null
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)" --target structloc_fuzzers
start=$(date +%s)
log="$build/fuzz_all.log"
status=0
ctest --test-dir "$build" -L fuzz -j 2 --timeout 0 --output-on-failure -V >"$log" 2>&1 || status=$?
grep -E ": [0-9?]+ executions|FINDING" "$log" | sed 's/^[0-9]*: //' || true
echo "fuzz_all: $runs executions per target, $(( $(date +%s) - start )) s in all (log: $log)"
exit "$status"
