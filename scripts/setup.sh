#!/usr/bin/env bash
# Installs whatever the project needs that is missing (Debian 12 packages), then builds the
# catkin workspace in build/ws (or $SAP_WS), whose src/sap_broadphase mirrors this repository.
# Says what it did in one line ("setup: ..."); a check that finds nothing to do takes a second.
#
# The sources are mirrored (rsync by content, so make rebuilds only what changed), not
# symlinked: roslaunch searches a package's directory following links, and a link from
# build/ws/src back to the repository, which contains build/, would be an endless loop.
# Usage: scripts/setup.sh [extra catkin_make arguments, e.g. tests]
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WS="${SAP_WS:-$ROOT/build/ws}"
# The catkin_make arguments built since the mirror last changed, one line each: the same
# arguments on unchanged sources need no catkin_make.
BUILT="$WS/.sap_built_targets"

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

# Sets `missing` to the wanted packages dpkg does not list as installed (one dpkg-query).
find_missing_packages() {
  local wanted installed
  mapfile -t wanted < <(grep -v '^\s*#' "$ROOT/scripts/apt-packages.txt" | tr -s ' \n' '\n' |
    grep -v '^$')
  wanted_count=${#wanted[@]}
  # Unknown packages make dpkg-query fail; they are missing all the same.
  installed=$(dpkg-query -W -f='${Package} ${Status}\n' "${wanted[@]}" 2>/dev/null |
    awk '$NF == "installed" && $(NF-1) == "ok" {print $1}' || true)
  mapfile -t missing < <(printf '%s\n' "${wanted[@]}" | grep -vxF -f <(printf '%s\n' "$installed"))
}

install_missing_packages() {
  find_missing_packages
  if [ ${#missing[@]} -gt 0 ]; then
    echo "setup: installing ${missing[*]}"
    as_root apt-get update -q
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
  fi
}

# Mirrors the repository into the workspace; sets `changed` to the number of entries rsync
# created, updated or deleted.
mirror_sources() {
  mkdir -p "$WS/src"
  local mirror="$WS/src/sap_broadphase"
  [ -L "$mirror" ] && rm -f "$mirror"
  # Content decides what is copied (--checksum) and times are not preserved (no -t): a file
  # that changed gets the time of the copy, newer than any object built from its old content,
  # and an unchanged file keeps its time, so make rebuilds exactly what changed. Directories'
  # times are not compared (-O): only what rsync copies or deletes is itemized.
  local itemized
  itemized=$(rsync -rlpgoDO --checksum --delete --itemize-changes \
    --exclude=/build/ --exclude=/.git/ --exclude=/artifacts/ "$ROOT/" "$mirror/")
  changed=$(printf '%s' "$itemized" | grep -c . || true)
}

build_workspace() {
  local arguments="${*:-all}"
  if [ "$changed" -eq 0 ] && [ -f "$WS/devel/setup.bash" ] && [ -f "$BUILT" ] &&
     grep -qxF -- "$arguments" "$BUILT"; then
    echo "setup: $wanted_count packages installed, sources unchanged, '$arguments' built: nothing to do"
    return
  fi
  echo "setup: $wanted_count packages installed, $changed changed entries mirrored: catkin_make $arguments"
  [ "$changed" -eq 0 ] || rm -f "$BUILT"
  # Debian's ROS needs the system python, not a pyenv shim that may come first in PATH.
  export PYENV_VERSION=system
  catkin_make -C "$WS" -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -j"$(nproc)" "$@"
  echo "$arguments" >>"$BUILT"
}

install_missing_packages
mirror_sources
build_workspace "$@"
