#!/usr/bin/env bash
# The installed product works on its own: installs the build into a temporary
# prefix, moves the prefix (the install must be relocatable), checks the layout,
# runs the installed "structloc simulate" and "structloc replay" on the shipped
# scenario, checks that no build or source path leaks into --help, and builds
# and runs a tiny consumer project against find_package(structloc).
# The installed simulator also runs once with no file options, so that it must
# find its default scenario and QoS profiles beside itself (DDS on DOMAIN,
# loopback only).
# Usage: install_test.sh BUILD_DIR SOURCE_DIR DOMAIN [CONSUMER_LINK_FLAGS].
# Removes everything it created.
set -euo pipefail
build_dir=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
domain="$3"
consumer_link_flags="${4:-}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build_dir" --prefix "$work/first" >/dev/null
mv "$work/first" "$work/prefix"
prefix="$work/prefix"

for f in bin/structloc bin/structloc_simulator bin/structloc_localisation bin/structloc_calibration \
         bin/structloc_check_qos bin/structloc_keystore include/structloc/localisation_core/localiser/localiser.hpp \
         lib/cmake/structloc/structlocConfig.cmake lib/cmake/structloc/structlocTargets.cmake \
         lib/cmake/structloc/opencv_modules.cmake \
         share/structloc/maps/office_floor.xml share/structloc/maps/params/office_sick.xml \
         share/structloc/maps/scenarios/office_people.xml share/structloc/maps/robots/tricycle.xml \
         share/structloc/qos/structloc_qos.xml share/structloc/launch_xml/demo.launch.xml; do
  [[ -e "$prefix/$f" ]] || { echo "install_test: $f missing from the installed tree" >&2; exit 1; }
done
if ls "$prefix/bin" | grep -q _test; then
  echo "install_test: a test executable was installed into bin/" >&2
  exit 1
fi

for program in structloc structloc_localisation structloc_simulator structloc_calibration; do
  help=$("$prefix/bin/$program" --help 2>&1)
  for leaked in "$build_dir" "$source_dir"; do
    if grep -qF "$leaked" <<<"$help"; then
      echo "install_test: $program --help names $leaked" >&2
      exit 1
    fi
  done
done

share="$prefix/share/structloc"
env -u STRUCTLOC_SHARE_DIR "$prefix/bin/structloc_simulator" --domain "$domain" --time-scale 0 \
  --exit-when-done >"$work/simulator.txt" 2>&1 ||
  { cat "$work/simulator.txt" >&2; echo "install_test: the installed simulator failed" >&2; exit 1; }
grep -q "office_people" "$work/simulator.txt" ||
  { cat "$work/simulator.txt" >&2; echo "install_test: default scenario not used" >&2; exit 1; }
"$prefix/bin/structloc" simulate --scenario "$share/maps/scenarios/office_people.xml" \
  --out "$work/run" >/dev/null
"$prefix/bin/structloc" replay --map "$share/maps/office_floor.xml" --log "$work/run/run.clf" \
  --initial-pose "$(cat "$work/run/initial_pose")" --truth "$work/run/truth.tum" \
  --params "$share/maps/params/office_sick.xml" --out "$work/replayed.tum" | tee "$work/replay.txt"
[[ -s "$work/replayed.tum" ]] || { echo "install_test: replay wrote no trajectory" >&2; exit 1; }

cmake -S "$source_dir/tests/install/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_EXE_LINKER_FLAGS="$consumer_link_flags" >/dev/null
cmake --build "$work/consumer" >/dev/null
"$work/consumer/consumer"
echo "install_test: installed tree, relocated prefix, replay and find_package(structloc) all work"
