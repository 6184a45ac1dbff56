#!/usr/bin/env bash
# The decision run for a change to SLAM (issue 41): Freiburg 079 and Intel,
# each as a raw log with the real-recording table's synthesised odometry
# errors (as slam_recordings.sh makes them), mapped in halves (Freiburg scans
# 0:2400 and 2400:4791, Intel 0:455 and 455:910), each half's path judged by
# its RMSE against the corrected poses after one rigid alignment, and their
# mean. A change is judged on these parts, by a rule written before the run
# (the maps guide says which rules were used), and the whole logs and MIT
# (slam_recordings.sh) are run afterwards for the record: choosing on the
# figures they report would tune to them.
#
# Usage: tests/evaluation/slam_halves.sh [SLAM_PARAMS.xml] [OUT_DIR] [BUILD_DIR] [DATA_DIR]
#        (defaults: the built-in SLAM options, slam_halves, build, ../shared/data)
set -euo pipefail
slam_params="${1:-}"
[ $# -gt 0 ] && shift
# shellcheck source=tests/evaluation/recordings_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/recordings_common.sh"
recordings_setup slam_halves "$@"
options=()
[ -n "$slam_params" ] && options=(--slam-params "$slam_params")

echo "| half | scans | aligned RMSE mm | aligned max mm |"
echo "|---|---|---|---|"
sum=0
for name in freiburg_079 intel; do
  synthesise_raw_log "$name"
  halves="0:2400 2400:4791"
  [ "$name" = intel ] && halves="0:455 455:910"
  for half in $halves; do
    slam=$("$structloc" slam --log "$out/$name.raw.log" --truth "$out/$name.truth.tum" \
      --poses-out "$out/$name.${half%%:*}.slam.tum" --scans "$half" "${options[@]}")
    aligned=$(sed -n 's/^  slam .*aligned: RMSE \([0-9.]*\) mm, max \([0-9.]*\) mm.*/\1 \2/p' <<<"$slam")
    read -r rmse max <<<"$aligned"
    printf '| %s | %s | %s | %s |\n' "$name" "$half" "$rmse" "$max"
    sed -n 's/^  \(scan latency .*\)/  (\1)/p' <<<"$slam"
    sum=$(awk -v a="$sum" -v b="$rmse" 'BEGIN { print a + b }')
  done
done
awk -v s="$sum" 'BEGIN { printf "mean aligned RMSE of the four halves: %.1f mm\n", s / 4 }'
