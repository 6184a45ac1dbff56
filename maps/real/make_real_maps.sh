#!/usr/bin/env bash
# Rebuilds the maps of the two SLAM-corrected real recordings in ../shared/data
# (Freiburg 079 and Intel, GMapping-corrected poses) and the pictures the docs
# show, with the structloc CLI only:
#   1. map build   walls, corners, pillars from the recording       -> NAME.xml
#   2. map check   the built map against the same recording        -> NAME_check.png
#   3. map grid    a 5 cm log-odds grid ray-cast from the recording (independent of 1)
#   4. map import  walls from that grid                            -> NAME_from_grid.png
#   5. map check   the imported map against the recording          -> NAME_from_grid_check.png
# Usage: maps/real/make_real_maps.sh [BUILD_DIR] [DATA_DIR]   (defaults: build, ../shared/data)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
structloc="${1:-$root/build}/bin/structloc"
data="${2:-$root/../shared/data}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

cd "$work"  # grids and imported maps are named plainly in the pictures
for name in freiburg_079 intel; do
  log="$data/${name//_/-}-corrected.log.gz"
  echo "== $name"
  "$structloc" map build --log "$log" --out "$here/$name.xml" --name "$name" --quiet
  "$structloc" map check --map "$here/$name.xml" --log "$log" --plot "$here/${name}_check.png"
  "$structloc" map grid --log "$log" --out "$name.yaml"
  "$structloc" map import --grid "$name.yaml" --out "${name}_from_grid.xml" \
    --plot "$here/${name}_from_grid.png"
  "$structloc" map check --map "${name}_from_grid.xml" --log "$log" \
    --plot "$here/${name}_from_grid_check.png"
done
