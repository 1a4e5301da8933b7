#!/usr/bin/env bash
# Builds and runs the tests under sanitizers, each in its own catkin workspace:
#
#   build/ws_asan  g++ -fsanitize=address,undefined,float-cast-overflow (no recovery): the core,
#                  CLI, ROS-unit, stress and fuzz-replay gtests (test_core test_engine test_cli
#                  test_ros_units test_stress test_fuzz_replay test_fuzz_replay_ros)
#   build/ws_tsan  clang++ -fsanitize=thread with LLVM's libomp and its Archer tool, so that
#                  OpenMP barriers are visible to TSan: the node's threading rostest
#                  (test/ros/node.test: worker thread, service thread, burst) and the engine
#                  at several thread counts (test_stress: sequence, infinity, filter and skip
#                  suites)
#
#   scripts/sanitize.sh            # both
#   scripts/sanitize.sh asan       # or: tsan
#   SANITIZE_REV=HEAD scripts/sanitize.sh   # a committed tree instead of the working tree
#
# Prints one line per test binary and a summary; exits non-zero on any finding. Reports stay
# in build/sanitize/. Until test/tests.cmake includes test/stress/stress_tests.cmake, the
# workspaces' mirrors get that line appended (the mirror is a build artifact; the repository
# is not touched).
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
REPORTS="$ROOT/build/sanitize"
SUPP="$ROOT/test/stress/sanitizers"
WHAT=${1:-all}
JOBS=${SANITIZE_JOBS:-2}
export PYENV_VERSION=system
mkdir -p "$REPORTS"
failures=0

mirror() {  # workspace
  local ws=$1
  mkdir -p "$ws/src"
  if [ -n "${SANITIZE_REV:-}" ]; then
    # A committed tree (e.g. SANITIZE_REV=HEAD while others edit the working tree).
    local staging="$ws/src/.sap_broadphase_rev"
    rm -rf "$staging" && mkdir -p "$staging"
    git -C "$ROOT" archive "$SANITIZE_REV" | tar -x -C "$staging"
    rsync -a --delete --checksum "$staging/" "$ws/src/sap_broadphase/"
    rm -rf "$staging"
  else
    rsync -a --delete --exclude=/build/ --exclude=/.git/ --exclude=/artifacts/ "$ROOT/" \
      "$ws/src/sap_broadphase/"
  fi
  local tests="$ws/src/sap_broadphase/test/tests.cmake"
  grep -q 'stress_tests.cmake' "$tests" || echo 'include(test/stress/stress_tests.cmake)' >> "$tests"
}

run_gtest() {  # label binary [args...]
  local label=$1 binary=$2; shift 2
  local log="$REPORTS/$label.log" start=$SECONDS
  if "$binary" "$@" > "$log" 2>&1 && ! grep -qE 'ERROR: (Address|Leak|Thread)Sanitizer|runtime error:|WARNING: ThreadSanitizer' "$log"; then
    echo "sanitize: $label clean ($(grep -oE '[0-9]+ tests? from [0-9]+ test suites? ran' "$log" | tail -1), $((SECONDS - start)) s)"
  else
    failures=$((failures + 1))
    echo "sanitize: $label FAILED (log $log):"
    grep -E 'ERROR: |SUMMARY: |runtime error:|WARNING: ThreadSanitizer|\[  FAILED  \]' "$log" | head -15
  fi
}

asan() {
  local ws="$ROOT/build/ws_asan"
  local flags="-fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer -g -O1"
  mirror "$ws"
  echo "sanitize: building ASan+UBSan workspace $ws"
  catkin_make -C "$ws" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" -DCATKIN_ENABLE_TESTING=ON \
    -j"$JOBS" test_core test_engine test_cli test_ros_units test_stress test_fuzz_replay \
    test_fuzz_replay_ros > "$REPORTS/asan_build.log" 2>&1 ||
    { echo "sanitize: ASan build failed (log $REPORTS/asan_build.log)"; tail -20 "$REPORTS/asan_build.log"; return 1; }
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
  export LSAN_OPTIONS="suppressions=$SUPP/lsan.supp:print_suppressions=0"
  export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
  export OMP_WAIT_POLICY=passive
  local bin="$ws/devel/lib/sap_broadphase"
  for test in test_core test_engine test_cli test_ros_units test_stress test_fuzz_replay \
              test_fuzz_replay_ros; do
    run_gtest "asan_$test" "$bin/$test"
  done
  unset ASAN_OPTIONS LSAN_OPTIONS UBSAN_OPTIONS
}

