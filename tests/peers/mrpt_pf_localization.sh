#!/usr/bin/env bash
# Side by side with a standard particle-filter localiser (issue 12): MRPT's
# pf-localization and structloc replay on the same evaluation logs and the same
# truth, with MRPT set up the way ../shared/reviews/mrpt-fair-peer-36dc199.md
# found it must be on CARMEN logs to run at its best. A documented peer run,
# not part of ctest; it installs nothing.
#
# Usage (from the repository root, after building structloc):
#   tests/peers/mrpt_pf_localization.sh --log CORRECTED.log[.gz] --map WORLD.xml [options]
# e.g.
#   tests/peers/mrpt_pf_localization.sh --log ../shared/data/intel-corrected.log.gz \
#       --map maps/real/intel.xml --restamp 0.5
# Options:
#   --structloc PATH    structloc binary (default build/bin/structloc)
#   --params XML        structloc localiser parameters (default maps/params/sick_lms2xx.xml)
#   --restamp SPEED     passed to synthesise-odometry (needed for Intel's key scans)
#   --settings LIST     MRPT settings to run, comma-separated, of S1,S2,S3 or "all" (default S3)
#   --grids LIST        grids for MRPT, comma-separated, of exported,raycast,hits (default all three)
#   --odometry LIST     odometry variants, of perfect,errors (default both)
#   --init-xy M         half-width of MRPT's initial box around the true first pose, m (default 0.2)
#   --init-yaw DEG      half-width of that box in heading, deg (default 5)
#   --results DIR       also copy the table, the TUM estimates and the run logs to DIR
#   --raycast-grid      accepted for compatibility (the ray-cast grid is in the default --grids)
#
# The settings (fixed before any run in the review, the same for every building;
# NOT to be tuned on the recordings this script is run on):
#   all: likelihood field (Thrun) sigma 0.05 m, LF_maxCorrsDistance 0.3 m,
#        zHit/zRandom 0.95/0.05, standard proposal, multinomial resampling at
#        ESS < N/2, a fixed number of particles, started uniform within
#        --init-xy / --init-yaw of the true first pose;
#        MRPT's probabilistic motion model (CActionRobotMovement2D mmGaussian):
#        std x,y = 5 mm + a1*d + a2*|dphi|, std phi = 0.25 deg + a3*d + a4*|dphi|
#   S1:  500 particles, every 4th beam, a1..a4 = 5 %/m, 1 mm/deg, 1 deg/m, 5 %/deg
#   S2: 2000 particles, every 2nd beam, the noise of S1
#   S3: 2000 particles, every 2nd beam, a1..a4 = 2 %/m, 0.5 mm/deg, 0.5 deg/m, 2 %/deg
#        (2-3x the measured odometry error per step; the review's best)
#
# What it does, for each odometry variant (perfect; "errors": 1.5 % scale
# error, 0.3 deg/m heading drift, 5 mm and 0.1 deg noise per sqrt(m)):
#  1. structloc synthesise-odometry: evaluation log (ODOM + ROBOTLASER1) and truth (TUM);
#  2. structloc replay on the world map from the true first pose (--initial-pose);
#  3. mrpt_peer_tools.cpp (compiled here, into the temporary directory, against
#     libmrpt-dev) writes the evaluation log as an action/sensory-frame rawlog:
#     each scan with its own stamp, its beams exactly as in the log (beam 0 at
#     start_angle, aperture (N-1)*angular_res, sensor pose = laser pose relative
#     to robot pose), no-return readings (>= max_range) invalid, and per scan a
#     CActionRobotMovement2D from the odometry increment (computeFromOdometry,
#     the setting's noise); the first scan is written twice because
#     pf-localization runs no filter step on its first entry;
#  4. grids, all 5 cm, the likelihood options baked into the .gridmap (which is
#     where pf-localization reads them from): "exported" = `structloc map export`
#     of the world map; "raycast" = `structloc map grid` of the corrected log;
#     "hits" = only the cells where the log's beams (< 20 m) end, seen from the
#     true poses, occupied. loadFromROSMapServerYAML rounds a map_server origin
#     to a whole cell: the initial box is moved by that shift and the shift is
#     subtracted from every estimate (the hits grid is cell-aligned: no shift);
#  5. pf-localization with mrpt_pf_localization.ini.in filled in;
#  6. pose_errors.py: position RMSE / max and heading RMSE against the truth, for
#     MRPT (its per-scan mean) and structloc alike; CPU per scan = user + sys
#     time of the whole process (start-up and map loading included) / scans;
#     for structloc that includes its whole-map searches at scans the tracked
#     pose did not explain (their number is in the note);
#  7. prints the table.
# Everything is made in a temporary directory that is removed on exit.
# MRPT seeds its generator from the clock: its figures vary a little from run to run.
# Exit status: 0 done, 1 a step failed, 2 a tool is missing or the usage is wrong.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"

