#!/usr/bin/env bash
# The benchmarks (docs/BENCHMARKS.md): one script regenerates every CSV and plot the page reads.
#
#   scripts/bench.sh --all     every sap_bench experiment the page reads (a CSV and the PNGs
#                              each), memory in a process of its own, the Python module's
#                              script when the module is built, sap_microbench, the runs of
#                              their own folders (busy_2p17/, busy_2p20/, peers_2p17/,
#                              memory_2p23/, physx_sizes/ and physx_2p20/ when PhysX is
#                              named), MPI ranks of this machine, and the runs
#                              through ROS (scripts/bench_ros.sh) when the catkin workspace is
#                              used; into bench/results/<machine>/ with machine.txt (about 40
#                              minutes on an idle 2-core machine with PhysX, measured: a third of
#                              it peers, peers_2p17/ and coherence, a tenth the busy runs;
#                              --experiments runs some). The default.
#   scripts/bench.sh --quick   the same, smallest sizes, a few frames and runs, no ROS and no
#                              microbenchmarks (under a minute); into build/bench_quick/<machine>/.
#                              The test command runs it as a smoke test (scripts/test_no_ros.sh).
# Each run overwrites the last; the tables go to stdout.
#
# Usage: scripts/bench.sh [--all|--quick] [--bin DIR] [--out DIR] [--no-install] [--no-micro]
#                         [--no-ros] [--experiments A,B] [-- SAP_BENCH_ARGS...]
#   --bin DIR          sap_bench (and sap_microbench, the Python module in DIR/python) from DIR,
#                      e.g. build/no_ros: nothing is built or installed, nothing through ROS
#   --out DIR          write results to DIR instead
#   --no-install       do not apt-get the optional peers and gnuplot
#   --no-micro         skip sap_microbench
#   --no-ros           skip the runs through ROS
#   --experiments A,B  only these sap_bench experiments (and nothing else)
#   --physx DIR        also build PhysX 5's CPU broad phases (ABP, PABP, MBP) as peers, from the
#                      PhysX source checkout DIR (never copied here; docs/BENCHMARKS.md, Peers)
#   after --, arguments go to sap_bench (e.g. -- --max-n 2^19 --runs 5)
# Environment: SAP_WS (catkin workspace, default build/ws), SAP_BENCH_MACHINE (folder name,
# default: short host name plus core count), SAP_PHYSX_DIR (as --physx).
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WS="${SAP_WS:-$ROOT/build/ws}"
OPTIONAL_PACKAGES=(libcgal-dev libtbb-dev libbullet-dev libfcl-dev gnuplot-nox)
# Every experiment whose CSV docs/BENCHMARKS.md reads; memory and peers run on their own
# (below).
EXPERIMENTS=fig1_sort,fig23_phases,fig4_stacked,dispersion,fig5_ball,fig6_plane,sizes,busy,threads,pareto,coherence,skips,query,events

quick=0
install=1
micro=1
ros=1
bin=""
out=""
physx="${SAP_PHYSX_DIR:-}"
only=""
bench_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --all) quick=0 ;;
    --quick) quick=1 ;;
    --bin) bin=$(cd "$2" && pwd); shift ;;
    --no-install) install=0 ;;
    --no-micro) micro=0 ;;
    --no-ros) ros=0 ;;
    --experiments) only="$2"; shift ;;
    --out) out="$2"; shift ;;
    --physx) physx="$2"; shift ;;
    --) shift; bench_args=("$@"); break ;;
    -h|--help) sed -n '2,32p' "$0"; exit 0 ;;
    *) echo "bench.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done

machine="${SAP_BENCH_MACHINE:-$(hostname -s)-$(nproc)c}"
if [ -z "$out" ]; then
  if [ "$quick" -eq 1 ]; then out="$ROOT/build/bench_quick/$machine"; else out="$ROOT/bench/results/$machine"; fi
fi
# Quick: a smoke test of every experiment, not a measurement.
if [ "$quick" -eq 1 ]; then micro=0; ros=0; fi
if [ -n "$bin" ]; then install=0; ros=0; fi

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }

# The peers and gnuplot are optional: a failed install only loses those rows and the PNGs.
install_optional_packages() {
  local missing=()
  for pkg in "${OPTIONAL_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed' || missing+=("$pkg")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "bench.sh: installing ${missing[*]}"
  if ! { as_root apt-get update -q && as_root env DEBIAN_FRONTEND=noninteractive \
      apt-get install -y -q --no-install-recommends "${missing[@]}"; }; then
    echo "bench.sh: WARNING: could not install ${missing[*]}; continuing without them" >&2
  fi
}

[ "$install" -eq 1 ] && install_optional_packages
if [ -z "$bin" ]; then
  # The benchmarks are on by default in the catkin build; said here in case the workspace was
  # configured without them. PhysX only when named: the workspace's cache keeps the last
  # directory given.
  physx_flag=()
  [ -n "$physx" ] && physx_flag=("-DSAP_PHYSX_DIR=$(cd "$physx" && pwd)")
  SAP_WS="$WS" "$ROOT/scripts/setup.sh" -DSAP_BUILD_BENCHMARKS=ON "${physx_flag[@]}"
  bin="$WS/devel/lib/sap_broadphase"
fi

