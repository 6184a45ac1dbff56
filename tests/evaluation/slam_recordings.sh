#!/usr/bin/env bash
# The SLAM evaluation on real recordings (issue 41), one command:
#   MIT CSAIL (raw odometry): `structloc slam --relations`, Kuemmerle et al.
#             2009's relation metric, beside raw odometry;
#   Freiburg 079 and Intel: odometry re-synthesised from the corrected poses
#             with the real-recording errors (as real_recordings.sh: 1.5 %
#             scale error, 0.3 deg/m heading drift, 5 mm and 0.1 deg noise per
#             sqrt(m); Intel re-stamped at 0.5 m/s), `structloc slam --truth
#             --out` (the path against the corrected poses, as it is and after
#             one rigid alignment: the path has the frame of its first
#             odometry), then `structloc replay` of the same log on the map
#             slam built, against the corrected poses (the real-recording bars:
#             RMSE <= 50 mm, max <= 200 mm), also after an alignment that
#             scales the estimate (how much of the error is scale).
# The corrected poses are GMapping's, not ground truth: on these logs they
# are themselves off by centimetres. Then the same log localised on the map
# of maps/real/ (built on the corrected poses) too, and the three paths
# (that one, the one on the map slam built, the SLAM path) judged by
# relations over 1, 5 and 20 m of travel drawn from the corrected poses
# (structloc_relative_error): what a robot navigating by the map suffers,
# apart from the map's global shape. Last, how well the corrected poses and
# the SLAM path each fit the raw scans step by step, with no reference
# (structloc_path_scan_fit: scans 1-1.5 m and 0.1-0.3 m apart, the mean
# distance of one's points from the other's surfaces, and the scale of the
# path's steps the scans prefer) and where the robot passed a place again
# (structloc_revisit_fit: scans 10 m of travel or more apart that both paths
# put within 1 m and 30 deg, the same mean distance beside the least that
# relative poses near them give: a path bent at the scale of rooms fits there
# the worse), and how straight the map built on each is
# against the building's axes (structloc_map_straightness: the shipped map
# of maps/real/, built on the corrected poses, and the one slam built).
# Outputs (paths, maps, pictures) go to OUT_DIR.
#
# Usage: tests/evaluation/slam_recordings.sh [OUT_DIR] [BUILD_DIR] [DATA_DIR]
#        (defaults: slam_evaluation, build, ../shared/data); SLAM_PARAMS=FILE
#        in the environment maps every log with those SLAM options.
set -euo pipefail
# shellcheck source=tests/evaluation/recordings_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/recordings_common.sh"
recordings_setup slam_evaluation "$@"
slam_options=()
[ -n "${SLAM_PARAMS:-}" ] && slam_options=(--slam-params "$SLAM_PARAMS")

echo "MIT CSAIL, raw odometry:"
"$structloc" slam --log "$data/mit-csail.clf.gz" --relations "$data/mit-csail.relations" \
  --poses-out "$out/mit-csail.slam.tum" "${slam_options[@]}" |
  grep -E "structloc slam:|scan latency|relation errors|  (slam|odometry) "
