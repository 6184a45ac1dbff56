#!/usr/bin/env bash
# Builds the image structloc:latest (or TAG) from a build tree: installs it
# into a staging folder, lists the Debian packages that hold the libraries its
# executables link (ldd + dpkg -S, so the image has what the build linked and
# nothing else), copies this host's apt sources (same package versions), makes
# the base image if the engine lacks it, and runs docker build (host network:
# apt reaches Debian's archive without Docker's NAT rules).
# Usage: docker/build_image.sh BUILD_DIR [TAG]; uses DOCKER_HOST if set.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build_dir="$(cd "$1" && pwd)"
tag="${2:-structloc:latest}"
stage="$(mktemp -d)"
trap 'rm -rf "$stage"' EXIT

cmake --install "$build_dir" --prefix "$stage/prefix" >/dev/null
rm -rf "$stage/prefix/include" "$stage/prefix/lib"  # headers and static libraries: not run
# Scripts (structloc_keystore) link nothing: ldd is asked about programs only.
for f in "$stage"/prefix/bin/*; do
  if ldd "$f" >/dev/null 2>&1; then ldd "$f"; fi
done | awk '$3 ~ /^\// { print $3 }' | sort -u |
  while read -r library; do
    real="$(readlink -f "$library")"
    for candidate in "$library" "$real" "${library#/usr}" "/usr$library" "${real#/usr}"; do
      if owner="$(dpkg -S "$candidate" 2>/dev/null)"; then
        echo "${owner%%:*}"
        break
      fi
    done
  done | sort -u >"$stage/runtime-packages.txt"
echo "fastdds-tools" >>"$stage/runtime-packages.txt" # the discovery server
if [ -f /etc/apt/sources.list.d/debian.sources ]; then
  cp /etc/apt/sources.list.d/debian.sources "$stage/debian.sources"
else
  printf 'Types: deb\nURIs: http://deb.debian.org/debian\nSuites: bookworm bookworm-updates\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
    >"$stage/debian.sources"
fi
cp "$here/Dockerfile" "$stage/Dockerfile"
if ! docker image inspect structloc-base:bookworm >/dev/null 2>&1; then
  "$here/make_base_image.sh"
fi
echo "build_image: $(wc -l <"$stage/runtime-packages.txt") Debian packages for the runtime"
docker build --network host -q -t "$tag" "$stage"
echo "build_image: built $tag"
