#!/usr/bin/env bash
# Converts the real front-steered tricycle recording (shared/data/
# tricycle-calibration-dataset.txt, Grisetti's Probabilistic Robotics course
# data) into structloc's calibration formats:
#   OUT/encoders.csv  t,traction_ticks,steering_ticks
#   OUT/fixes.csv     t,x,y,theta        (the tracker's pose of the sensor)
#   OUT/nominal.xml   robot parameter file with the header's nominal values
#
# The dataset's lines: "time: T ticks: STEER TRACTION model_pose: x y th
# tracker_pose: x y th". Its header gives Ksteer, Ktraction, axis_length,
# steer_offset, the encoders' maxima (steering 8192, traction 5000) and the
# sensor's mounting (1.5 m ahead of base_link). Its model:
#   steering angle = Ksteer * 2 pi * s / 8192 + steer_offset, where the
#     absolute steering encoder reads s in 0..8191 and s > 4096 means s - 8192;
#   distance per traction tick = Ktraction / 5000 (32-bit wrapping counter).
# Mapped onto our robot file: steering_rad_per_tick = Ksteer * 2 pi / 8192,
# steering_zero_tick = 0 (steering ticks written signed), traction_ticks_per_rev
# = 5000 and wheel_radius = Ktraction / (2 pi), so that wheel_radius * 2 pi /
# ticks_per_rev is Ktraction / 5000 per tick; axle_distance = axis_length.
#
# Usage: convert_tricycle_dataset.sh DATASET.txt OUT_DIR
set -euo pipefail
in="${1:?usage: convert_tricycle_dataset.sh DATASET.txt OUT_DIR}"
out="${2:?usage: convert_tricycle_dataset.sh DATASET.txt OUT_DIR}"
[ -r "$in" ] || { echo "convert_tricycle_dataset.sh: cannot read $in" >&2; exit 2; }
mkdir -p "$out"

values=$(awk '/^#parameter_values:/ {print $2, $3, $4, $5; exit}' "$in")
maxima=$(awk '/^#joints_max_enc_values:/ {print $2, $3; exit}' "$in")
mount=$(awk '/translation:/ { gsub(/[\[\],]/, " "); for (i = 1; i < NF; ++i) if ($i == "translation:") { print $(i+1), $(i+2); exit } }' "$in")
[ -n "$values" ] && [ -n "$maxima" ] && [ -n "$mount" ] ||
  { echo "convert_tricycle_dataset.sh: $in lacks the #parameter_values / #joints_max_enc_values / translation header" >&2; exit 2; }
read -r ksteer ktraction axis offset <<<"$values"
read -r steer_max traction_max <<<"$maxima"
read -r mount_x mount_y <<<"$mount"

awk -v smax="$steer_max" 'BEGIN { print "t,traction_ticks,steering_ticks" }
  $1 == "time:" && $3 == "ticks:" {
    s = $4 + 0; if (s > smax / 2) s -= smax;
    printf "%s,%s,%d\n", $2, $5, s }' "$in" > "$out/encoders.csv"
awk 'BEGIN { print "t,x,y,theta" }
  $1 == "time:" { for (i = 1; i <= NF; ++i) if ($i == "tracker_pose:") printf "%s,%s,%s,%s\n", $2, $(i+1), $(i+2), $(i+3) }' \
  "$in" > "$out/fixes.csv"
awk -v ks="$ksteer" -v kt="$ktraction" -v axis="$axis" -v off="$offset" -v smax="$steer_max" \
    -v tmax="$traction_max" -v mx="$mount_x" -v my="$mount_y" 'BEGIN {
  pi = atan2(0, -1)
  printf "<?xml version=\"1.0\"?>\n<!-- nominal parameters of the real tricycle dataset (converted by convert_tricycle_dataset.sh) -->\n"
  printf "<robot wheel_radius=\"%.10g\" axle_distance=\"%s\" steering_offset=\"%s\"\n", kt / (2 * pi), axis, off
  printf "       traction_ticks_per_rev=\"%s\" traction_counter_bits=\"32\"\n", tmax
  printf "       steering_rad_per_tick=\"%.10g\" steering_zero_tick=\"0\"\n", ks * 2 * pi / smax
  printf "       sensor_x=\"%s\" sensor_y=\"%s\" sensor_theta=\"0\"/>\n", mx, my }' > "$out/nominal.xml"
echo "wrote $out/encoders.csv ($(($(wc -l < "$out/encoders.csv") - 1)) samples), $out/fixes.csv, $out/nominal.xml"
