#!/usr/bin/env bash
# The demo: set-up if missing, then a roscore on loopback, scene_publisher feeding boxes to the
# node for a bounded time, one line per frame (boxes, pairs, milliseconds). Stops everything it
# started, by PID, when it ends or is interrupted.
# Usage: scripts/demo.sh [--seconds S] [--scene uniform|ball|plane] [--boxes N] [--rate HZ]
#                        [--threads T] [--rviz]
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
SECONDS_TO_RUN=${DEMO_SECONDS:-20}
SCENE=uniform BOXES=10000 RATE=10 THREADS=0 RVIZ=0
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) SECONDS_TO_RUN=$2; shift 2 ;;
    --scene) SCENE=$2; shift 2 ;;
    --boxes) BOXES=$2; shift 2 ;;
    --rate) RATE=$2; shift 2 ;;
    --threads) THREADS=$2; shift 2 ;;
    --rviz) RVIZ=1; shift ;;
    -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
    *) echo "demo: unknown argument '$1' (try --help)" >&2; exit 2 ;;
  esac
done

mkdir -p "$ROOT/build"
echo "demo: set-up check: packages, sources mirrored, build (first run: several minutes;" \
  "log in build/demo_setup.log)"
"$ROOT/scripts/setup.sh" >"$ROOT/build/demo_setup.log" 2>&1 || {
  tail -n 20 "$ROOT/build/demo_setup.log" >&2
  echo "demo: set-up failed, see $ROOT/build/demo_setup.log" >&2; exit 1; }
grep '^setup: ' "$ROOT/build/demo_setup.log" | sed 's/^setup: /demo: set-up: /' || true
source "$ROOT/scripts/env.sh"

# OpenMP threads sleep at barriers rather than spin (see README.md, "Threads").
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
source "$ROOT/scripts/processes.sh"

PORT=$(free_loopback_port)
export ROS_MASTER_URI=http://127.0.0.1:$PORT
export ROS_LOG_DIR=$ROOT/build/demo_logs
mkdir -p "$ROS_LOG_DIR"
echo "demo: roscore on $ROS_MASTER_URI, $SCENE scene, $BOXES boxes at $RATE Hz for $SECONDS_TO_RUN s"
roscore -p "$PORT" >"$ROS_LOG_DIR/roscore.log" 2>&1 &
PIDS+=($!)
for _ in $(seq 100); do rostopic list >/dev/null 2>&1 && break; sleep 0.2; done
rostopic list >/dev/null 2>&1 || { echo "demo: roscore did not start" >&2; exit 1; }

rosrun sap_broadphase node __name:=sap_broadphase \
  _threads:="$THREADS" >"$ROS_LOG_DIR/node.log" 2>&1 &
PIDS+=($!)
rosrun sap_broadphase scene_publisher _scene:="$SCENE" _n:="$BOXES" _rate:="$RATE" \
  >"$ROS_LOG_DIR/scene_publisher.log" 2>&1 &
PIDS+=($!)
if [ "$RVIZ" = 1 ]; then
  rosrun rviz rviz -d "$ROOT/rviz/demo.rviz" >"$ROS_LOG_DIR/rviz.log" 2>&1 &
  PIDS+=($!)
fi

# One line per frame from the node's `stats`, for the bounded time.
python3 - "$SECONDS_TO_RUN" <<'PY'
import sys, time
import rospy
from sap_broadphase.msg import FrameStats

seconds = float(sys.argv[1])
last = [None]

def show(stats):
    last[0] = stats
    if stats.path == "refused":
        print("frame refused: %s" % stats.last_refusal, flush=True)
        return
    print("frame %5d  boxes %8d  pairs %8d  %8.2f ms  (sort %.2f, candidates %.2f, "
          "pairing %.2f)  %s, %d threads, dropped %d"
          % (stats.frames_processed, stats.boxes, stats.pairs, stats.ms_total, stats.ms_sort,
             stats.ms_candidates, stats.ms_pairing, stats.path, stats.threads,
             stats.frames_dropped), flush=True)

rospy.init_node("demo_stats_printer", anonymous=True, disable_signals=True)
rospy.Subscriber("stats", FrameStats, show, queue_size=100)
end = time.monotonic() + seconds
while time.monotonic() < end and not rospy.is_shutdown():
    time.sleep(0.1)
s = last[0]
if s is None:
    print("demo: no frame arrived in %.0f s (logs in %s)" % (seconds, "build/demo_logs"))
    sys.exit(1)
print("demo: %d frames received, %d processed, %d dropped, %d refused"
      % (s.frames_received, s.frames_processed, s.frames_dropped, s.frames_refused))
rospy.signal_shutdown("demo over")
PY
