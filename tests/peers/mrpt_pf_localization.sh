#!/usr/bin/env bash
# Side by side with a standard particle-filter localiser (issue 12): MRPT's
# pf-localization and structloc replay on the same evaluation logs, the same
# world map (MRPT gets it as the grid `structloc map export` writes) and the same
# truth. A documented peer run, not part of ctest; it installs nothing.
#
# Usage (from the repository root, after building structloc):
#   tests/peers/mrpt_pf_localization.sh --log CORRECTED.log[.gz] --map WORLD.xml [options]
# e.g.
#   tests/peers/mrpt_pf_localization.sh --log ../shared/data/intel-corrected.log.gz \
#       --map maps/real/intel.xml --restamp 0.5 --raycast-grid
# Options:
#   --structloc PATH    structloc binary (default build/bin/structloc)
#   --params XML        structloc localiser parameters (default maps/params/office_sick.xml)
#   --restamp SPEED     passed to synthesise-odometry (needed for Intel's key scans)
#   --raycast-grid      also run MRPT on the 5 cm grid ray-cast from the log (`structloc map grid`)
#   --particles N       MRPT's initial particle count (default 5000; KLD adapts it within 500..5000)
#   --odo-std-xy M      MRPT motion-model minimum std, m (default 0.05)
#   --odo-std-phi DEG   MRPT motion-model minimum std, deg (default 2.0)
#   --init-xy M         half-width of MRPT's initial box around the true first pose, m (default 0.2)
#   --init-yaw DEG      half-width of that box in heading, deg (default 5)
#
# What it does, for two odometry variants (perfect; 1.5 % scale error, 0.3 deg/m
# heading drift, 5 mm and 0.1 deg noise per sqrt(m), the figures of the README):
#  1. structloc synthesise-odometry: evaluation log (ODOM + ROBOTLASER1) and truth (TUM);
#  2. structloc map export (and with --raycast-grid, map grid): map_server YAML + PGM;
#  3. carmen2rawlog: the evaluation log as an MRPT rawlog; ros-map-yaml2mrpt: the YAML
#     as a .gridmap.gz (this keeps map_server's origin convention: the YAML origin is
#     the world pose of the lower-left pixel);
#  4. pf-localization with mrpt_pf_localization.ini.in filled in: likelihood field
#     (Thrun) observation model, KLD-adaptive particles, initial particles uniform in a
#     small box around the true first pose (MRPT's app offers uniform boxes only; our
#     replay gets the exact first pose through --initial-pose);
#  5. pose_errors.py: MRPT's per-scan mean estimate to TUM, and position RMSE / max /
#     heading RMSE against the truth, for MRPT and for structloc replay alike;
#  6. prints the table, with the wall time of each run.
# Everything is made in a temporary directory that is removed on exit.
# Exit status: 0 done, 1 a step failed, 2 a tool is missing or the usage is wrong.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"

usage() { sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d' | sed 's/^# \{0,1\}//'; }

log="" map="" structloc="$repo/build/bin/structloc" params="$repo/maps/params/office_sick.xml"
restamp="" raycast=0 particles=5000 odo_std_xy=0.05 odo_std_phi=2.0 init_xy=0.2 init_yaw=5
while [[ $# -gt 0 ]]; do
    case "$1" in
        --log) log="$2"; shift 2 ;;
        --map) map="$2"; shift 2 ;;
        --structloc) structloc="$2"; shift 2 ;;
        --params) params="$2"; shift 2 ;;
        --restamp) restamp="$2"; shift 2 ;;
        --raycast-grid) raycast=1; shift ;;
        --particles) particles="$2"; shift 2 ;;
        --odo-std-xy) odo_std_xy="$2"; shift 2 ;;
        --odo-std-phi) odo_std_phi="$2"; shift 2 ;;
        --init-xy) init_xy="$2"; shift 2 ;;
        --init-yaw) init_yaw="$2"; shift 2 ;;
        -h|--help) usage; exit 0 ;;
        *) echo "unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
