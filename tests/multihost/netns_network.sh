# Sourced by the tests that stand in for several hosts (multihost/): builds
# the network, a bridge in a namespace of its own (PREFIX-br) and one
# namespace per host (PREFIX-HOST) joined to it by a veth, host k holding
# SUBNET.k/24 on eth0. No real interface is touched and no packet can leave
# the machine. Fills netns_names (for netns_cleanup.sh) as it goes, so that a
# failure half-way still removes what was made. Usage:
#   source netns_network.sh; netns_require_root
#   work="$(mktemp -d)"; netns_trap_cleanup
#   netns_make_network PREFIX SUBNET HOST...

# shellcheck source=../netns_cleanup.sh
source "$(dirname "${BASH_SOURCE[0]}")/../netns_cleanup.sh"

# Exits 77 (ctest: skipped), saying why, unless namespaces and iptables can be used.
netns_require_root() {
  if [ "$(id -u)" -ne 0 ]; then
    echo "SKIPPED: network namespaces need root (run the test command as root)"
    exit 77
  fi
  if ! command -v iptables >/dev/null; then
    echo "SKIPPED: iptables is not installed (./setup.sh deps installs it)"
    exit 77
  fi
}

# On any exit, also a failed one, removes the namespaces made so far and $work.
netns_trap_cleanup() {
  netns_names=()
  trap netns_cleanup EXIT
  trap 'exit 130' INT TERM
}
netns_make_network() {
  local prefix="$1" subnet="$2" h i=1
  shift 2
  netns_names+=("$prefix-br")
  ip netns add "$prefix-br"
  ip -n "$prefix-br" link add br0 type bridge
  ip -n "$prefix-br" link set br0 up
  for h in "$@"; do
    netns_names+=("$prefix-$h")
    ip netns add "$prefix-$h"
    ip link add eth0 netns "$prefix-$h" type veth peer name "v$h" netns "$prefix-br"
    ip -n "$prefix-br" link set "v$h" master br0 up
    ip -n "$prefix-$h" link set lo up
    ip -n "$prefix-$h" addr add "$subnet.$i/24" dev eth0
    ip -n "$prefix-$h" link set eth0 up
    i=$((i + 1))
  done
}