usage() { sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d' | sed 's/^# \{0,1\}//'; }

log="" map="" structloc="$repo/build/bin/structloc" params="$repo/maps/params/sick_lms2xx.xml"
restamp="" settings="S3" grids_opt="exported,raycast,hits" variants_opt="perfect,errors"
init_xy=0.2 init_yaw=5 results=""
while [[ $# -gt 0 ]]; do
    case "$1" in
        --log) log="$2"; shift 2 ;;
        --map) map="$2"; shift 2 ;;
        --structloc) structloc="$2"; shift 2 ;;
        --params) params="$2"; shift 2 ;;
        --restamp) restamp="$2"; shift 2 ;;
        --settings) settings="$2"; shift 2 ;;
        --grids) grids_opt="$2"; shift 2 ;;
        --odometry) variants_opt="$2"; shift 2 ;;
        --init-xy) init_xy="$2"; shift 2 ;;
        --init-yaw) init_yaw="$2"; shift 2 ;;
        --results) results="$2"; shift 2 ;;
        --raycast-grid) shift ;;
        -h|--help) usage; exit 0 ;;
        *) echo "unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
done
if [[ -z "$log" || -z "$map" ]]; then
    echo "--log CORRECTED.log and --map WORLD.xml are required (see --help)" >&2
    exit 2
fi
[[ $settings == all ]] && settings="S1,S2,S3"
IFS=',' read -r -a setting_list <<< "$settings"
IFS=',' read -r -a grids <<< "$grids_opt"
IFS=',' read -r -a variants <<< "$variants_opt"
for s in "${setting_list[@]}"; do [[ $s =~ ^S[123]$ ]] || { echo "--settings: '$s' is not S1, S2 or S3" >&2; exit 2; }; done
for g in "${grids[@]}"; do [[ $g =~ ^(exported|raycast|hits)$ ]] || { echo "--grids: unknown grid '$g'" >&2; exit 2; }; done
for v in "${variants[@]}"; do [[ $v =~ ^(perfect|errors)$ ]] || { echo "--odometry: unknown variant '$v'" >&2; exit 2; }; done
for n in "$init_xy" "$init_yaw"; do [[ $n =~ ^[0-9]+(\.[0-9]+)?$ ]] || { echo "--init-xy/--init-yaw need a number" >&2; exit 2; }; done
for f in "$log" "$map" "$params" "$here/mrpt_pf_localization.ini.in" "$here/pose_errors.py" "$here/mrpt_peer_tools.cpp"; do
    [[ -r "$f" ]] || { echo "cannot read '$f'" >&2; exit 2; }
done
[[ -x "$structloc" ]] || { echo "no structloc at '$structloc': build it (cmake --build build --target structloc) or pass --structloc" >&2; exit 2; }
apt_line="apt-get install mrpt-apps libmrpt-dev g++ (Debian/Ubuntu), then run this again"
command -v pf-localization > /dev/null || { echo "'pf-localization' is missing: $apt_line" >&2; exit 2; }
command -v g++ > /dev/null || { echo "'g++' is missing: $apt_line" >&2; exit 2; }
command -v python3 > /dev/null || { echo "python3 is missing" >&2; exit 2; }
mrpt_modules="mrpt-maps mrpt-obs mrpt-poses mrpt-io mrpt-serialization mrpt-containers mrpt-math mrpt-system mrpt-core mrpt-rtti"
if command -v pkg-config > /dev/null && pkg-config --exists $mrpt_modules 2> /dev/null; then
    mrpt_flags=($(pkg-config --cflags --libs $mrpt_modules))
