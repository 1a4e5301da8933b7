#!/usr/bin/env bash
# Builds the libFuzzer targets (clang++ with -fsanitize=fuzzer,address,undefined) and runs each
# for a bounded number of inputs or seconds, starting from the seed corpus in fuzz/corpus/.
#
#   scripts/fuzz.sh                       # 20000 runs per target
#   scripts/fuzz.sh --runs 100000
#   scripts/fuzz.sh --seconds 120         # per target
#   scripts/fuzz.sh --target text         # one target: text, boxset, box_array, sequence, wire or settings
#   scripts/fuzz.sh --save                # merge new coverage into fuzz/corpus/ afterwards
#   scripts/fuzz.sh --junit FILE          # also write each target's verdict as a JUnit test case
#
# Targets: fuzz_text (readBoxText, round trip, engine vs oracle), fuzz_boxset (validate() on
# raw box sets, engine vs oracle), fuzz_box_array (BoxArray deserialization and the ROS
# conversions, engine vs oracle), fuzz_sequence (the input picks a configuration, with every
# skip switchable, and the edits between frames; one engine, every frame vs the oracle,
# fuzz/sequence_checks.h), fuzz_wire (every type the node reads from the wire, arbitrary,
# truncated and lying bytes through WireLayout and roscpp, fuzz/wire_checks.h), fuzz_settings
# (every value of any kind through the engine's field table as rosparam, reconfigure requests
# and Python carry them, and every row of the limits table, fuzz/settings_checks.h). The ROS
# message headers are generated here with gencpp, so
# no catkin workspace is needed. Crashes land in build/fuzz/crashes/; copy each one into
# fuzz/regressions/<target>/ so that test_fuzz_replay (test/stress) replays it for ever.
# Exits non-zero when a target finds a crash.
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT="$ROOT/build/fuzz"
RUNS=20000
SECONDS_PER_TARGET=""
TARGETS=(text boxset box_array sequence wire settings)
SAVE=0
JUNIT=""
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) RUNS="$2"; shift 2 ;;
    --seconds) SECONDS_PER_TARGET="$2"; shift 2 ;;
    --target) TARGETS=("$2"); shift 2 ;;
    --save) SAVE=1; shift ;;
    --junit) JUNIT="$2"; shift 2 ;;
    -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
    *) echo "fuzz.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done

CXX=${CXX_FUZZ:-clang++}
command -v "$CXX" >/dev/null || { echo "fuzz.sh: $CXX not found (apt-get install clang libclang-rt-dev libomp-dev)" >&2; exit 2; }
SAN="-fsanitize=address,undefined -fno-sanitize-recover=undefined"
FLAGS="-std=c++17 -O1 -g -fno-omit-frame-pointer -fopenmp -Wall -Wextra $SAN"
INCLUDES="-I$ROOT/include -I$ROOT/src -I$ROOT/src/ros -I$ROOT/fuzz -I$ROOT/test/stress -I$OUT/gen"
FLAGS="$FLAGS -DSAP_ADAPTERS_MSGS_DIR=\"$ROOT/src/ros/adapters_msgs\""
mkdir -p "$OUT/obj" "$OUT/gen/sap_broadphase" "$OUT/crashes"

# ROS message and service headers straight from the .msg and .srv files (Debian's gencpp).
for spec in msg/BoxArray.msg msg/PairArray.msg srv/ComputePairs.srv srv/QueryBoxes.srv; do
  header="$OUT/gen/sap_broadphase/$(basename "${spec%.*}").h"
  if [ ! -f "$header" ] || [ "$ROOT/$spec" -nt "$header" ]; then
    PYENV_VERSION=system /usr/bin/python3 /usr/lib/gencpp/gen_cpp.py "$ROOT/$spec" \
      -Isap_broadphase:"$ROOT/msg" -Istd_msgs:/usr/share/std_msgs/msg -p sap_broadphase \
      -o "$OUT/gen/sap_broadphase" -e /usr/share/gencpp >/dev/null
  fi
done
if [ ! -f "$OUT/gen/sap_broadphase/ComputePairs.h" ] || [ "$ROOT/srv/ComputePairs.srv" -nt "$OUT/gen/sap_broadphase/ComputePairs.h" ]; then
  PYENV_VERSION=system /usr/bin/python3 /usr/lib/gencpp/gen_cpp.py "$ROOT/srv/ComputePairs.srv" \
    -Isap_broadphase:"$ROOT/msg" -Istd_msgs:/usr/share/std_msgs/msg -p sap_broadphase \
    -o "$OUT/gen/sap_broadphase" -e /usr/share/gencpp >/dev/null
fi

# Objects: instrumented for coverage (fuzzer-no-link) and the sanitizers; rebuilt when older
# than their source or any header.
newest_header=$(find "$ROOT/include" "$ROOT/src" "$ROOT/fuzz" "$ROOT/test/stress" -name '*.h' \
  -printf '%T@\n' | sort -n | tail -1)
