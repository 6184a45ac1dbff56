#!/usr/bin/env bash
# The secure deployment meets the demo's accuracy bar (issue 16): a keystore
# from the shipped structloc_keystore, launch_xml/structloc.launch.xml with
# security_keystore:=, every component authenticated, access-controlled and
# encrypted, and "structloc watch" under the operator identity judging the run
# against the simulator's ground truth. A second, unauthenticated watch on the
# same domain must hear nothing: the secure run is closed to strangers.
# Loopback only (the default participant profile). Everything it creates is
# removed on exit.
#   secure_demo_test.sh BUILD_DIR DOMAIN
set -euo pipefail
build_dir="$1"
domain="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
structloc="$build_dir/bin/structloc"
work="$(mktemp -d)"
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -INT "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

"$build_dir/bin/structloc_keystore" "$work/keys"

"$structloc" watch --domain "$domain" --security-keystore "$work/keys" --timeout-s 240 \
  >"$work/watch.log" 2>&1 &
watch_pid=$!
pids+=("$watch_pid")
"$structloc" launch "$here/../../launch_xml/structloc.launch.xml" "domain:=$domain" \
  "security_keystore:=$work/keys" calibration:=false time_scale:=2 wait_for_subscribers:=1 \
  exit_when_done:=true >"$work/launch.log" 2>&1 &
launch_pid=$!
pids+=("$launch_pid")
# The stranger listens only while the secure run is known to be publishing
# (the operator hears its ground truth), so that hearing nothing means
# something.
for _ in $(seq 600); do
  grep -q "ground truth arriving" "$work/watch.log" && break
  kill -0 "$watch_pid" 2>/dev/null || break
  sleep 0.2
done
"$structloc" watch --domain "$domain" --timeout-s 15 >"$work/stranger.log" 2>&1 &
stranger_pid=$!
pids+=("$stranger_pid")

watch_status=0
wait "$watch_pid" || watch_status=$?
stranger_status=0
wait "$stranger_pid" || stranger_status=$?
cat "$work/watch.log"
failed=0
if [ "$watch_status" -ne 0 ]; then
  echo "FAILED: the operator's verdict on the secure run (exit $watch_status); the launch said:"
  cat "$work/launch.log"
  failed=1
fi
if ! grep -q "ground truth arriving" "$work/watch.log"; then
  echo "FAILED: the operator never heard the secure run, so the stranger's silence proves nothing"
  failed=1
elif ! { [ "$stranger_status" -eq 1 ] && grep -q "no ground truth" "$work/stranger.log"; }; then
  echo "FAILED: an unauthenticated participant heard the secure run (exit $stranger_status):"
  cat "$work/stranger.log"
  failed=1
fi
if [ "$failed" -ne 0 ]; then exit 1; fi
echo "PASSED: the secure run met the accuracy bar, and an unauthenticated participant heard nothing"
