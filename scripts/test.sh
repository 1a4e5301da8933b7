#!/usr/bin/env bash
# The test command: set-up if missing, build everything, run every test (GoogleTest for the
# core and CLI, rostest for the node). Exits non-zero when any test fails.
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
set +e
summary=$(catkin_test_results --verbose "$WS/build/test_results")
status=$?
set -e
echo "$summary" | tail -n 40
# Count test cases from the JUnit files for a plain closing line.
read -r total failed skipped < <(python3 - "$WS/build/test_results" <<'PY'
import sys, pathlib, xml.etree.ElementTree as ET
total = failed = skipped = 0
for path in pathlib.Path(sys.argv[1]).rglob("*.xml"):
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError:
        failed += 1; total += 1; continue
    for case in root.iter("testcase"):
        total += 1
        if case.find("failure") is not None or case.find("error") is not None: failed += 1
        elif case.find("skipped") is not None: skipped += 1
print(total, failed, skipped)
PY
)
passed=$((total - failed - skipped))
if [ "$total" -eq 0 ]; then echo "no test ran"; exit 1; fi
echo "tests: $passed passed, $failed failed, $skipped skipped"
exit $status
