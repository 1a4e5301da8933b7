#!/usr/bin/env bash
# Runs every rostest of the package (or the ones named) N times in a row on a loaded machine:
# K busy loops (one core's worth of spinning each) run beside the tests the whole time. A test
# that passes here once and fails on a slower or busier machine is a bug; this is how the
# project looks for such tests before CI does.
#
# Usage: scripts/rostest_repeat.sh [--runs N] [--busy K] [--out DIR] [TEST ...]
#   --runs N   runs of each test (default 20)
#   --busy K   busy loops beside the tests (default 2)
#   --out DIR  logs and the summary (default build/rostest_repeat)
#   TEST       names of test/ros/*.test without the extension (default: all of them)
# Each round runs every test once, in order; a failed run's log is kept as
# DIR/<test>_<round>.log. The summary (DIR/summary.txt) gives passes per test and the load.
# Needs the built workspace (scripts/setup.sh tests). Every process it starts is stopped by
# PID on exit; each rostest starts its own master on a free port (rostest's default).
# Exit status: 0 when every run passed, 1 otherwise.
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
runs=20
busy=2
out="$ROOT/build/rostest_repeat"
tests=()
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift ;;
    --busy) busy="$2"; shift ;;
    --out) out="$2"; shift ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    -*) echo "rostest_repeat.sh: unknown option $1" >&2; exit 2 ;;
    *) tests+=("$1") ;;
  esac
  shift
done
if [ ${#tests[@]} -eq 0 ]; then
  for file in "$ROOT"/test/ros/*.test; do tests+=("$(basename "$file" .test)"); done
fi
mkdir -p "$out"
out=$(cd "$out" && pwd)
source "$ROOT/scripts/env.sh"
source "$ROOT/scripts/processes.sh"
trap 'exit 130' INT TERM
# Results of this run only: rostest writes its XML under ROS_HOME, logs under ROS_LOG_DIR.
export ROS_HOME="$out/ros_home" ROS_LOG_DIR="$out/ros_log"
rm -rf "$ROS_HOME" "$ROS_LOG_DIR"
mkdir -p "$ROS_HOME" "$ROS_LOG_DIR"

for _ in $(seq "$busy"); do
  bash -c 'while :; do :; done' &
  PIDS+=($!)
done

declare -A passed
for test in "${tests[@]}"; do passed[$test]=0; done
summary="$out/summary.txt"
{
  echo "rostest_repeat.sh: $runs runs of ${#tests[@]} tests, $busy busy loops beside them"
  echo "commit: $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?')"
  echo "start: $(date -u +%FT%TZ), $(uptime)"
} >"$summary"
for round in $(seq "$runs"); do
  for test in "${tests[@]}"; do
    log="$out/${test}_${round}.log"
    start=$(date +%s)
    rc=0
    timeout -k 10 900 rostest sap_broadphase "$test.test" >"$log" 2>&1 || rc=$?
    # rostest's own verdict (without --text it reads every test's XML result): its exit
    # status and the RESULT line of its summary.
    if [ "$rc" -eq 0 ] && grep -q ' \* RESULT: SUCCESS' "$log"; then
      passed[$test]=$((passed[$test] + 1))
      rm -f "$log"
      verdict=pass
    else
      verdict="FAIL (exit $rc, log $log)"
    fi
    echo "round $round $test: $verdict, $(($(date +%s) - start)) s, load $(cut -d' ' -f1 /proc/loadavg)" |
      tee -a "$summary"
  done
done
echo "end: $(date -u +%FT%TZ)" >>"$summary"
status=0
for test in "${tests[@]}"; do
  echo "$test: ${passed[$test]} of $runs passed" | tee -a "$summary"
  [ "${passed[$test]}" -eq "$runs" ] || status=1
done
exit "$status"
