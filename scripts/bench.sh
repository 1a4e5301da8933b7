#!/usr/bin/env bash
# The benchmarks (docs/BENCHMARKS.md). Installs the optional peers (CGAL, Bullet, FCL) and
# gnuplot when missing, builds the workspace, runs every sap_bench experiment into
# bench/results/<machine>/ (a CSV and the PNGs per experiment, machine.txt) and the Google
# Benchmark microbenchmarks (microbench.csv) into the same folder; each run overwrites the
# last. The tables go to stdout.
#
# Usage: scripts/bench.sh [--quick] [--out DIR] [--no-install] [--no-micro] [--physx DIR]
#                         [-- SAP_BENCH_ARGS...]
#   --quick       small sizes and few frames (minutes); results go to build/bench_quick/<machine>/
#   --out DIR     write results to DIR instead
#   --no-install  do not apt-get the optional peers and gnuplot
#   --no-micro    skip sap_microbench
#   --physx DIR   also build PhysX 5's CPU broad phases (ABP, PABP, MBP) as peers, from the
#                 PhysX source checkout DIR (never copied here; docs/BENCHMARKS.md, Peers)
#   after --, arguments go to sap_bench (e.g. -- --max-n 2^19 --runs 5)
# Environment: SAP_WS (catkin workspace, default build/ws), SAP_BENCH_MACHINE (folder name,
# default: short host name plus core count), SAP_PHYSX_DIR (as --physx).
set -eo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WS="${SAP_WS:-$ROOT/build/ws}"
OPTIONAL_PACKAGES=(libcgal-dev libtbb-dev libbullet-dev libfcl-dev gnuplot-nox)
EXPERIMENTS=fig1_sort,fig23_phases,fig4_stacked,dispersion,fig5_ball,fig6_plane,threads,pareto,peers,coherence

quick=0
install=1
micro=1
out=""
physx="${SAP_PHYSX_DIR:-}"
bench_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --no-install) install=0 ;;
    --no-micro) micro=0 ;;
    --out) out="$2"; shift ;;
    --physx) physx="$2"; shift ;;
    --) shift; bench_args=("$@"); break ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) echo "bench.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done

machine="${SAP_BENCH_MACHINE:-$(hostname -s)-$(nproc)c}"
if [ -z "$out" ]; then
  if [ "$quick" -eq 1 ]; then out="$ROOT/build/bench_quick/$machine"; else out="$ROOT/bench/results/$machine"; fi
fi

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
# The benchmarks are on by default in the catkin build; said here in case the workspace was
# configured without them.
# PhysX only when named: the workspace's cache keeps the last directory given.
physx_flag=()
[ -n "$physx" ] && physx_flag=("-DSAP_PHYSX_DIR=$(cd "$physx" && pwd)")
SAP_WS="$WS" "$ROOT/scripts/setup.sh" -DSAP_BUILD_BENCHMARKS=ON "${physx_flag[@]}"
bin="$WS/devel/lib/sap_broadphase"

mkdir -p "$out"
rm -f "$out/machine.txt"
{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "commit: $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?')$(git -C "$ROOT" diff --quiet 2>/dev/null || echo ' (with local changes)')"
  echo "kernel: $(uname -sr)"
  lscpu 2>/dev/null | grep -E '^(Model name|CPU\(s\)|Thread|Core|Socket|L2|L3)' || true
  echo "memory: $(awk '/MemTotal/ {print $2 " kB"}' /proc/meminfo)"
} > "$out/machine.txt"

quick_flag=()
[ "$quick" -eq 1 ] && quick_flag=(--quick)
echo "bench.sh: results in $out"
"$bin/sap_bench" "${quick_flag[@]}" --out "$out" -e "$EXPERIMENTS" "${bench_args[@]}"
# Memory in a process of its own, so earlier experiments' heap does not hide the peak.
"$bin/sap_bench" "${quick_flag[@]}" --out "$out" -e memory "${bench_args[@]}"

if [ "$micro" -eq 1 ] && [ -x "$bin/sap_microbench" ]; then
  micro_args=(--benchmark_out="$out/microbench.csv" --benchmark_out_format=csv)
  # Quick: the small sizes only, briefly.
  [ "$quick" -eq 1 ] && micro_args+=(--benchmark_min_time=0.01 "--benchmark_filter=[/:](1024|8192|32768|65536|131072)(/|$)|SuccTreeRange")
  "$bin/sap_microbench" "${micro_args[@]}"
fi
echo "bench.sh: done; results in $out"
