#!/usr/bin/env bash
# How much a map built from a raw recording depends on which scans the
# recording lost (issue 41): a loaded machine drops a few scans from a live
# recording (`structloc record`), and SLAM's path, and so the map built on
# it, then changes by centimetres. The office tour with people is simulated
# offline and mapped by `structloc slam` whole, then with five of its scans
# dropped in each of PATTERNS seeded patterns; each path, and the replay of
# the log on the map built on it, is judged against the truth after one
# rigid alignment (a self-built map has a frame of its own). Prints one row
# per pattern and the spread; the offline test (self_built_map_test.cpp)
# holds the whole log to its bars.
#
# Usage: tests/evaluation/slam_dropped_scans.sh [PATTERNS] [OUT_DIR] [BUILD_DIR]
#        (defaults: 24, slam_dropped_scans, build)
set -euo pipefail
patterns="${1:-24}"
# shellcheck source=tests/evaluation/recordings_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/recordings_common.sh"
recordings_setup slam_dropped_scans "${@:2}"
"$structloc" simulate --scenario "$root/maps/scenarios/office_people.xml" --out "$out/tour" >/dev/null
scans=$(grep -c '^ROBOTLASER1 ' "$out/tour/run.clf")

# One row, LABEL: LOG mapped and localised on its map (files $out/STEM.*).
judge() {
  local label=$1 name=$2 log=$3 slam replay
  slam=$("$structloc" slam --log "$log" --truth "$out/tour/truth.tum" \
    --poses-out "$out/$name.slam.tum" --out "$out/$name.xml")
  replay=$("$structloc" replay --map "$out/$name.xml" --log "$log" \
    --params "$root/maps/params/office_sick.xml" --truth "$out/tour/truth.tum" \
    --initial-pose "$(first_pose "$out/$name.slam.tum")" --out "$out/$name.localised.tum" 2>"$out/$name.replay.log")
  printf '| %s | %s | %s |\n' "$label" \
    "$(sed -n 's/^  slam .*aligned: RMSE \([0-9.]*\) mm, max \([0-9.]*\) mm.*/\1 \/ \2/p' <<<"$slam")" \
    "$(sed -n 's/^estimate vs truth after one rigid alignment: position RMSE \([0-9.]*\) mm, max \([0-9.]*\) mm.*/\1 \/ \2/p' <<<"$replay")"
}

echo "| scans dropped | SLAM path aligned RMSE / max mm | localisation on its map aligned RMSE / max mm |"
echo "|---|---|---|"
judge none whole "$out/tour/run.clf" | tee "$out/rows.md"
for seed in $(seq 1 "$patterns"); do
  awk -v seed="$seed" -v scans="$scans" '
    BEGIN { srand(seed); while (n < 5) { k = int(rand() * scans) + 1; if (!(k in gone)) { gone[k] = 1; n++ } } }
    /^ROBOTLASER1 / && (++laser in gone) { next }
    { print }' "$out/tour/run.clf" >"$out/drop$seed.clf"
  judge "5 (pattern $seed)" "drop$seed" "$out/drop$seed.clf" | tee -a "$out/rows.md"
done
awk -F'|' 'NR > 1 {
    split($3, s, " / "); split($4, l, " / ")
    n++; if (s[2] > smax) smax = s[2]; if (l[1] > lmax) lmax = l[1]; if (l[2] > lmaxmax) lmaxmax = l[2]
    if (s[2] > 200) over++
  } END {
    printf "with scans dropped: SLAM path max up to %.1f mm (%d of %d above 200 mm); ", smax, over + 0, n
    printf "localisation on its map RMSE up to %.1f mm, max up to %.1f mm\n", lmax, lmaxmax
  }' "$out/rows.md"
