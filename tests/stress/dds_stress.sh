#!/usr/bin/env bash
# The stress run of the flaky-test issue: the DDS tests and the whole suite
# again and again, also with both cores kept busy by two other processes and
# with thousands of ephemeral UDP ports held by another process. Prints one
# line per run and a summary; exits non-zero if any run failed.
#
#   tests/stress/dds_stress.sh [BUILD_DIR] [RUNS]      (defaults: build, 10)
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="$(cd "${1:-$here/../../build}" && pwd)"
runs="${2:-10}"
jobs="$(nproc 2>/dev/null || echo 2)"
failures=0
hogs=()
stop_hogs() {
  for pid in "${hogs[@]}"; do kill "$pid" 2>/dev/null; done
  hogs=()
}
trap stop_hogs EXIT

run() {  # run LABEL COMMAND...: one line with the outcome and the time taken
  local label="$1"; shift
  local start end
  start=$(date +%s)
  if "$@" > "$build/stress_last.log" 2>&1; then
    end=$(date +%s); echo "  $label: passed ($((end - start)) s)"
  else
    end=$(date +%s); echo "  $label: FAILED ($((end - start)) s), log: $build/stress_last_failure.log"
    cp "$build/stress_last.log" "$build/stress_last_failure.log"
    failures=$((failures + 1))
  fi
}

cd "$build" || exit 2
echo "1. DDS tests, ctest -j$jobs --repeat until-fail:$runs"
run "dds x$runs" ctest -L dds -j "$jobs" --timeout 600 --repeat "until-fail:$runs"
echo "2. the whole suite $runs times in a row"
for i in $(seq 1 "$runs"); do run "suite $i" ctest -j "$jobs" --timeout 600; done
echo "3. DDS tests $runs times while two other processes keep both cores busy"
for _ in 1 2; do (while :; do :; done) & hogs+=($!); done
for i in $(seq 1 "$runs"); do run "dds busy $i" ctest -L dds -j "$jobs" --timeout 600; done
stop_hogs
echo "4. DDS tests $runs times while another process holds 14000 ephemeral UDP ports"
for i in $(seq 1 "$runs"); do
  run "dds ports $i" "$here/ephemeral_port_pressure.py" --sockets 14000 -- \
    ctest -L dds -j "$jobs" --timeout 600
done
echo "stress: $failures failed run(s)"
[ "$failures" -eq 0 ]
