# Sourced by the tests that stand in for several hosts (multihost/): builds
# the network, a bridge in a namespace of its own (PREFIX-br) and one
# namespace per host (PREFIX-HOST) joined to it by a veth, host k holding
# SUBNET.k/24 on eth0. No real interface is touched and no packet can leave
# the machine. Fills netns_names (for netns_cleanup.sh) as it goes, so that a
# failure half-way still removes what was made. Usage:
#   netns_make_network PREFIX SUBNET HOST...
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