done
if [[ -z "$log" || -z "$map" ]]; then
    echo "--log CORRECTED.log and --map WORLD.xml are required (see --help)" >&2
    exit 2
fi
for f in "$log" "$map" "$params" "$here/mrpt_pf_localization.ini.in" "$here/pose_errors.py"; do
    [[ -r "$f" ]] || { echo "cannot read '$f'" >&2; exit 2; }
done
[[ -x "$structloc" ]] || { echo "no structloc at '$structloc': build it (cmake --build build --target structloc) or pass --structloc" >&2; exit 2; }
for tool in pf-localization carmen2rawlog ros-map-yaml2mrpt; do
    if ! command -v "$tool" > /dev/null; then
        echo "'$tool' is missing: apt-get install mrpt-apps (Debian/Ubuntu), then run this again" >&2
        exit 2
    fi
done
command -v python3 > /dev/null || { echo "python3 is missing" >&2; exit 2; }

work="$(mktemp -d "${TMPDIR:-/tmp}/mrpt_peer.XXXXXX")"
trap 'rm -rf "$work"' EXIT

fail() { echo "$1 failed; its output:" >&2; tail -n 20 "$2" >&2; exit 1; }
seconds_since() { awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }'; }

# 2. grids
"$structloc" map export --map "$map" --grid "$work/exported.yaml" > "$work/export.out" 2>&1 \
    || fail "structloc map export" "$work/export.out"
grids=(exported)
if [[ $raycast -eq 1 ]]; then
    "$structloc" map grid --log "$log" --out "$work/raycast.yaml" > "$work/raycast.out" 2>&1 \
        || fail "structloc map grid" "$work/raycast.out"
    grids+=(raycast)
fi
for g in "${grids[@]}"; do
    ros-map-yaml2mrpt -i "$work/$g.yaml" -d "$work" -w -q > "$work/$g.convert.out" 2>&1 \
        || fail "ros-map-yaml2mrpt on the $g grid" "$work/$g.convert.out"
    [[ -s "$work/$g.gridmap.gz" ]] || fail "ros-map-yaml2mrpt (no $g.gridmap.gz)" "$work/$g.convert.out"
done

rows=()
for variant in perfect errors; do
    # 1. evaluation log and truth
    synth=(--log "$log" --out "$work/$variant.log" --truth "$work/$variant.tum")
    [[ $variant == errors ]] && synth+=(--scale-error 0.015 --heading-drift 0.3 --noise-xy 0.005 --noise-theta 0.1)
    [[ -n "$restamp" ]] && synth+=(--restamp "$restamp")
    "$structloc" synthesise-odometry "${synth[@]}" > "$work/$variant.synth.out" 2>&1 \
        || fail "structloc synthesise-odometry ($variant)" "$work/$variant.synth.out"
    read -r x0 y0 yaw0 < <(python3 - "$work/$variant.tum" <<'PY'
import math, sys
for line in open(sys.argv[1]):
    f = line.split()
    if f and not f[0].startswith("#"):
        qx, qy, qz, qw = map(float, f[4:8])
        print(f[1], f[2], math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz)))
        break
