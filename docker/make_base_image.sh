#!/usr/bin/env bash
# Builds the Debian 12 base image structloc-base:bookworm without a registry:
# debootstrap a minimal bookworm and import it into the local Docker engine.
# Needs root, debootstrap and a running dockerd.
set -euo pipefail
root="$(mktemp -d)"
trap 'rm -rf "$root"' EXIT
debootstrap --variant=minbase bookworm "$root"
tar -C "$root" -c . | docker import - structloc-base:bookworm
echo "imported structloc-base:bookworm"
