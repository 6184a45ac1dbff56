#!/usr/bin/env bash
# Multi-host test without extra machines: every component runs on its own
# "host", a Linux network namespace joined to the others by a veth link to a
# bridge that lives in a namespace of its own, so no real interface is touched
# and no packet can leave the machine. Each host starts its share of
# launch_xml/structloc.launch.xml with the structloc_network profile, as a
# deployment over several computers would; a checker host runs
# "structloc watch", which exits 0 only if the localisation met the demo's
# accuracy bar against the simulator's ground truth.
#   multicast         Fast DDS's default discovery over UDP multicast
#   discovery_server  multicast dropped by iptables on every host, discovery
#                     through "fastdds discovery" started by the launch file on
#                     a host of its own (ROS_DISCOVERY_SERVER); a control
#                     participant that does not use the server must hear nothing
# Usage: netns_multihost_test.sh BUILD_DIR multicast|discovery_server DOMAIN
# Needs root (network namespaces) and iptables; exits 77 (ctest: skipped) and
# says why when either is missing. Everything it creates is removed on exit.
set -euo pipefail

build_dir="$1"
mode="$2"
domain="$3"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
launch_file="$here/../../launch_xml/structloc.launch.xml"
structloc="$build_dir/bin/structloc"

case "$mode" in
  multicast | discovery_server) ;;
  *)
    echo "usage: $0 BUILD_DIR multicast|discovery_server DOMAIN" >&2
    exit 2
    ;;
esac
# shellcheck source=netns_network.sh
source "$(dirname "${BASH_SOURCE[0]}")/netns_network.sh"
netns_require_root

prefix="slmh$$"
hosts=(chk cal loc sim srv)
subnet="10.213.0"
server_ip="$subnet.5"
work="$(mktemp -d)"
declare -A launch_pid

netns_trap_cleanup

netns_make_network "$prefix" "$subnet" "${hosts[@]}"
if [ "$mode" = discovery_server ]; then
  for h in "${hosts[@]}"; do
    ip netns exec "$prefix-$h" iptables -A OUTPUT -d 224.0.0.0/4 -j DROP
    ip netns exec "$prefix-$h" iptables -A INPUT -d 224.0.0.0/4 -j DROP
  done
fi
echo "network: ${#hosts[@]} hosts on $subnet.0/24 (bridge in $prefix-br), mode $mode, domain $domain"

discovery_server=""
if [ "$mode" = discovery_server ]; then discovery_server="$server_ip:11811"; fi
common=("domain:=$domain" participant_profile:=structloc_network "discovery_server:=$discovery_server"
  simulator:=false localisation:=false calibration:=false)

# Starts `structloc launch` on host $1 with the common arguments and $2...
start_host() {
  local h="$1"
  shift
  ip netns exec "$prefix-$h" "$structloc" launch "$launch_file" "${common[@]}" "$@" \
    >"$work/$h.log" 2>&1 &
  launch_pid[$h]=$!
}

if [ "$mode" = discovery_server ]; then
  start_host srv start_discovery_server:=true "discovery_server_ip:=$server_ip"
fi
ROS_DISCOVERY_SERVER="$discovery_server" ip netns exec "$prefix-chk" "$structloc" watch \
  --domain "$domain" --participant-profile structloc_network --timeout-s 240 \
  >"$work/chk.log" 2>&1 &
watch_pid=$!
start_host cal calibration:=true
start_host loc localisation:=true
sleep 2
start_host sim simulator:=true time_scale:=2 wait_for_subscribers:=1 exit_when_done:=true

# The control: with multicast dropped, a participant that does not know the
# discovery server must hear nothing, or the run above proves nothing.
control_status=0
if [ "$mode" = discovery_server ]; then
  ROS_DISCOVERY_SERVER="" ip netns exec "$prefix-chk" "$structloc" watch --domain "$domain" \
    --participant-profile structloc_network --timeout-s 8 >"$work/control.log" 2>&1 ||
    control_status=$?
fi

watch_status=0
wait "$watch_pid" || watch_status=$?
cat "$work/chk.log"

# The simulator's launch ends by itself with the scenario; the others are
# stopped as an operator would, and must stop cleanly.
sim_status=0
wait "${launch_pid[sim]}" || sim_status=$?
failed=0
for h in loc cal srv; do
  [ -n "${launch_pid[$h]:-}" ] || continue
  kill -INT "${launch_pid[$h]}"
  status=0
  wait "${launch_pid[$h]}" || status=$?
  if [ "$status" -ne 0 ]; then
    echo "FAILED: host $h's launch exited with $status after SIGINT"
    failed=1
  fi
done
if ! grep -q "simulator ended with exit code 0\|simulator exited with code 0" "$work/sim.log" ||
  [ "$sim_status" -ne 0 ]; then
  echo "FAILED: the simulator's launch did not end cleanly (exit $sim_status)"
  failed=1
fi
if ! grep -q "localisation: stopped cleanly" "$work/loc.log"; then
  echo "FAILED: the localisation did not stop cleanly"
  failed=1
fi
if [ "$mode" = discovery_server ]; then
  if ! grep -q "Server is running" "$work/srv.log"; then
    echo "FAILED: the discovery server did not start"
    failed=1
  fi
fi
if [ "$mode" = discovery_server ] &&
  ! { [ "$control_status" -eq 1 ] && grep -q "no ground truth" "$work/control.log"; }; then
  echo "FAILED: the control participant without the discovery server heard the run (exit" \
    "$control_status): multicast is not blocked"
  failed=1
fi
if [ "$watch_status" -ne 0 ]; then
  echo "FAILED: the checker host's verdict (exit $watch_status)"
  failed=1
fi
if [ "$failed" -ne 0 ]; then exit 1; fi
echo "PASSED: $mode discovery across ${#hosts[@]} network namespaces met the accuracy bar"
