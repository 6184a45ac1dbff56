#!/usr/bin/env bash
# Runs one libFuzzer target for RUNS executions on a copy of its seed corpus
# (our own shipped files), in a temporary folder removed afterwards, even on
# failure (under STRUCTLOC_FUZZ_WORK_DIR, else TMPDIR or /tmp; ctest points it
# into the build tree, where only a run killed outright, as by ctest's time
# limit, leaves its folder behind). Exit 0 when no input crashed it, tripped a sanitizer, hung (10 s)
# or went over 2 GB; otherwise libFuzzer's exit code, with the input it saved
# and how to reproduce it (72 when it was interrupted, which is no finding).
# With STRUCTLOC_FUZZ_CORPUS_DIR set, the corpus is that folder's
# subfolder named after the fuzzer, kept afterwards: a long run split into
# legs (on a slow target, or across machines) goes on from where the last leg
# left its corpus instead of from the seeds.
# Usage: tests/fuzz/run_fuzzer.sh FUZZER RUNS SEED_FILE...
set -euo pipefail
fuzzer="$1" runs="$2"
shift 2
work="$(mktemp -d "${STRUCTLOC_FUZZ_WORK_DIR:-${TMPDIR:-/tmp}}/structloc-fuzz.XXXXXX")"
trap 'rm -rf "$work"' EXIT
name="$(basename "$fuzzer")"
corpus="$work/corpus"
[ -n "${STRUCTLOC_FUZZ_CORPUS_DIR:-}" ] && corpus="$STRUCTLOC_FUZZ_CORPUS_DIR/$name"
mkdir -p "$corpus" "$work/tmp" "$work/findings"
for seed in "$@"; do
  [ -f "$seed" ] && cp "$seed" "$corpus/$(basename "$(dirname "$seed")")_$(basename "$seed")"
done
echo "$name: corpus $corpus, $(find "$corpus" -type f | wc -l) inputs at the start"
status=0
TMPDIR="$work/tmp" "$fuzzer" -runs="$runs" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
  -print_final_stats=1 -artifact_prefix="$work/findings/" "$corpus" >"$work/log" 2>&1 || status=$?
executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log")
coverage=$(grep -o 'cov: [0-9]*' "$work/log" | tail -1 | cut -d' ' -f2)
if [ "$status" -eq 72 ]; then  # libFuzzer's exit code when SIGINT or SIGTERM stopped it
  echo "$name: interrupted after ${executions:-?} executions (not a finding)"
  exit "$status"
fi
if [ "$status" -ne 0 ]; then
  echo "$name: FINDING after ${executions:-?} executions (exit $status)"
  tail -60 "$work/log"
  for f in "$work/findings"/*; do
    [ -f "$f" ] || continue
    echo "input ($f), as base64 (reproduce: base64 -d > input; $fuzzer input):"
    base64 "$f" | head -40
  done
  exit "$status"
fi
echo "$name: ${executions:-?} executions, ${coverage:-?} coverage edges, no finding"
