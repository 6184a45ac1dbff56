#!/usr/bin/env bash
# Removes what Fast DDS processes killed by our tests leave in /dev/shm: zombie
# ports and segments (`fastdds shm clean`, which keeps those of live
# processes) and data-sharing segments that no running process has mapped.
# Run by ctest before and after the DDS tests; safe beside running DDS apps.
set -u
if command -v fastdds >/dev/null 2>&1; then
  fastdds shm clean >/dev/null 2>&1 || echo "fastdds shm clean failed (ignored)"
fi
shopt -s nullglob
removed=0
for segment in /dev/shm/fast_datasharing_*; do
  if ! grep -qsF "$segment" /proc/[0-9]*/maps; then
    rm -f "$segment" && removed=$((removed + 1))
  fi
done
echo "dds shared memory: $(ls /dev/shm | grep -c fast) Fast DDS files left, $removed unused data-sharing segments removed"
