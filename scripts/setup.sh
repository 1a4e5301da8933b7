#!/usr/bin/env bash
# Installs whatever the project needs that is missing (Debian 12 packages), then builds the
# catkin workspace in build/ws (or $SAP_WS), whose src/sap_broadphase mirrors this repository.
#
# The sources are mirrored (rsync, mtimes kept, so make rebuilds only what changed), not
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
  # Files rsync transfers get the current time: one edited while an earlier build compiled its
  # old copy would otherwise carry an mtime older than that object, and never be rebuilt.
  rsync -a --delete --out-format='%n' --exclude=/build/ --exclude=/.git/ --exclude=/artifacts/ \
    "$ROOT/" "$mirror/" | while IFS= read -r changed; do
    [ -f "$mirror/$changed" ] && touch "$mirror/$changed"
  done
  # Debian's ROS needs the system python, not a pyenv shim that may come first in PATH.
  export PYENV_VERSION=system
  catkin_make -C "$WS" -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -j"$(nproc)" "$@"
}

install_missing_packages
build_workspace "$@"
