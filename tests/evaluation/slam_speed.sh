#!/usr/bin/env bash
# How long `structloc slam` takes on a 5000-scan recording that loops all the
# time (issue 41: 5000 scans in 2 minutes on our 2 cores). The hall patrol
# (maps/scenarios/hall_patrol.xml: laps around a pillar with a 1081-beam laser,
# people and boxes) is simulated offline and mapped; prints the wall-clock and
# CPU time, SLAM's own count, and its path against the truth after one rigid
# alignment. Freiburg 079 (4791 scans, 360 beams, fewer revisits) is timed by
# slam_recordings.sh.
#
# Usage: tests/evaluation/slam_speed.sh [OUT_DIR] [BUILD_DIR] [THREADS]
#        (defaults: slam_speed, build, the <run threads> default)
set -euo pipefail
# shellcheck source=tests/evaluation/recordings_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/recordings_common.sh"
recordings_setup slam_speed "${@:1:2}"
threads_params=()
if [ -n "${3:-}" ]; then
  printf '<?xml version="1.0"?>\n<slam_params base="defaults">\n  <run threads="%s"/>\n</slam_params>\n' \
    "$3" >"$out/threads.xml"
  threads_params=(--slam-params "$out/threads.xml")
fi
"$structloc" simulate --scenario "$root/maps/scenarios/hall_patrol.xml" --out "$out/patrol" >/dev/null
/usr/bin/time -f '%e %U %S %M' -o "$out/time.txt" "$structloc" slam --log "$out/patrol/run.clf" \
  --truth "$out/patrol/truth.tum" --poses-out "$out/patrol.slam.tum" "${threads_params[@]}" \
  >"$out/slam.txt"
read -r wall user system memory <"$out/time.txt"
echo "hall patrol: $(grep -c '^ROBOTLASER1 ' "$out/patrol/run.clf") scans"
echo "wall-clock ${wall} s, CPU ${user} s user + ${system} s system, ${memory} KB at most"
grep '^structloc slam:' "$out/slam.txt"
sed -n 's/^  slam .*aligned: RMSE \([0-9.]*\) mm, max \([0-9.]*\) mm.*/SLAM path against the truth, aligned: RMSE \1 mm, max \2 mm/p' "$out/slam.txt"