mkdir -p "$out"
# sap_bench appends a line per experiment to machine.txt: a whole run starts it afresh, a run
# of some experiments adds to it.
[ -z "$only" ] && rm -f "$out/machine.txt"
{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "commit: $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?')$(git -C "$ROOT" diff --quiet 2>/dev/null || echo ' (with local changes)')"
  echo "kernel: $(uname -sr)"
  lscpu 2>/dev/null | grep -E '^(Model name|CPU\(s\)|Thread|Core|Socket|L2|L3)' || true
  echo "memory: $(awk '/MemTotal/ {print $2 " kB"}' /proc/meminfo)"
  echo "load at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
} >> "$out/machine.txt"

quick_flag=()
[ "$quick" -eq 1 ] && quick_flag=(--quick)
echo "bench.sh: results in $out"
"$bin/sap_bench" "${quick_flag[@]}" --out "$out" -e "${only:-$EXPERIMENTS}" "${bench_args[@]}"
[ -n "$only" ] && { echo "bench.sh: done; results in $out"; exit 0; }
# Memory in a process of its own, so earlier experiments' heap does not hide the peak.
"$bin/sap_bench" "${quick_flag[@]}" --out "$out" -e memory "${bench_args[@]}"
# The peers with the frames the page's table states (frame 0 builds, medians of frames 1-3);
# peers_2p17/ below keeps the default 6.
peers_frames=(--frames 4)
[ "$quick" -eq 1 ] && peers_frames=()
"$bin/sap_bench" "${quick_flag[@]}" --out "$out" -e peers "${peers_frames[@]}" "${bench_args[@]}"

# Runs of their own, each in a folder the page names: the busy machine at 2^17 and at 2^20
# (fewer frames), the peers at 2^17, MPI ranks of this machine (not in --quick), and, when
# PhysX is named (--physx; with --bin, the PhysX that sap_bench was built with), the size sweep
# beside PhysX's ABP and PABP (200 steady frames, 2^12-2^17) and at 2^20 (20 steady frames:
# sizes.csv's 3 hold the first cycle's build, not the steady state).
if [ "$quick" -eq 1 ]; then
  mid_busy=(--sizes 2^10 --frames 3); big_busy=(--sizes 2^12 --frames 3); big_peers=(--max-n 2^12)
  physx_small=(--sizes 2^10 --frames 3); physx_big=(--sizes 2^11 --frames 3)
else
  mid_busy=(--sizes 2^17); big_busy=(--sizes 2^20 --frames 20); big_peers=(--max-n 2^17)
  physx_small=(--sizes 2^12,2^14,2^17 --frames 201); physx_big=(--sizes 2^20 --frames 21)
fi
run_in_folder() {  # folder experiment sap_bench-arguments...
  local folder="$out/$1" experiment=$2; shift 2
  mkdir -p "$folder"; rm -f "$folder/machine.txt"
  "$bin/sap_bench" "${quick_flag[@]}" --out "$folder" -e "$experiment" "$@" "${bench_args[@]}"
}
run_in_folder busy_2p17 busy "${mid_busy[@]}"
run_in_folder busy_2p20 busy "${big_busy[@]}"
run_in_folder peers_2p17 peers "${big_peers[@]}"
[ "$quick" -eq 1 ] || "$bin/sap_bench" --out "$out" -e distributed --max-n 2^20 "${bench_args[@]}"
# Memory at 2^23 (8.4 million boxes, a few GB; about 5 minutes): the size where users are bound
# by memory rather than time. The engine only: PhysX's contenders are measured up to 2^20
# (bench/exp_memory.cpp, kMostPeerBoxes).
[ "$quick" -eq 1 ] || run_in_folder memory_2p23 memory --sizes 2^23
if [ -n "$physx" ]; then
  run_in_folder physx_sizes sizes "${physx_small[@]}" --threads 2
  run_in_folder physx_2p20 sizes "${physx_big[@]}" --threads 2
else
  echo "bench.sh: no PhysX named (--physx DIR): no physx_sizes/"
fi

# The Python module beside rtree, when the module is built (the plain CMake build's python/
# folder, or the catkin workspace's) and rtree is installed.
python_path="$bin/python"
[ -d "$python_path/sap_broadphase" ] || python_path="$WS/devel/lib/python3/dist-packages"
if PYTHONPATH="$python_path" python3 -c 'import sap_broadphase, rtree' 2>/dev/null; then
  PYTHONPATH="$python_path" python3 "$ROOT/python/bench/bench_python.py" "${quick_flag[@]}" --out "$out"
else
  echo "bench.sh: the Python module or rtree is missing: no python_*.csv"
fi

# The microbenchmarks the page cites (BM_SkinPass: the kept-candidate pass's target); the
# whole suite (242 cases; the page reads no other) by hand.
if [ "$micro" -eq 1 ] && [ -x "$bin/sap_microbench" ]; then
  "$bin/sap_microbench" --benchmark_filter=BM_SkinPass --benchmark_out="$out/microbench.csv" \
    --benchmark_out_format=csv
fi

# Through ROS: the node against a nodelet at 2^20, the nodelet alone, small frames; the
# workspace was built above, so no set-up again.
if [ "$ros" -eq 1 ]; then
  "$ROOT/scripts/bench_ros.sh" --no-setup --out "$out" -- --n 2^17,2^20 --density 0.05,0.35 \
    --frames 10 --no-throughput
  "$ROOT/scripts/bench_ros.sh" --no-setup --out "$out/nodelet" -- --transport nodelet \
    --n 2^17,2^20 --density 0.05,0.35 --frames 20 --no-throughput
  "$ROOT/scripts/bench_ros.sh" --no-setup --quick --out "$out/small_frames"
fi
echo "bench.sh: done; results in $out"
