#!/usr/bin/env bash
# Containerised run of the product: builds the runtime image from the build
# tree (docker/build_image.sh), starts docker/compose.yaml (discovery server,
# simulator, localisation, calibration and checker, one container each, on an
# internal network) and passes when the checker does (the demo's accuracy bar
# over DDS between containers). Run by "./setup.sh test" after ctest.
# It needs root, Docker's engine (docker.io), docker-compose and debootstrap
# (./setup.sh installs them as root); without them it says SKIPPED and why,
# and exits 77. It starts a private dockerd (its own socket, no iptables
# rules, no default bridge) and stops it at the end, also on failure, after
# removing the containers and the network; images stay in BUILD_DIR/docker-data
# so the next run reuses the base image.
# Usage: tests/container/container_test.sh BUILD_DIR
set -euo pipefail

build_dir="$(cd "$1" && pwd)"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
docker_dir="$here/../../docker"
skip() {
  echo "container test SKIPPED: $1"
  exit 77
}
[ "$(id -u)" -eq 0 ] || skip "starting Docker's engine needs root"
for tool in dockerd docker docker-compose debootstrap; do
  command -v "$tool" >/dev/null || skip "$tool is not installed (./setup.sh test installs it as root)"
done

run="$(mktemp -d)"
project="structloc_test_$$"
export DOCKER_HOST="unix://$run/docker.sock"
compose=(docker-compose -p "$project" -f "$docker_dir/compose.yaml")
cleanup() {
  local status=$?
  set +e
  if [ "$status" -ne 0 ] && [ -S "$run/docker.sock" ]; then
    "${compose[@]}" logs --no-color 2>/dev/null | tail -n 60
  fi
  [ -S "$run/docker.sock" ] && "${compose[@]}" down -v --remove-orphans >/dev/null 2>&1
  if [ -f "$run/dockerd.pid" ]; then
    kill "$(cat "$run/dockerd.pid")" 2>/dev/null
    for _ in $(seq 50); do [ -f "$run/dockerd.pid" ] || break; sleep 0.2; done
  fi
  # dockerd leaves its default network namespace mounted under its exec root.
  grep -o " $run[^ ]*" /proc/mounts | sort -r | xargs -r umount -l
  rm -rf "$run"
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

dockerd --data-root "$build_dir/docker-data" --exec-root "$run/exec" --pidfile "$run/dockerd.pid" \
  -H "$DOCKER_HOST" --iptables=false --bridge=none >"$run/dockerd.log" 2>&1 &
for _ in $(seq 100); do docker info >/dev/null 2>&1 && break; sleep 0.2; done
docker info >/dev/null 2>&1 || {
  tail -n 20 "$run/dockerd.log"
  skip "Docker's engine did not start (its log is above)"
}
echo "container test: private dockerd up ($(docker version --format '{{.Server.Version}}'))"

start=$SECONDS
"$docker_dir/build_image.sh" "$build_dir" structloc:test
echo "container test: image ready in $((SECONDS - start)) s"
export STRUCTLOC_IMAGE=structloc:test
"${compose[@]}" up -d
checker="$("${compose[@]}" ps -q checker)"
verdict="$(docker wait "$checker")"
docker logs "$checker"
echo "container test: checker exited with $verdict"
for service in localisation calibration discovery; do
  state="$(docker inspect -f '{{.State.Status}} {{.State.OOMKilled}}' "$("${compose[@]}" ps -q "$service")")"
  if [ "$state" != "running false" ]; then
    echo "container test FAILED: $service is '$state', not running"
    exit 1
  fi
done
[ "$verdict" -eq 0 ] || { echo "container test FAILED: the checker's verdict"; exit 1; }
echo "container test PASSED: five containers, discovery server, the accuracy bar met"
