#!/usr/bin/env bash
# The evaluation on real recordings (issue 12), one command: localises the two
# SLAM-corrected recordings of ../shared/data (Freiburg 079, Intel) with the
# SICK LMS 2xx preset and prints position RMSE, max, heading RMSE, lost time,
# the update's thread CPU time (median / p99 / max) and the mean CPU per scan
# with the work between scans, against the corrected poses, for
#   odometry  perfect (the corrected poses) and perturbed (1.5 % scale error,
#             0.3 deg/m heading drift, 5 mm and 0.1 deg noise per sqrt(m));
#   maps      shipped  maps/real/NAME.xml, built from the whole recording;
#             grid of all  imported from a 5 cm grid ray-cast from the whole
#                      recording (`map grid`, then `map import --grid`);
#             built    built from one part, localised on another (Freiburg:
#                      built from scans 719-4790, localised on 0-718; Intel:
#                      built from 182-909, localised on 0-181);
#             grid     imported from a 5 cm grid ray-cast from that same part.
# Pictures of map, scans and trajectories go to OUT_DIR (one PNG per row).
# The same bars are checked by ctest (tests/real_data/tracking_real_logs_test.cpp, label shared_data).
#
# Usage: tests/evaluation/real_recordings.sh [OUT_DIR] [BUILD_DIR] [DATA_DIR]
#        (defaults: real_evaluation, build, ../shared/data)
set -euo pipefail
# shellcheck source=tests/evaluation/recordings_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/recordings_common.sh"
recordings_setup real_evaluation "$@"

# row NAME PART ODOMETRY MAP_KIND MAP LOG TRUTH
row() {
  local report
  report=$("$structloc" replay --map "$5" --log "$6" --truth "$7" --params "$params" \
    --initial-pose "$(first_pose "$7")" --out "$out/$1_$2_$3_${4// /_}.tum" \
    --plot "$out/$1_$2_$3_${4// /_}.png" --timings 2>&1)
  local error lost update all
  error=$(sed -n 's/^estimate vs truth: position RMSE \([0-9.]*\) mm, max \([0-9.]*\) mm, heading RMSE \([0-9.]*\) deg.*/\1 | \2 | \3/p' <<<"$report")
  lost=$(sed -n 's/^lost: .*the longest \([0-9.]*\) s).*/\1/p' <<<"$report")
  # The update's thread CPU time (median / p99 / max), and the mean CPU per
  # scan with the work between scans (visibility ahead, search slices).
  update=$(awk '/update \(thread CPU\)/ { print $4 " / " $5 " / " $6 }' <<<"$report")
  all=$(awk '/scan \+ between \(CPU\)/ { print $8 }' <<<"$report")
  printf '| %s | %s | %s | %s | %s | %s | %s | %s |\n' "$1" "$2" "$4" "$3" "$error" "$lost" \
    "$update" "$all"
}

echo "| recording | scans localised | map | odometry | RMSE mm | max mm | heading RMSE deg | longest lost s | update us (median / p99 / max) | CPU per scan, mean us |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for name in freiburg_079 intel; do
  log="$data/${name//_/-}-corrected.log.gz"
  restamp=()
  if [ "$name" = intel ]; then
    restamp=(--restamp 0.5)
    map_part=182: test_part=0:182
  else
    map_part=719: test_part=0:719
  fi
  "$structloc" map grid --log "$log" --out "$out/${name}_grid_all.yaml" >/dev/null
  "$structloc" map import --grid "$out/${name}_grid_all.yaml" --out "$out/${name}_grid_all.xml" >/dev/null
  "$structloc" map build --log "$log" --scans "$map_part" --out "$out/${name}_built.xml" --quiet >/dev/null
  "$structloc" map grid --log "$log" --scans "$map_part" --out "$out/${name}_grid.yaml" >/dev/null
  "$structloc" map import --grid "$out/${name}_grid.yaml" --out "$out/${name}_grid.xml" >/dev/null
  for odometry in perfect perturbed; do
    errors=()
    [ "$odometry" = perturbed ] &&
      errors=("${odometry_errors[@]}")
    for part in all "$test_part"; do
      tag="$name.$odometry.${part/:/-}"
      scans=()
      [ "$part" != all ] && scans=(--scans "$part")
      "$structloc" synthesise-odometry --log "$log" --out "$out/$tag.log" --truth "$out/$tag.tum" \
        "${errors[@]}" "${restamp[@]}" "${scans[@]}" >/dev/null
    done
    row "$name" all "$odometry" shipped "$root/maps/real/$name.xml" \
      "$out/$name.$odometry.all.log" "$out/$name.$odometry.all.tum"
    row "$name" all "$odometry" "grid of all" "$out/${name}_grid_all.xml" \
      "$out/$name.$odometry.all.log" "$out/$name.$odometry.all.tum"
    for kind in built grid; do
      row "$name" "$test_part" "$odometry" "$kind" "$out/${name}_$kind.xml" \
        "$out/$name.$odometry.${test_part/:/-}.log" "$out/$name.$odometry.${test_part/:/-}.tum"
    done
  done
done
