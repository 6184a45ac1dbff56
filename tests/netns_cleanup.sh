# Sourced by the tests that build network namespaces (multihost/, interop/):
# on any exit, also a failed one, kills every process in the namespaces named
# in netns_names, deletes them, shows the tail of each log in $work when the
# test failed, and removes $work. Usage:
#   netns_names=(a b); work="$(mktemp -d)"
#   trap netns_cleanup EXIT; trap 'exit 130' INT TERM
netns_cleanup() {
  local status=$? ns f
  set +e
  for ns in "${netns_names[@]}"; do
    ip netns pids "$ns" 2>/dev/null | xargs -r kill -9 2>/dev/null
  done
  wait 2>/dev/null
  for ns in "${netns_names[@]}"; do ip netns del "$ns" 2>/dev/null; done
  if [ "$status" -ne 0 ]; then
    for f in "$work"/*.log; do
      [ -f "$f" ] && { echo "----- $(basename "$f")"; tail -n 40 "$f"; }
    done
  fi
  rm -rf "$work"
  exit "$status"
}