echo
echo "| recording | SLAM path RMSE / max mm | aligned RMSE / max mm | localisation on its map: RMSE / max mm | aligned RMSE / max mm | aligned with scale: scale, RMSE / max mm | longest lost s | slam s |"
echo "|---|---|---|---|---|---|---|---|"
for name in freiburg_079 intel; do
  synthesise_raw_log "$name"
  log="$out/$name.raw.log"
  truth="$out/$name.truth.tum"
  slam=$("$structloc" slam --log "$log" --truth "$truth" --poses-out "$out/$name.slam.tum" \
    --out "$out/$name.slam.xml" --plot "$out/$name.slam.png" "${slam_options[@]}")
  path=$(sed -n 's/^  slam *RMSE \([0-9.]*\) mm, max \([0-9.]*\) mm.*aligned: RMSE \([0-9.]*\) mm, max \([0-9.]*\) mm.*/\1 \/ \2 | \3 \/ \4/p' <<<"$slam")
  seconds=$(sed -n 's/^structloc slam: [0-9]* scans in \([0-9.]*\) s.*/\1/p' <<<"$slam")
  report=$("$structloc" replay --map "$out/$name.slam.xml" --log "$log" --truth "$truth" \
    --params "$params" --initial-pose "$(first_pose "$truth")" --out "$out/$name.localised.tum" \
    --plot "$out/$name.localised.png" 2>&1)
  as_is=$(sed -n 's/^estimate vs truth: position RMSE \([0-9.]*\) mm, max \([0-9.]*\) mm.*/\1 \/ \2/p' <<<"$report")
  aligned=$(sed -n 's/^estimate vs truth after one rigid alignment: position RMSE \([0-9.]*\) mm, max \([0-9.]*\) mm.*/\1 \/ \2/p' <<<"$report")
  scaled=$(sed -n 's/^estimate vs truth after one alignment with scale (\([0-9.]*\)): position RMSE \([0-9.]*\) mm, max \([0-9.]*\) mm.*/\1, \2 \/ \3/p' <<<"$report")
  lost=$(sed -n 's/^lost: .*the longest \([0-9.]*\) s).*/\1/p' <<<"$report")
  printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$path" "$as_is" "$aligned" "$scaled" "$lost" "$seconds"
  # The same log on the map of maps/real/ (built on the corrected poses), for the relations below.
  if ! "$structloc" replay --map "$root/maps/real/$name.xml" --log "$log" --truth "$truth" \
    --params "$params" --initial-pose "$(first_pose "$truth")" \
    --out "$out/$name.shipped.tum" >"$out/$name.shipped.txt" 2>&1; then
    cat "$out/$name.shipped.txt" >&2
    exit 1
  fi
done
echo
echo "Relations over 1, 5 and 20 m of travel drawn from the corrected poses (structloc_relative_error):"
relative="$(dirname "$structloc")/../tests/structloc_relative_error"
for name in freiburg_079 intel; do
  for path in shipped localised slam; do
    case $path in
      shipped) echo "  $name, localised on the map built on the corrected poses (maps/real/):" ;;
      localised) echo "  $name, localised on the map slam built:" ;;
      slam) echo "  $name, the SLAM path:" ;;
    esac
    "$relative" "$out/$name.$path.tum" "$out/$name.truth.tum" 1 5 20 | sed 's/^/    /'
  done
done
echo
echo "Steps against the raw scans (structloc_path_scan_fit):"
fit="$(dirname "$structloc")/../tests/structloc_path_scan_fit"
for name in freiburg_079 intel; do
  for path in truth slam; do
    label="$([ $path = truth ] && echo "corrected poses" || echo "SLAM path")"
    for apart in "1.0 1.5" "0.1 0.3"; do
      printf '  %s, %s: ' "$name" "$label"
      # shellcheck disable=SC2086 # the two distances, split on purpose
      "$fit" "$out/$name.raw.log" "$out/$name.$path.tum" $apart
    done
  done
done
echo
echo "Places passed again after 10 m or more, against the raw scans (structloc_revisit_fit):"
revisit="$(dirname "$structloc")/../tests/structloc_revisit_fit"
for name in freiburg_079 intel; do
  printf '  %s, A the SLAM path, B the corrected poses: ' "$name"
  "$revisit" "$out/$name.raw.log" "$out/$name.slam.tum" "$out/$name.truth.tum"
  printf '  %s, A localised on the map slam built, B on the map of maps/real/: ' "$name"
  "$revisit" "$out/$name.raw.log" "$out/$name.localised.tum" "$out/$name.shipped.tum"
done
echo
echo "Walls against the building's axes (structloc_map_straightness):"
straightness="$(dirname "$structloc")/../tests/structloc_map_straightness"
for name in freiburg_079 intel; do
  "$straightness" "$root/maps/real/$name.xml"
  "$straightness" "$out/$name.slam.xml"
done