PY
)

    # structloc on the world map
    start=$(date +%s.%N)
    "$structloc" replay --map "$map" --log "$work/$variant.log" --truth "$work/$variant.tum" \
        --initial-pose "$x0 $y0 $yaw0" --out "$work/$variant.ours.tum" --params "$params" \
        > "$work/$variant.replay.out" 2>&1 || fail "structloc replay ($variant)" "$work/$variant.replay.out"
    took=$(seconds_since "$start")
    lost=$(sed -n 's/^lost: \([0-9]*\) scans.*/\1/p' "$work/$variant.replay.out")
    refused=$(sed -n 's/^ *rejected \([0-9]*\):.*/\1/p' "$work/$variant.replay.out" | awk '{n += $1} END {print n + 0}')
    read -r n rmse worst heading < <(python3 "$here/pose_errors.py" tum "$work/$variant.ours.tum" "$work/$variant.tum")
    rows+=("$variant|structloc replay|world map|$n|$rmse|$worst|$heading|${lost:-0} lost, $refused refused|$took")

    # 3. rawlog
    carmen2rawlog -i "$work/$variant.log" -o "$work/$variant.rawlog" -w -q > "$work/$variant.rawlog.out" 2>&1 \
        || fail "carmen2rawlog ($variant)" "$work/$variant.rawlog.out"

    # 4. pf-localization, 5. errors
    for g in "${grids[@]}"; do
        ini="$work/$variant.$g.ini"
        sed -e "s|@MIN_STD_XY_M@|$odo_std_xy|" -e "s|@MIN_STD_PHI_DEG@|$odo_std_phi|" \
            -e "s|@MAP_FILE@|$work/$g.gridmap.gz|" -e "s|@RAWLOG_FILE@|$work/$variant.rawlog|" \
            -e "s|@OUT_DIR@|$work/$variant.$g.pf|" -e "s|@PARTICLES@|$particles|" \
            -e "s|@INIT_MIN_X@|$(awk -v a="$x0" -v b="$init_xy" 'BEGIN{print a-b}')|" \
            -e "s|@INIT_MAX_X@|$(awk -v a="$x0" -v b="$init_xy" 'BEGIN{print a+b}')|" \
            -e "s|@INIT_MIN_Y@|$(awk -v a="$y0" -v b="$init_xy" 'BEGIN{print a-b}')|" \
            -e "s|@INIT_MAX_Y@|$(awk -v a="$y0" -v b="$init_xy" 'BEGIN{print a+b}')|" \
            -e "s|@INIT_MIN_YAW_DEG@|$(awk -v a="$yaw0" -v b="$init_yaw" 'BEGIN{print a*180/3.14159265358979-b}')|" \
            -e "s|@INIT_MAX_YAW_DEG@|$(awk -v a="$yaw0" -v b="$init_yaw" 'BEGIN{print a*180/3.14159265358979+b}')|" \
            "$here/mrpt_pf_localization.ini.in" > "$ini"
        if grep -q '@[A-Z_]*@' "$ini"; then echo "unfilled placeholder in $ini" >&2; exit 1; fi
        start=$(date +%s.%N)
        (cd "$work" && pf-localization "$ini" < /dev/null > "$work/$variant.$g.pf.out" 2>&1) \
            || fail "pf-localization ($variant, $g grid)" "$work/$variant.$g.pf.out"
        took=$(seconds_since "$start")
        read -r n rmse worst heading < <(python3 "$here/pose_errors.py" mrpt-log "$work/$variant.$g.pf.out" \
            "$work/$variant.tum" --tum-out "$work/$variant.$g.mrpt.tum")
        rows+=("$variant|MRPT pf-localization|$g grid|$n|$rmse|$worst|$heading||$took")
    done
done

# 6. the table
echo "log $(basename "$log"), map $(basename "$map"); odometry 'errors' = 1.5 % scale, 0.3 deg/m, noise 5 mm and 0.1 deg per sqrt(m)"
echo "errors over the poses each localiser estimated (of $(grep -vc '^#' "$work/perfect.tum") scans); MRPT seeds its generator from the clock, so its figures vary a little from run to run"
printf '%-8s %-21s %-14s %6s %10s %10s %12s %-24s %8s\n' odometry localiser map poses "RMSE m" "max m" "heading deg" note "time s"
for r in "${rows[@]}"; do
    IFS='|' read -r a b c d e f g h i <<< "$r"
    printf '%-8s %-21s %-14s %6s %10s %10s %12s %-24s %8s\n' "$a" "$b" "$c" "$d" "$e" "$f" "$g" "$h" "$i"
done