elif [[ -r /usr/include/mrpt/maps/include/mrpt/maps/COccupancyGridMap2D.h ]]; then
    # Debian's libmrpt-dev ships CMake configs but no .pc files: its layout.
    mrpt_flags=()
    for d in /usr/include/mrpt/*/include; do mrpt_flags+=("-I$d"); done
    [[ -d /usr/include/eigen3 ]] && mrpt_flags+=(-I/usr/include/eigen3)
    for m in $mrpt_modules; do mrpt_flags+=("-l$m"); done
else
    echo "the MRPT headers are missing: $apt_line" >&2
    exit 2
fi

work="$(mktemp -d "${TMPDIR:-/tmp}/mrpt_peer.XXXXXX")"
trap 'rm -rf "$work"' EXIT

fail() { echo "$1 failed; its output:" >&2; tail -n 20 "$2" >&2; exit 1; }
# timed CPU_FILE OUT_FILE COMMAND...: runs COMMAND (stdin from /dev/null, output
# to OUT_FILE) and writes "user sys wall" seconds of it and its children.
timed() {
    python3 - "$@" <<'PY'
import resource, subprocess, sys, time
cpu, out, cmd = sys.argv[1], sys.argv[2], sys.argv[3:]
start = time.monotonic()
with open(out, "w") as f:
    rc = subprocess.call(cmd, stdin=subprocess.DEVNULL, stdout=f, stderr=subprocess.STDOUT)
wall = time.monotonic() - start
r = resource.getrusage(resource.RUSAGE_CHILDREN)
with open(cpu, "w") as f:
    f.write(f"{r.ru_utime:.3f} {r.ru_stime:.3f} {wall:.3f}\n")
sys.exit(rc)
PY
}
# ms per scan from a CPU file: (user + sys) / scans
per_scan_ms() { awk -v n="$2" '{ printf "%.2f", 1000 * ($1 + $2) / n }' "$1"; }
wall_s() { awk '{ printf "%.1f", $3 }' "$1"; }
mm() { awk -v m="$1" 'BEGIN { printf "%.1f", 1000 * m }'; }

# the settings: particles decimation a1(m/m) a2(m/deg) a3(deg/m) a4(deg/deg) floor_xy(m) floor_phi(deg)
setting_values() {
    case "$1" in
        S1) echo "500 4 0.05 0.001 1.0 0.05 0.005 0.25" ;;
        S2) echo "2000 2 0.05 0.001 1.0 0.05 0.005 0.25" ;;
        S3) echo "2000 2 0.02 0.0005 0.5 0.02 0.005 0.25" ;;
    esac
}

# 0. the helper
g++ -std=c++17 -O2 -o "$work/mrpt_peer_tools" "$here/mrpt_peer_tools.cpp" "${mrpt_flags[@]}" \
    > "$work/compile.out" 2>&1 || fail "compiling mrpt_peer_tools.cpp against libmrpt-dev" "$work/compile.out"
tools="$work/mrpt_peer_tools"

# 4a. map_server grids from structloc
need_yaml=()
for g in "${grids[@]}"; do [[ $g != hits ]] && need_yaml+=("$g"); done
for g in "${need_yaml[@]}"; do
    case "$g" in
        exported) "$structloc" map export --map "$map" --grid "$work/exported.yaml" > "$work/exported.make.out" 2>&1 \
                      || fail "structloc map export" "$work/exported.make.out" ;;
        raycast) "$structloc" map grid --log "$log" --out "$work/raycast.yaml" > "$work/raycast.make.out" 2>&1 \
                      || fail "structloc map grid" "$work/raycast.make.out" ;;
    esac
done

rows=()
scans=0
for variant in "${variants[@]}"; do
    # 1. evaluation log and truth
    synth=(--log "$log" --out "$work/$variant.log" --truth "$work/$variant.tum")
    [[ $variant == errors ]] && synth+=(--scale-error 0.015 --heading-drift 0.3 --noise-xy 0.005 --noise-theta 0.1)
    [[ -n "$restamp" ]] && synth+=(--restamp "$restamp")
    "$structloc" synthesise-odometry "${synth[@]}" > "$work/$variant.synth.out" 2>&1 \
        || fail "structloc synthesise-odometry ($variant)" "$work/$variant.synth.out"
    scans=$(grep -vc '^#' "$work/$variant.tum")
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

    # 2. structloc on the world map
    timed "$work/$variant.replay.cpu" "$work/$variant.replay.out" \
        "$structloc" replay --map "$map" --log "$work/$variant.log" --truth "$work/$variant.tum" \
        --initial-pose "$x0 $y0 $yaw0" --out "$work/$variant.structloc.tum" --params "$params" \
        || fail "structloc replay ($variant)" "$work/$variant.replay.out"
    lost=$(sed -n 's/^lost: \([0-9]*\) scans.*/\1/p' "$work/$variant.replay.out")
    searches=$(sed -n 's/^searched the whole map at \([0-9]*\) scans.*/\1/p' "$work/$variant.replay.out")
    read -r n rmse worst heading < <(python3 "$here/pose_errors.py" tum "$work/$variant.structloc.tum" "$work/$variant.tum") \
        || fail "pose_errors.py (structloc, $variant)" /dev/null
    rows+=("$variant|structloc replay|$(basename "$params" .xml)|world map|$n|$(mm "$rmse")|$(mm "$worst")|$heading|$(per_scan_ms "$work/$variant.replay.cpu" "$scans")|$(wall_s "$work/$variant.replay.cpu")|${lost:-0} lost, ${searches:-0} whole-map searches")

    for setting in "${setting_list[@]}"; do
        read -r particles decimation a1 a2 a3 a4 floor_xy floor_phi <<< "$(setting_values "$setting")"
        # 3. rawlog with this setting's motion noise
        "$tools" rawlog --log "$work/$variant.log" --out "$work/$variant.$setting.rawlog" \
            --a1 "$a1" --a2 "$a2" --a3 "$a3" --a4 "$a4" --min-xy "$floor_xy" --min-phi "$floor_phi" \
            > "$work/$variant.$setting.rawlog.out" 2>&1 \
            || fail "mrpt_peer_tools rawlog ($variant, $setting)" "$work/$variant.$setting.rawlog.out"
        for g in "${grids[@]}"; do
            # 4b. the grid with this setting's likelihood options (made once per setting)
            gm="$work/$g.$setting.gridmap.gz"
            if [[ ! -s "$gm" ]]; then
                if [[ $g == hits ]]; then
                    "$tools" grid-hits --log "$work/$variant.log" --truth "$work/$variant.tum" --out "$gm" \
                        --decimation "$decimation" > "$work/$g.$setting.grid.out" 2>&1 \
                        || fail "mrpt_peer_tools grid-hits ($setting)" "$work/$g.$setting.grid.out"
                else
                    "$tools" grid-yaml --yaml "$work/$g.yaml" --out "$gm" \
                        --decimation "$decimation" > "$work/$g.$setting.grid.out" 2>&1 \
                        || fail "mrpt_peer_tools grid-yaml ($g, $setting)" "$work/$g.$setting.grid.out"
                fi
            fi
            read -r dx dy < <(sed -n 's/^shift \([-0-9.e]*\) \([-0-9.e]*\)$/\1 \2/p' "$work/$g.$setting.grid.out")
            [[ -n "${dx:-}" && -n "${dy:-}" ]] || fail "reading the origin shift of the $g grid" "$work/$g.$setting.grid.out"
            # 5. pf-localization
            run="$variant.$setting.$g"
            ini="$work/$run.ini"
            sed -e "s|@MAP_FILE@|$gm|" -e "s|@RAWLOG_FILE@|$work/$variant.$setting.rawlog|" \
                -e "s|@OUT_DIR@|$work/$run.pf|" -e "s|@PARTICLES@|$particles|g" -e "s|@DECIMATION@|$decimation|" \
                -e "s|@INIT_MIN_X@|$(awk -v a="$x0" -v s="$dx" -v b="$init_xy" 'BEGIN{printf "%.6f", a+s-b}')|" \
                -e "s|@INIT_MAX_X@|$(awk -v a="$x0" -v s="$dx" -v b="$init_xy" 'BEGIN{printf "%.6f", a+s+b}')|" \
                -e "s|@INIT_MIN_Y@|$(awk -v a="$y0" -v s="$dy" -v b="$init_xy" 'BEGIN{printf "%.6f", a+s-b}')|" \
                -e "s|@INIT_MAX_Y@|$(awk -v a="$y0" -v s="$dy" -v b="$init_xy" 'BEGIN{printf "%.6f", a+s+b}')|" \
                -e "s|@INIT_MIN_YAW_DEG@|$(awk -v a="$yaw0" -v b="$init_yaw" 'BEGIN{printf "%.6f", a*180/3.14159265358979-b}')|" \
                -e "s|@INIT_MAX_YAW_DEG@|$(awk -v a="$yaw0" -v b="$init_yaw" 'BEGIN{printf "%.6f", a*180/3.14159265358979+b}')|" \
                "$here/mrpt_pf_localization.ini.in" > "$ini"
            if grep -q '@[A-Z_]*@' "$ini"; then echo "unfilled placeholder in $ini" >&2; exit 1; fi
            timed "$work/$run.cpu" "$work/$run.pf.out" pf-localization "$ini" \
                || fail "pf-localization ($variant, $setting, $g grid)" "$work/$run.pf.out"
            read -r n rmse worst heading < <(python3 "$here/pose_errors.py" mrpt-log "$work/$run.pf.out" \
                "$work/$variant.tum" --skip 1 --shift "$dx" "$dy" --tum-out "$work/$run.mrpt.tum") \
                || fail "pose_errors.py (MRPT, $run)" "$work/$run.pf.out"
            rows+=("$variant|MRPT pf-localization|$setting|$g grid|$n|$(mm "$rmse")|$(mm "$worst")|$heading|$(per_scan_ms "$work/$run.cpu" "$scans")|$(wall_s "$work/$run.cpu")|shift $(mm "$dx"),$(mm "$dy") mm")
        done
    done
