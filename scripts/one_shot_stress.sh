#!/usr/bin/env bash
# No message lost at connection, at the target's count: test/ros/one_shot.test with 50 one-shot
# publishers of each source type (one_shot_sources_50.yaml), optionally beside busy loops that
# load the machine. The test command runs the same test with 20 a type; this one takes some
# 10 to 20 minutes, so it runs on request (docs/ROBUSTNESS.md, "No message lost at connection").
#
#   scripts/one_shot_stress.sh              # 50 trials a type
#   scripts/one_shot_stress.sh --busy 2     # beside two `yes > /dev/null` loops (stopped by PID)
#   scripts/one_shot_stress.sh --trials 30
#
# Needs the workspace built (scripts/setup.sh sap_broadphase_node sap_broadphase_python
# sap_broadphase_generate_messages_py). Prints the lost trials and the wall time; exits non-zero
# when a message was lost or the test failed.
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
TRIALS=50
BUSY=0
while [ $# -gt 0 ]; do
  case "$1" in
    --trials) TRIALS="$2"; shift 2 ;;
    --busy) BUSY="$2"; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    *) echo "one_shot_stress.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
# shellcheck disable=SC1091
source "$ROOT/scripts/env.sh"
LOG_DIR="$ROOT/build/one_shot_stress"
mkdir -p "$LOG_DIR"
busy=()
stop_busy() { for pid in "${busy[@]}"; do kill "$pid" 2>/dev/null || true; done; }
trap stop_busy EXIT
for _ in $(seq 1 "$BUSY"); do
  yes > /dev/null &
  busy+=($!)
done
start=$SECONDS
status=0
# The test's time limit: 60 s a round of five publishers (about 18 s a round beside two busy
# loops on a loaded 2-core machine), so that a slow machine fails only for a lost message.
rostest --text sap_broadphase one_shot.test trials:="$TRIALS" time_limit:=$((60 * TRIALS)) \
  sources:="$ROOT/test/ros/one_shot_sources_50.yaml" > "$LOG_DIR/rostest.log" 2>&1 || status=1
wall=$((SECONDS - start))
stop_busy
busy=()
reached=$(grep -c ': reached' "$LOG_DIR/rostest.log" || true)
lost=$(grep -c ': LOST' "$LOG_DIR/rostest.log" || true)
grep -q 'RESULT: SUCCESS' "$LOG_DIR/rostest.log" || status=1
echo "one_shot_stress: $TRIALS trials a type, $BUSY busy loops: $reached reached, $lost lost, ${wall} s (log $LOG_DIR/rostest.log)"
grep ': LOST' "$LOG_DIR/rostest.log" | sed 's/.*\]: /  /' || true
exit $status
