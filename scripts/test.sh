#!/usr/bin/env bash
# The test command: set-up if missing, build everything, run every test (GoogleTest for the
# core and CLI, rostest for the node), then build and test the engine once more without ROS
# (scripts/test_no_ros.sh), so that plain-CMake build cannot rot, and last `pip install .` in a
# fresh venv with the Python tests on what it installed (scripts/pip_check.sh). Exits non-zero
# when any test fails.
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh"
"$ROOT/scripts/setup.sh" tests
source "$ROOT/scripts/env.sh"
WS="${SAP_WS:-$ROOT/build/ws}"
rm -rf "$WS/build/test_results"
# Each rostest gets its own roscore on a loopback port chosen by rostest itself.
export ROS_MASTER_URI=http://127.0.0.1:11411
# Idle OpenMP threads sleep instead of spinning: a test machine is often shared, and spinning
# workers slow every parallel region by an order of magnitude when cores are oversubscribed.
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
catkin_make -C "$WS" run_tests -j1 -DPYTHON_EXECUTABLE=/usr/bin/python3 2>&1 | tee "$ROOT/build/test.log" | grep -E '^\[( RUN|  PASSED|  FAILED|  FAILED ) *\]|^\[ *(OK|FAILED) *\]|SUMMARY|FAILURE|ERROR' || true
# The fuzzers (ASan/UBSan, scripts/fuzz.sh) for a few seconds a target, from the seed corpus:
# each target's verdict is a test case; a build that fails is one failed case.
fuzz_junit="$WS/build/test_results/fuzz/fuzz.xml"
if ! "$ROOT/scripts/fuzz.sh" --seconds "${SAP_FUZZ_SECONDS:-8}" --junit "$fuzz_junit" \
     > "$ROOT/build/fuzz.log" 2>&1 && [ ! -f "$fuzz_junit" ]; then
  mkdir -p "$(dirname "$fuzz_junit")"
  echo '<?xml version="1.0"?><testsuite name="fuzz" tests="1" failures="1"><testcase classname="fuzz" name="build"><failure message="scripts/fuzz.sh failed before fuzzing: see build/fuzz.log"/></testcase></testsuite>' > "$fuzz_junit"
fi
grep -E '^fuzz.sh: fuzz_' "$ROOT/build/fuzz.log" || true
set +e
summary=$(catkin_test_results --verbose "$WS/build/test_results")
status=$?
set -e
echo "$summary" | tail -n 40
read -r total failed skipped < <(python3 "$ROOT/scripts/junit_summary.py" "$WS/build/test_results")
if [ "$total" -eq 0 ]; then echo "no test ran"; exit 1; fi
# The count and catkin_test_results (the exit status) must agree: a failure the count missed
# (a result file it could not read as a failure) is still one.
if [ "$status" -ne 0 ] && [ "$failed" -eq 0 ]; then
  echo "catkin_test_results reports a failure that the count missed, see its output above"
  failed=1
fi
echo "tests (catkin): $((total - failed - skipped)) passed, $failed failed, $skipped skipped"

# The same engine, CLI tools, benchmarks and ROS-free tests with plain CMake, no catkin.
set +e
"$ROOT/scripts/test_no_ros.sh" "$ROOT/build/no_ros" > "$ROOT/build/test_no_ros.log" 2>&1
no_ros_status=$?
set -e
grep -E '^ *[0-9]+/[0-9]+ Test|tests passed|tests without ROS|test_no_ros:' \
  "$ROOT/build/test_no_ros.log" || true
read -r no_ros_total no_ros_failed no_ros_skipped < <(python3 "$ROOT/scripts/junit_summary.py" \
  "$ROOT/build/no_ros/test_results")
if [ "$no_ros_status" -ne 0 ] && [ "$no_ros_failed" -eq 0 ]; then
  echo "scripts/test_no_ros.sh failed outside the tests, see build/test_no_ros.log"
  no_ros_failed=1
fi
total=$((total + no_ros_total))
failed=$((failed + no_ros_failed))
skipped=$((skipped + no_ros_skipped))

# `pip install .` in a fresh venv, then the Python tests against what it installed.
set +e
"$ROOT/scripts/pip_check.sh" "$ROOT/build/pip_check" > "$ROOT/build/pip_check.log" 2>&1
pip_status=$?
set -e
read -r pip_total pip_failed pip_skipped < <(python3 "$ROOT/scripts/junit_summary.py" \
  "$ROOT/build/pip_check/test_results")
echo "pip install and its Python tests: $((pip_total - pip_failed - pip_skipped)) passed, $pip_failed failed (build/pip_check.log)"
if [ "$pip_status" -ne 0 ] && [ "$pip_failed" -eq 0 ]; then
  echo "scripts/pip_check.sh failed outside the tests, see build/pip_check.log"
  pip_failed=1
fi
total=$((total + pip_total))
failed=$((failed + pip_failed))
skipped=$((skipped + pip_skipped))
echo "tests: $((total - failed - skipped)) passed, $failed failed, $skipped skipped"
# The last line and the exit status say the same: non-zero exactly when a failure is counted.
[ "$failed" -eq 0 ] && [ "$status" -eq 0 ] && [ "$no_ros_status" -eq 0 ] && [ "$pip_status" -eq 0 ]