done

# 7. the table
{
    echo "log $(basename "$log"), map $(basename "$map"), $scans scans${restamp:+, restamped at $restamp m/s}; odometry 'errors' = 1.5 % scale, 0.3 deg/m, noise 5 mm and 0.1 deg per sqrt(m)"
    echo "errors over the poses each localiser estimated; CPU per scan = (user + sys) of the whole process / $scans scans; MRPT seeds its generator from the clock"
    printf '%-8s %-21s %-12s %-14s %6s %9s %9s %12s %13s %8s  %s\n' odometry localiser setting map poses "RMSE mm" "max mm" "heading deg" "CPU/scan ms" "wall s" note
    for r in "${rows[@]}"; do
        IFS='|' read -r a b c d e f g h i j k <<< "$r"
        printf '%-8s %-21s %-12s %-14s %6s %9s %9s %12s %13s %8s  %s\n' "$a" "$b" "$c" "$d" "$e" "$f" "$g" "$h" "$i" "$j" "$k"
    done
} | tee "$work/table.txt"

if [[ -n "$results" ]]; then
    mkdir -p "$results"
    cp "$work/table.txt" "$work"/*.tum "$work"/*.out "$work"/*.ini "$work"/*.cpu "$results"/ 2> /dev/null || true
    for y in "$work"/*.yaml; do [[ -e "$y" ]] && cp "$y" "${y%.yaml}.pgm" "$results"/ || true; done
fi
