#!/usr/bin/env bash
# Builds the engine of one commit (or of the working tree) as a shared library that
# ab_compare loads, with the flags of the CMake Release build (-O3, OpenMP):
#
#   bench/micro/ab/ab_build.sh 31bb4fc build/ab/old.so     # a commit
#   bench/micro/ab/ab_build.sh worktree build/ab/new.so    # the working tree
#   bench/micro/ab/ab_build.sh driver build/ab/ab_compare  # the driver, linked with the scenes
#                                                         # of build/core's engine (AB_CORE_LIB)
#
# Symbols are bound inside each library (-Bsymbolic, no semantic interposition), so two builds
# of the engine live side by side in one process, each inlined as in a static build.
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
REV=$1
OUT=$2
[ -n "$REV" ] && [ -n "$OUT" ] || { echo "usage: ab_build.sh COMMIT|worktree OUT.so" >&2; exit 2; }
CXX=${CXX:-g++}
if [ "$REV" = driver ]; then
  # The scenes come from a static build of the engine (they are the same every commit); the
  # engines under test only through the libraries.
  CORE=${AB_CORE_LIB:-$ROOT/build/core/libsap_broadphase_core.a}
  mkdir -p "$(dirname "$OUT")"
  $CXX -O2 -std=c++17 -fopenmp -I"$ROOT/include" -I"$ROOT/src" "$ROOT/bench/micro/ab/ab_compare.cpp" \
    "$CORE" -ldl -o "$OUT"
  echo "ab_build: $OUT"
  exit 0
fi
SRC=$(mktemp -d)
OBJ=$(mktemp -d)
trap 'rm -rf "$SRC" "$OBJ"' EXIT
if [ "$REV" = worktree ]; then
  cp -r "$ROOT/include" "$ROOT/src" "$SRC/"
else
  git -C "$ROOT" archive "$REV" include src | tar -x -C "$SRC"
fi
LAUNCH=$(command -v ccache || true)
for file in "$SRC"/src/core/*.cpp "$ROOT/bench/micro/ab/ab_engine.cpp"; do
  echo "$LAUNCH $CXX -O3 -DNDEBUG -std=c++17 -fopenmp -fPIC -fno-semantic-interposition" \
    "-I$SRC/include -I$SRC/src -c $file -o $OBJ/$(basename "$file").o"
done | xargs -P "${AB_JOBS:-2}" -I{} sh -c '{}'
mkdir -p "$(dirname "$OUT")"
$CXX -shared -fopenmp -Wl,-Bsymbolic "$OBJ"/*.o -o "$OUT"
echo "ab_build: $OUT from $REV"
