#!/usr/bin/env bash
# structloc's one-command entry point: installs the Debian packages the project
# needs (idempotent, non-interactive; as root or through sudo), configures and
# builds into build/, then runs what was asked:
#   ./setup.sh demo    the main job: simulated robot localised live, summary + picture
#                      (installs and builds only what the demo runs)
#   ./setup.sh test    every test (ctest; beside it the container test and short
#                      runs of the fuzz targets), non-zero exit when one fails
#   ./setup.sh build   dependencies and build (with the tests) only
#   ./setup.sh deps    dependencies (with the tests') only
#   ./setup.sh container, ./setup.sh fuzz
#                      the container test, the fuzz targets' short runs (after
#                      "build"; "test" runs both beside ctest)
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build_dir="${STRUCTLOC_BUILD_DIR:-$here/build}"
jobs="$(nproc 2>/dev/null || echo 2)"

# What the product needs to build and run (all the demo installs).
packages=(
  build-essential cmake g++ make pkg-config
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools
  libeigen3-dev libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libtinyxml2-dev libceres-dev zlib1g-dev libyaml-cpp-dev libdxflib-dev
  procps openssl
)

# For building the tests and benchmarks ("./setup.sh build" and "test"):
# GoogleTest, Google Benchmark, Cyclone DDS for the interoperability tests,
# ip and iptables for the network-namespace tests.
test_packages=(
  libgtest-dev libgmock-dev libbenchmark-dev
  cyclonedds-dev cyclonedds-tools
  iproute2 iptables
)

# For the container test (run by "./setup.sh test" after ctest): Docker's
# engine and compose, and debootstrap for the locally made base image.
container_packages=(docker.io docker-compose debootstrap)

# For the fuzz targets (built by "./setup.sh test" with clang, libFuzzer and
# the sanitizers' runtimes).
fuzz_packages=(clang libclang-rt-14-dev)

# For tests that find a component stuck: gdb prints its threads' stacks, so
# that a failure seen once in CI says where it was stuck.
debug_packages=(gdb)

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

install_dependencies() {
  local missing=() wanted=("${packages[@]}")
  if [ "${1:-}" = for-build ] || [ "${1:-}" = for-tests ]; then wanted+=("${test_packages[@]}"); fi
  if [ "${1:-}" = for-tests ]; then
    wanted+=("${fuzz_packages[@]}" "${debug_packages[@]}")
    # Only root can start a Docker engine: others skip the container test.
    [ "$(id -u)" -eq 0 ] && wanted+=("${container_packages[@]}")
  fi
  for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ "${#missing[@]}" -eq 0 ]; then
    echo "setup: all Debian packages present"
    return
  fi
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# Builds everything with the tests, or (given targets: the demo's programs)
# only those, configured without the tests.
build() {
  local testing=ON targets=()
  if [ "$#" -gt 0 ]; then testing=OFF; targets=(--target "$@"); fi
  cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING="$testing" >/dev/null
  cmake --build "$build_dir" -j "$jobs" "${targets[@]}"
  echo "setup: built into $build_dir (executables in $build_dir/bin)"
}

# What "structloc demo" runs: the CLI, which launches the simulator and the
# localisation component (launch_xml/demo.launch.xml); not the tests.
demo_targets=(structloc structloc_simulator_main structloc_localisation_main)

run_tests() {
  local exclude=()
  if [ ! -d "$here/../shared/data" ]; then
    # CI has shared/ beside the checkout and runs these; say so when they cannot run.
    echo "setup: $here/../shared/data is not here: leaving out the tests on real recordings (label shared_data)"
    exclude=(-LE shared_data)
  fi
  # Tests that compute hold a core each (the "cpus" resource of
  # build/tests/resources.json); those that wait on DDS traffic and clocks run
  # beside them, hence four jobs per core (tests/CMakeLists.txt says which is which).
  local ctest=(ctest --test-dir "$build_dir" --output-on-failure -j "$((4 * jobs))" --timeout 600
    "${exclude[@]}")
  if [ "$(id -u)" -eq 0 ] && unshare --net true 2>/dev/null; then
    # As root the tests run in a network namespace of their own with only a
    # loopback: not one packet of theirs can reach this machine's interfaces.
    echo "setup: running the tests in a private network namespace (loopback only)"
    unshare --net sh -c 'ip link set lo up && exec "$@"' sh "${ctest[@]}"
  else
    "${ctest[@]}"
  fi
}