compile() {  # source object
  local src=$1 obj=$2
  if [ ! -f "$obj" ] || [ "$src" -nt "$obj" ] || \
     [ "$(stat -c %Y "$obj")" -lt "${newest_header%.*}" ]; then
    echo "fuzz.sh: compiling ${src#$ROOT/}"
    $CXX $FLAGS -fsanitize=fuzzer-no-link $INCLUDES -c "$src" -o "$obj"
  fi
}
export -f compile
export CXX FLAGS INCLUDES ROOT newest_header
sources=("$ROOT"/src/core/*.cpp "$ROOT/src/ros/conversions.cpp" "$ROOT/fuzz/fuzz_checks.cpp" \
         "$ROOT/fuzz/box_array_checks.cpp" "$ROOT/fuzz/sequence_checks.cpp" \
         "$ROOT/fuzz/wire_checks.cpp" "$ROOT/src/ros/wire_layout.cpp" \
         "$ROOT/fuzz/settings_checks.cpp" \
         "$ROOT/test/stress/stress_sequences.cpp" "$ROOT"/fuzz/fuzz_*.cpp)
for src in "${sources[@]}"; do echo "$src $OUT/obj/$(basename "$src" .cpp).o"; done | \
  xargs -P2 -n2 bash -c 'compile "$0" "$1"'

core_objs=()
for src in "$ROOT"/src/core/*.cpp; do core_objs+=("$OUT/obj/$(basename "$src" .cpp).o"); done
link() {  # target extra-objects... extra-libs
  local target=$1; shift
  $CXX $FLAGS -fsanitize=fuzzer -o "$OUT/fuzz_$target" "$OUT/obj/fuzz_$target.o" \
    "$OUT/obj/fuzz_checks.o" "$OUT/obj/stress_sequences.o" "${core_objs[@]}" "$@"
}
link text
link boxset
link box_array "$OUT/obj/box_array_checks.o" "$OUT/obj/conversions.o" \
  -lroscpp_serialization -lrostime -lcpp_common
link sequence "$OUT/obj/sequence_checks.o"
link wire "$OUT/obj/wire_checks.o" "$OUT/obj/wire_layout.o" -lroscpp_serialization -lrostime \
  -lcpp_common
link settings "$OUT/obj/settings_checks.o"

# Runs: ASan must not abort on allocations it cannot serve (roscpp-style bad_alloc is
# handled by the targets); OpenMP threads wait passively on this small machine.
export ASAN_OPTIONS="allocator_may_return_null=1:detect_leaks=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"
export OMP_WAIT_POLICY=passive
status=0
cases=""
for target in "${TARGETS[@]}"; do
  work="$OUT/corpus/$target"
  mkdir -p "$work"
  cp -n "$ROOT/fuzz/corpus/$target"/* "$work/" 2>/dev/null || true
  limit=(-runs="$RUNS")
  [ -n "$SECONDS_PER_TARGET" ] && limit=(-max_total_time="$SECONDS_PER_TARGET")
  dict=()
  [ "$target" = text ] && dict=(-dict="$ROOT/fuzz/text.dict")
  echo "fuzz.sh: fuzz_$target ${limit[*]} (corpus $(ls "$work" | wc -l) files)"
  start=$(date +%s)
  if "$OUT/fuzz_$target" "${limit[@]}" "${dict[@]}" -max_len=4096 -rss_limit_mb=2048 \
       -artifact_prefix="$OUT/crashes/$target-" -print_final_stats=1 "$work" \
       > "$OUT/$target.log" 2>&1; then
    cases+="<testcase classname=\"fuzz\" name=\"fuzz_$target\"/>"
    echo "fuzz.sh: fuzz_$target clean: $(grep -E '^stat::number_of_executed_units' "$OUT/$target.log" | awk '{print $2}') inputs in $(( $(date +%s) - start )) s, corpus $(ls "$work" | wc -l) files, $(grep -oE 'cov: [0-9]+' "$OUT/$target.log" | tail -1)"
  else
    status=1
    cases+="<testcase classname=\"fuzz\" name=\"fuzz_$target\"><failure message=\"fuzz_$target found a problem: $OUT/$target.log\"/></testcase>"
    echo "fuzz.sh: fuzz_$target FOUND A PROBLEM (log $OUT/$target.log):"
    grep -E 'ERROR|fuzz_|SUMMARY|Test unit written' "$OUT/$target.log" | head -20
  fi
  if [ "$SAVE" = 1 ]; then
    "$OUT/fuzz_$target" -merge=1 "$ROOT/fuzz/corpus/$target" "$work" >/dev/null 2>&1 || true
  fi
done
if [ -n "$JUNIT" ]; then
  mkdir -p "$(dirname "$JUNIT")"
  printf '<?xml version="1.0"?>\n<testsuite name="fuzz" tests="%d" failures="%d">%s</testsuite>\n' \
    "${#TARGETS[@]}" "$(grep -o '<failure' <<<"$cases" | wc -l)" "$cases" > "$JUNIT"
fi
exit $status
