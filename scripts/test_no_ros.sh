#!/usr/bin/env bash
# The engine without ROS: builds the core library, the CLI tools, the Python module, the
# benchmarks and the ROS-free tests with plain CMake (-DSAP_BUILD_ROS=OFF, so no catkin is
# needed or used; tests and benchmarks are options, -DSAP_BUILD_TESTS=ON
# -DSAP_BUILD_BENCHMARKS=ON, off in a consumer's plain build), runs
# the tests, installs the engine, builds examples/find_package against the installed package
# config (find_package(sap_broadphase_core)) and checks the README and docs/ (links, commands,
# the C++ example, the benchmarks' CSVs, the engine's import rule: scripts/check_docs.py),
# smoke-runs every benchmark (scripts/bench.sh --quick), and runs the core tests a second time with the
# engine's invariants checked (-DSAP_ASSERTS=ON, in BUILD_DIR/asserts). Exits non-zero when
# anything fails.
#
# Needs only a C++17 compiler with OpenMP, CMake >= 3.16, GoogleTest and, for sap_microbench,
# Google Benchmark (Debian 12: g++ cmake make libgtest-dev libbenchmark-dev).
# Usage: scripts/test_no_ros.sh [BUILD_DIR]   (default build/no_ros; $SAP_JOBS parallel jobs)
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=$(mkdir -p "${1:-$ROOT/build/no_ros}" && cd "${1:-$ROOT/build/no_ros}" && pwd)
JOBS="${SAP_JOBS:-$(nproc)}"
PREFIX="$BUILD/install"
# libgomp's threads spin while waiting by default; on shared cores that slows everything.
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"

cmake -S "$ROOT" -B "$BUILD" -DSAP_BUILD_ROS=OFF -DCMAKE_BUILD_TYPE=Release \
  -DSAP_BUILD_TESTS=ON -DSAP_BUILD_BENCHMARKS=ON -DCMAKE_INSTALL_PREFIX="$PREFIX"
cmake --build "$BUILD" -j"$JOBS"

rm -rf "$BUILD/test_results"
set +e
(cd "$BUILD" && ctest --output-on-failure)
test_status=$?
set -e

# The core tests once more with the engine's invariants checked (SAP_ASSERT, -DSAP_ASSERTS=ON):
# a second build of only the core test targets, optimised as the first, so that the asserted
# run adds minutes, not the whole suite. Its JUnit files join the count below.
ASSERTS_BUILD="$BUILD/asserts"
ASSERTED_TESTS=(test_core test_engine test_skin_list test_frame_flow test_static_index test_query
  test_cli)
cmake -S "$ROOT" -B "$ASSERTS_BUILD" -DSAP_BUILD_ROS=OFF -DCMAKE_BUILD_TYPE=Release \
  -DSAP_BUILD_TESTS=ON -DSAP_ASSERTS=ON > /dev/null
cmake --build "$ASSERTS_BUILD" -j"$JOBS" --target "${ASSERTED_TESTS[@]}"
rm -rf "$ASSERTS_BUILD/test_results"
set +e
(cd "$ASSERTS_BUILD" &&
  ctest --output-on-failure -R "^($(IFS='|'; echo "${ASSERTED_TESTS[*]}"))\$")
asserts_status=$?
set -e
mkdir -p "$BUILD/test_results/asserts"
cp "$ASSERTS_BUILD"/test_results/*.xml "$BUILD/test_results/asserts/" 2>/dev/null || true
echo "test_no_ros: core tests with SAP_ASSERTS: $([ $asserts_status -eq 0 ] && echo passed || echo FAILED)"
if [ "$test_status" -eq 0 ]; then test_status=$asserts_status; fi

# The installed package: only the API headers, and a project of its own can use it.
rm -rf "$PREFIX"
cmake --install "$BUILD" > /dev/null
internal=$(find "$PREFIX/include" -type f ! -path "$PREFIX/include/sap_broadphase/core/*")
if [ -n "$internal" ]; then
  echo "test_no_ros: installed headers outside sap_broadphase/core/: $internal" >&2
  exit 1
fi
cmake -S "$ROOT/examples/find_package" -B "$BUILD/example" -DCMAKE_PREFIX_PATH="$PREFIX" \
  > /dev/null
cmake --build "$BUILD/example" > /dev/null
"$BUILD/example/broadphase_example"
echo "test_no_ros: examples/find_package built against $PREFIX and ran"
python3 "$ROOT/scripts/check_docs.py" --bin "$BUILD"

# Every benchmark at its smallest size, with this build's tools, so that no experiment rots
# (scripts/bench.sh --quick: a smoke test, its figures not read); one JUnit case.
bench_junit="$BUILD/test_results/bench_quick.xml"
mkdir -p "$BUILD/test_results"
if "$ROOT/scripts/bench.sh" --quick --bin "$BUILD" --out "$BUILD/bench_quick" \
    > "$BUILD/bench_quick.log" 2>&1; then
  echo '<?xml version="1.0"?><testsuite name="bench" tests="1" failures="0"><testcase classname="bench" name="quick"/></testsuite>' > "$bench_junit"
  echo "test_no_ros: scripts/bench.sh --quick ran every experiment"
else
  echo '<?xml version="1.0"?><testsuite name="bench" tests="1" failures="1"><testcase classname="bench" name="quick"><failure message="scripts/bench.sh --quick failed: see bench_quick.log in the build folder"/></testcase></testsuite>' > "$bench_junit"
  echo "test_no_ros: scripts/bench.sh --quick FAILED, see $BUILD/bench_quick.log" >&2
  test_status=1
fi

# Count test cases from the JUnit files, as scripts/test.sh does for the catkin build.
read -r total failed skipped < <(python3 "$ROOT/scripts/junit_summary.py" "$BUILD/test_results")
if [ "$total" -eq 0 ]; then echo "test_no_ros: no test ran"; exit 1; fi
echo "tests without ROS: $((total - failed - skipped)) passed, $failed failed, $skipped skipped"
exit $test_status
