# Sourced by the scripts that start ROS processes (demo.sh, bench_ros.sh, soak.sh): every
# process they start is recorded in PIDS and stopped, by PID, when the script exits.
# shellcheck shell=bash

PIDS=()

# Stops every recorded process: SIGINT first (ROS nodes shut down cleanly), SIGKILL after 5 s.
stop_all() {
  local pid
  for pid in "${PIDS[@]}"; do kill -INT "$pid" 2>/dev/null || true; done
  for pid in "${PIDS[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
  done
}
trap stop_all EXIT

# Prints a TCP port that is free on loopback right now.
free_loopback_port() {
  python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