run_container_test() {
  local status=0
  "$here/tests/container/container_test.sh" "$build_dir" || status=$?
  if [ "$status" -eq 77 ]; then return 0; fi  # skipped, and it said why
  return "$status"
}

# The fuzz targets in a clang build of their own (build-fuzz beside build/),
# each run briefly on its seed corpus (tests/fuzz; the long run is
# tests/fuzz/fuzz_all.sh, which leaves its own run count in the build's cache:
# hence the short run's count is set here every time).
run_fuzz_tests() {
  local fuzz_dir="${STRUCTLOC_FUZZ_BUILD_DIR:-$here/build-fuzz}"
  CC=clang CXX=clang++ cmake -S "$here" -B "$fuzz_dir" -DSTRUCTLOC_FUZZ=ON -DBUILD_TESTING=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTRUCTLOC_FUZZ_RUNS=20000 >/dev/null
  cmake --build "$fuzz_dir" -j "$jobs" --target structloc_fuzzers
  ctest --test-dir "$fuzz_dir" -L fuzz --output-on-failure -j "$jobs"
}

# The container test (mostly waiting on its containers) and the fuzz build and
# runs (at the lowest CPU priority, on what ctest leaves idle) run beside
# ctest, each with its output in a log that is printed when it ends.
# start_beside_ctest NAME NICE COMMAND...: setsid gives the job a session
# (and process group) of its own, so that stop_beside_ctest ends it with all
# it started. With the kernel's autogroup scheduling (on in Debian) a session
# is also a scheduling group, which gets as much CPU as ctest's whole session
# whatever the nice value of its processes; so the group's own nice value is
# set too (/proc/self/autogroup; without autogroups there is no such file).
declare -A background_pids=()
start_beside_ctest() {
  local name="$1" nice="$2" log="$build_dir/logs/$1.log"
  shift 2
  mkdir -p "$build_dir/logs"
  echo "setup: $name runs beside ctest (output: $log)"
  setsid sh -c 'echo "$0" 2>/dev/null >/proc/self/autogroup; exec nice -n "$0" "$@"' \
    "$nice" "$@" >"$log" 2>&1 &
  background_pids[$name]=$!
}
wait_beside_ctest() {
  local name="$1" status=0
  wait "${background_pids[$name]}" || status=$?
  echo "setup: ---- $name (exit $status) ----"
  cat "$build_dir/logs/$name.log"
  return "$status"
}
stop_beside_ctest() {
  local pid
  for pid in "${background_pids[@]}"; do kill -TERM -- "-$pid" 2>/dev/null; done
  return 0
}

run_demo() {
  "$build_dir/bin/structloc" demo --out "$build_dir/demo/fig44_office.png"
}

case "${1:-}" in
  deps) install_dependencies for-build ;;
  build) install_dependencies for-build; build ;;
  test)
    install_dependencies for-tests
    build
    status=0
    trap stop_beside_ctest INT TERM
    start_beside_ctest container_test 0 "$here/setup.sh" container
    start_beside_ctest fuzz_tests 19 "$here/setup.sh" fuzz
    run_tests || status=$?
    wait_beside_ctest container_test || status=$?
    wait_beside_ctest fuzz_tests || status=$?
    exit "$status"
    ;;
  demo) install_dependencies; build "${demo_targets[@]}"; run_demo ;;
  container) run_container_test ;;
  fuzz) run_fuzz_tests ;;
  *)
    echo "usage: ./setup.sh demo|test|build|deps|container|fuzz" >&2
    exit 2
    ;;
esac
