# shellcheck shell=bash
# Sourced by the evaluations on the real recordings of ../shared/data
# (real_recordings.sh, slam_recordings.sh): their arguments and a helper.
#   recordings_setup DEFAULT_OUT_DIR [OUT_DIR] [BUILD_DIR] [DATA_DIR]
# sets root (the repository), out (made if missing), structloc (the CLI),
# data, params (the SICK LMS 2xx preset the recordings are localised with)
# and odometry_errors (synthesise-odometry's options for the real-recording
# table's errors: 1.5 % scale error, 0.3 deg/m heading drift, 5 mm and
# 0.1 deg noise per sqrt(m)), followed by the options in the environment
# variable EXTRA_ODOMETRY_ERRORS when it is set (e.g. "--turn-scale-error 0.02
# --noise-theta-turn 3": wheels slipping in turns, as MIT CSAIL's odometry does).
# shellcheck disable=SC2034  # the caller uses them
recordings_setup() {
  root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
  out="${2:-$1}"
  structloc="${3:-$root/build}/bin/structloc"
  data="${4:-$root/../shared/data}"
  params="$root/maps/params/sick_lms2xx.xml"
  odometry_errors=(--scale-error 0.015 --heading-drift 0.3 --noise-xy 0.005 --noise-theta 0.1)
  local extra=()
  read -r -a extra <<<"${EXTRA_ODOMETRY_ERRORS:-}"
  odometry_errors+=("${extra[@]}")
  mkdir -p "$out"
}

# The first pose of a TUM file as "X Y THETA".
first_pose() {
  awk '!/^#/ { printf "%s %s %.9f\n", $2, $3, 2 * atan2($7, $8); exit }' "$1"
}

# Freiburg 079 or Intel (NAME freiburg_079 or intel) as a raw log with the
# odometry errors above (Intel re-stamped at 0.5 m/s), written to
# $out/NAME.raw.log with the corrected poses as truth in $out/NAME.truth.tum.
synthesise_raw_log() {
  local restamp=()
  [ "$1" = intel ] && restamp=(--restamp 0.5)
  "$structloc" synthesise-odometry --log "$data/${1//_/-}-corrected.log.gz" \
    --out "$out/$1.raw.log" --truth "$out/$1.truth.tum" "${odometry_errors[@]}" \
    "${restamp[@]}" >/dev/null
}
