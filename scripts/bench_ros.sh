#!/usr/bin/env bash
# End to end through ROS: a roscore on a free loopback port, the node, and
# sap_ros_latency publishing uniform-scene BoxArray frames and timing publish -> PairArray,
# split into the engine's sweep and everything outside it (see docs/BENCHMARKS.md). Two
# transports on the same frames, case by case: tcp (the node started here, another process)
# and nodelet (sap_ros_latency loads BroadphaseNodelet into its own process: publisher, node
# and measuring subscriber share it and pass the messages as pointers).
# Results: bench/results/<machine>/ros_latency.csv and ros_latency_frames.csv, load and
# conditions in ros_latency_conditions.txt; the table on stdout and in
# build/bench_ros_logs/ros_latency.log beside the build and ROS logs. Stops every process it
# started, by PID, on exit or interrupt; every step is time-bound.
#
# Usage: scripts/bench_ros.sh [--quick] [--out DIR] [--limit S] [--no-setup]
#                             [-- SAP_ROS_LATENCY_ARGS...]
#   --quick     n = 2^12, 2^14, d = 0.05, few frames; results go to build/bench_quick/<machine>/
#   --out DIR   write results to DIR instead
#   --limit S   seconds sap_ros_latency may run (default 3000, quick 240)
#   --no-setup  use the workspace as it is, without scripts/setup.sh (scripts/bench.sh has just
#               built it; a set-up mirrors the sources again, and the results written since
#               make it run catkin_make again)
#   after --, arguments go to sap_ros_latency (e.g. -- --n 2^17 --density 0.05 --frames 30,
#               or -- --transport nodelet)
# Environment: SAP_WS (catkin workspace, default build/ws), SAP_BENCH_MACHINE (folder name,
# default: short host name plus core count), OMP_WAIT_POLICY (default passive for the node).
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WS="${SAP_WS:-$ROOT/build/ws}"

quick=0
setup=1
out=""
limit=""
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --out) out="$2"; shift ;;
    --limit) limit="$2"; shift ;;
    --) shift; extra=("$@"); break ;;
    --no-setup) setup=0 ;;
    -h|--help) sed -n '2,24p' "$0"; exit 0 ;;
    *) echo "bench_ros.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done

machine="${SAP_BENCH_MACHINE:-$(hostname -s)-$(nproc)c}"
if [ -z "$out" ]; then
  if [ "$quick" -eq 1 ]; then out="$ROOT/build/bench_quick/$machine"; else out="$ROOT/bench/results/$machine"; fi
fi
if [ -z "$limit" ]; then
  if [ "$quick" -eq 1 ]; then limit=240; else limit=3000; fi
fi
mkdir -p "$out"
out=$(cd "$out" && pwd)
logs="$ROOT/build/bench_ros_logs"
mkdir -p "$logs"

if [ "$setup" -eq 1 ]; then
  echo "bench_ros.sh: set-up and build of $WS (log in $logs/setup.log)"
  if ! SAP_WS="$WS" timeout 3600 "$ROOT/scripts/setup.sh" -DSAP_BUILD_BENCHMARKS=ON \
      >"$logs/setup.log" 2>&1; then
    tail -n 20 "$logs/setup.log" >&2
    echo "bench_ros.sh: set-up failed" >&2
    exit 1
  fi
fi
export SAP_WS="$WS"
source "$ROOT/scripts/env.sh"
bin="$WS/devel/lib/sap_broadphase"
[ -x "$bin/sap_ros_latency" ] || { echo "bench_ros.sh: $bin/sap_ros_latency was not built" >&2; exit 1; }

# OpenMP threads of the node sleep at barriers rather than spin (README, "Threads").
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
source "$ROOT/scripts/processes.sh"
trap 'exit 130' INT TERM

PORT=$(free_loopback_port)
export ROS_MASTER_URI=http://127.0.0.1:$PORT
export ROS_LOG_DIR=$logs

conditions="$out/ros_latency_conditions.txt"
{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "commit: $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?')$(git -C "$ROOT" diff --quiet 2>/dev/null || echo ' (with local changes)')"
  echo "kernel: $(uname -sr)"
  lscpu 2>/dev/null | grep -E '^(Model name|CPU\(s\))' || true
  echo "memory: $(awk '/MemTotal/ {print $2 " kB"}' /proc/meminfo)"
  echo "OMP_WAIT_POLICY=$OMP_WAIT_POLICY; node (tcp) and BroadphaseNodelet (nodelet): threads 0 (all cores), publish_markers false"
  echo "uptime before: $(uptime)"
} >"$conditions"

echo "bench_ros.sh: roscore on $ROS_MASTER_URI; results in $out"
roscore -p "$PORT" >"$ROS_LOG_DIR/roscore.log" 2>&1 &
PIDS+=($!)
for _ in $(seq 150); do rostopic list >/dev/null 2>&1 && break; sleep 0.2; done
rostopic list >/dev/null 2>&1 || { echo "bench_ros.sh: roscore did not start" >&2; exit 1; }

"$bin/node" __name:=sap_broadphase _publish_markers:=false >"$ROS_LOG_DIR/node.log" 2>&1 &
PIDS+=($!)

args=(--out "$out")
[ "$quick" -eq 1 ] && args+=(--quick)
rc=0
# In the background so that the EXIT trap can stop it too, then waited for.
timeout -s INT -k 10 "$limit" "$bin/sap_ros_latency" "${args[@]}" "${extra[@]}" \
  >"$logs/ros_latency.log" &
PIDS+=($!)
wait "${PIDS[-1]}" || rc=$?
cat "$logs/ros_latency.log"
echo "uptime after: $(uptime)" >>"$conditions"
cat "$conditions"
if [ "$rc" -ne 0 ]; then
  echo "bench_ros.sh: sap_ros_latency failed (exit $rc; 124: over --limit $limit s)" >&2
  exit "$rc"
fi
echo "bench_ros.sh: done; results in $out"