tsan() {
  local ws="$ROOT/build/ws_tsan"
  local archer=/usr/lib/llvm-14/lib/libarcher.so
  [ -f "$archer" ] || { echo "sanitize: $archer missing (apt-get install libomp-14-dev)"; return 1; }
  mirror "$ws"
  echo "sanitize: building TSan workspace $ws (clang++, libomp + Archer)"
  catkin_make -C "$ws" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_CXX_FLAGS="-fsanitize=thread -g -O1" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=thread" \
    -DCATKIN_ENABLE_TESTING=ON -j"$JOBS" sap_broadphase_node test_node test_stress \
    > "$REPORTS/tsan_build.log" 2>&1 ||
    { echo "sanitize: TSan build failed (log $REPORTS/tsan_build.log)"; tail -20 "$REPORTS/tsan_build.log"; return 1; }
  rm -f "$REPORTS"/tsan_report.*
  # Archer tells TSan about OpenMP's barriers and tasks (without it every parallel region
  # reports false races); ignore_noninstrumented_modules skips accesses made inside the
  # uninstrumented ROS and boost libraries.
  export OMP_TOOL_LIBRARIES="$archer"
  export ARCHER_OPTIONS="verbose=0"
  export TSAN_OPTIONS="suppressions=$SUPP/tsan.supp:ignore_noninstrumented_modules=1:halt_on_error=0:second_deadlock_stack=1:history_size=4"
  export OMP_WAIT_POLICY=passive
  run_gtest tsan_test_stress "$ws/devel/lib/sap_broadphase/test_stress" \
    --gtest_filter='StressSequence.*:StressInfinity.*:StressDegenerate.GroupsAndMasks:StressSkips.*'
  # The node's rostest: every node process writes its TSan reports to tsan_report.<pid>.
  (
    set +u
    source "$ws/devel/setup.bash"
    export ROS_IP=127.0.0.1 ROS_HOSTNAME=127.0.0.1
    export TSAN_OPTIONS="$TSAN_OPTIONS:log_path=$REPORTS/tsan_report"
    rostest --text sap_broadphase node.test > "$REPORTS/tsan_node.log" 2>&1
  ) && node_ok=1 || node_ok=0
  if [ "$node_ok" = 1 ] && ! ls "$REPORTS"/tsan_report.* >/dev/null 2>&1; then
    echo "sanitize: tsan_node.test clean ($(grep -oE 'PASSED.*' "$REPORTS/tsan_node.log" | head -1))"
  else
    failures=$((failures + 1))
    echo "sanitize: tsan_node.test FAILED (rostest exit $node_ok, log $REPORTS/tsan_node.log)"
    cat "$REPORTS"/tsan_report.* 2>/dev/null | grep -E 'WARNING|SUMMARY|#[0-3] ' | head -30
  fi
  unset OMP_TOOL_LIBRARIES TSAN_OPTIONS
}

case "$WHAT" in
  asan) asan || failures=$((failures + 1)) ;;
  tsan) tsan || failures=$((failures + 1)) ;;
  all) asan || failures=$((failures + 1)); tsan || failures=$((failures + 1)) ;;
  *) echo "usage: scripts/sanitize.sh [all|asan|tsan]" >&2; exit 2 ;;
esac
if [ "$failures" -eq 0 ]; then echo "sanitize: all clean"; else echo "sanitize: $failures finding(s)"; fi
[ "$failures" -eq 0 ]
