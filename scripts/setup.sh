#!/usr/bin/env bash
# Installs whatever the project needs that is missing (Debian 12 packages), then builds the
# catkin workspace in build/ws (or $SAP_WS), whose src/sap_broadphase mirrors this repository.
#
# The sources are mirrored (rsync by content, so make rebuilds only what changed), not
# symlinked: roslaunch searches a package's directory following links, and a link from
# build/ws/src back to the repository, which contains build/, would be an endless loop.
# Usage: scripts/setup.sh [extra catkin_make arguments, e.g. tests]
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WS="${SAP_WS:-$ROOT/build/ws}"

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

install_missing_packages() {
  local wanted missing=()
  wanted=$(grep -v '^\s*#' "$ROOT/scripts/apt-packages.txt" | tr -s ' \n' ' ')
  for pkg in $wanted; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed' || missing+=("$pkg")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "setup: installing ${missing[*]}"
    as_root apt-get update -q
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
  fi
}

build_workspace() {
  mkdir -p "$WS/src"
  local mirror="$WS/src/sap_broadphase"
  [ -L "$mirror" ] && rm -f "$mirror"
  # Content decides what is copied (--checksum) and times are not preserved (no -t): a file
  # that changed gets the time of the copy, newer than any object built from its old content,
  # and an unchanged file keeps its time, so make rebuilds exactly what changed.
  rsync -rlpgoD --checksum --delete --exclude=/build/ --exclude=/.git/ --exclude=/artifacts/ \
    "$ROOT/" "$mirror/"
  # Debian's ROS needs the system python, not a pyenv shim that may come first in PATH.
  export PYENV_VERSION=system
  catkin_make -C "$WS" -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -j"$(nproc)" "$@"
}

install_missing_packages
build_workspace "$@"
