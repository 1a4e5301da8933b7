// A busy machine: the engine's default configuration against one thread while 0, 1 or 2 busy
// loops (child processes spinning, started and stopped here) share the cores, as on a robot's
// computer. libgomp reads OMP_WAIT_POLICY once, when the process starts, so each policy (unset,
// as `rosrun` starts the node, and passive) is measured in child runs of this executable with
// that environment, one per configuration (one engine in a process, as in the node); a child
// prints one line per size and the parent tabulates them.
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>

#include "bench_output.h"
#include "bench_scenes.h"
#include "bench_stats.h"
#include "experiments.h"
#include "sap_broadphase/core/broadphase.h"

namespace sap_bench {

using sap_broadphase::Broadphase;
using sap_broadphase::BroadphaseConfig;

namespace {

/// Set in a child run's environment: measure and print, don't orchestrate.
constexpr const char* kChildVariable = "SAP_BENCH_BUSY_CHILD";
/// Where a child run's sap_bench writes its machine log: not beside the results, which hold
/// the parent's line only.
constexpr const char* kChildOutDir = "/tmp/sap_bench_busy_child";
/// The prefix of a child's result lines on its stdout.
constexpr const char* kRowTag = "busy_row";
/// Motion a frame, in mean box edges (as the size sweep's steady state).
constexpr double kSpeed = 0.01;
constexpr double kDensity = 0.35;
constexpr int kMaxBusyLoops = 2;
/// Child runs of each configuration (--runs; 2 with --quick).
constexpr int kRunsPerConfiguration = 3;

std::string contenderName(int inThreads) {
  return "sap_broadphase_t" + std::to_string(inThreads);
}

double percentile90(std::vector<double> inValues) {
  if (inValues.empty()) return 0.0;
  std::sort(inValues.begin(), inValues.end());
  const auto rank = static_cast<std::size_t>(std::ceil(0.9 * inValues.size()));
  return inValues[std::max<std::size_t>(rank, 1) - 1];
}

/// The child's work: the default configuration on --threads threads, alone in its process as
/// in a node, in steady state over the scene's frames; one row per size.
void measureInChild(const Options& inOptions) {
  const int threads = sap_broadphase::resolveThreadCount(inOptions.threads);
  const int frames = inOptions.framesOr(201, 21);
  for (std::size_t n : inOptions.sizes({1u << 12, 1u << 14}, {1u << 12, 1u << 14})) {
    sap_broadphase::SceneConfig scene = uniformScene(n, kDensity, inOptions.seed);
    scene.speed = kSpeed;
    FrameFeed feed(scene, 0);
    BroadphaseConfig config;
    config.threads = threads;
    Broadphase engine(config);
    std::vector<double> ms;
    for (int f = 0; f < frames; ++f) {
      if (f > 0) feed.step();
      Stopwatch clock;
      engine.update(feed.boxes());
      if (f > 0) ms.push_back(clock.ms());  // frame 0 builds the steady state
    }
    std::cout << kRowTag << " " << n << " " << contenderName(threads) << " " << median(ms) << " "
              << percentile90(ms) << " " << ms.size() << "\n";
  }
  std::cout.flush();
}

/// A busy loop: a child process spinning until killed.
pid_t startBusyLoop() {
  const pid_t pid = fork();
  if (pid == 0) {
    volatile uint64_t spin = 0;
    for (;;) spin = spin + 1;
  }
  return pid;
}

void stopBusyLoop(pid_t inPid) {
  kill(inPid, SIGKILL);
  waitpid(inPid, nullptr, 0);
}

/// One measured row of a child run.
struct BusyRow {
  std::size_t n = 0;
  std::string contender;
  double median_ms = 0.0, p90_ms = 0.0;
  int frames = 0;
  int runs = 1;  ///< child runs whose medians this row's are the median of
};

/// One row from several runs of a configuration: the median of their medians and of their 90th
/// percentiles.
BusyRow medianRow(const std::vector<BusyRow>& inRuns) {
  BusyRow row = inRuns.front();
  std::vector<double> runMedians, runP90s;
  for (const BusyRow& run : inRuns) {
    runMedians.push_back(run.median_ms);
    runP90s.push_back(run.p90_ms);
  }
  row.median_ms = median(runMedians);
  row.p90_ms = median(runP90s);
  row.runs = static_cast<int>(inRuns.size());
  return row;
}

std::string selfPath() {
  char path[4096];
  const ssize_t length = readlink("/proc/self/exe", path, sizeof(path) - 1);
  if (length <= 0) return {};
  path[length] = '\0';
  return path;
}

/// Runs this executable as a child measuring the default on inThreads threads under inPolicy
/// ("" = unset) and parses its rows.
std::vector<BusyRow> runChild(const Options& inOptions, const std::string& inPolicy,
                              int inThreads) {
  std::ostringstream command;
  command << "env -u OMP_WAIT_POLICY " << (inPolicy.empty() ? "" : "OMP_WAIT_POLICY=" + inPolicy)
          << " " << kChildVariable << "=1 '" << selfPath() << "' -e busy --no-plots --out '"
          << kChildOutDir << "' --seed " << inOptions.seed << " --threads " << inThreads
          << (inOptions.quick ? " --quick" : "");
  if (inOptions.frames > 0) command << " --frames " << inOptions.frames;
  if (!inOptions.only_sizes.empty()) {
    command << " --sizes ";
    for (std::size_t k = 0; k < inOptions.only_sizes.size(); ++k)
      command << (k ? "," : "") << inOptions.only_sizes[k];
  }
  command << " 2>/dev/null";
  std::vector<BusyRow> rows;
  FILE* child = popen(command.str().c_str(), "r");
  if (child == nullptr) return rows;
  char line[512];
  while (std::fgets(line, sizeof(line), child) != nullptr) {
    std::istringstream fields(line);
    std::string tag;
    BusyRow row;
    if (fields >> tag >> row.n >> row.contender >> row.median_ms >> row.p90_ms >> row.frames &&
        tag == kRowTag)
      rows.push_back(row);
  }
  if (pclose(child) != 0) std::cerr << "busy: a child run failed: " << command.str() << "\n";
  return rows;
}

}  // namespace

void runBusy(const Options& inOptions) {
  if (std::getenv(kChildVariable) != nullptr) return measureInChild(inOptions);
  const int threads = sap_broadphase::resolveThreadCount(inOptions.threads);
  Table table(
      "Busy machine: ms per frame, steady at 1 % motion (uniform, d = 0.35), with busy loops "
      "beside the engine, each configuration alone in a process, the median of its runs' medians; "
      "ratio = median / one thread's median under the same load",
      {"n", "busy_loops", "omp_wait_policy", "contender", "median_ms", "p90_ms", "ratio_median",
       "frames", "runs"});
  std::map<std::size_t, std::map<std::string, Series>> medians, p90s;
  // Each configuration's child is run kRunsPerConfiguration times, the contenders alternating
  // (t2 t1, t1 t2, t2 t1): on 2 cores a child sometimes shares a core with a busy loop for its
  // whole run (its median doubles, its 90th percentile does not), and which child that happens
  // to is the scheduler's luck, not the code's; the median of the runs' medians is reported.
  const int runs = inOptions.runsOr(kRunsPerConfiguration);
  for (int busy = 0; busy <= kMaxBusyLoops; ++busy) {
    std::vector<pid_t> loops;
    for (int k = 0; k < busy; ++k) loops.push_back(startBusyLoop());
    for (const std::string policy : {"", "passive"}) {
      const std::string policyName = policy.empty() ? "unset" : policy;
      std::vector<int> contenders{threads};
      if (threads != 1) contenders.push_back(1);
      std::map<std::pair<std::size_t, std::string>, std::vector<BusyRow>> runsOf;
      for (int run = 0; run < runs; ++run) {
        for (std::size_t k = 0; k < contenders.size(); ++k) {
          const int contender = contenders[run % 2 == 0 ? k : contenders.size() - 1 - k];
          for (const BusyRow& row : runChild(inOptions, policy, contender))
            runsOf[{row.n, row.contender}].push_back(row);
        }
      }
      std::vector<BusyRow> rows;
      for (const auto& [key, measured] : runsOf) rows.push_back(medianRow(measured));
      std::stable_sort(rows.begin(), rows.end(), [](const BusyRow& inA, const BusyRow& inB) {
        return inA.n != inB.n ? inA.n < inB.n : inA.contender > inB.contender;
      });
      for (const BusyRow& row : rows) {
        double oneThread = 0.0;
        for (const BusyRow& other : rows)
          if (other.n == row.n && other.contender == contenderName(1)) oneThread = other.median_ms;
        table.addRow({fmtSize(row.n), std::to_string(busy), policyName, row.contender,
                      fmt(row.median_ms), fmt(row.p90_ms), fmtRatio(row.median_ms, oneThread),
                      std::to_string(row.frames), std::to_string(row.runs)});
        const std::string series = row.contender + " " + policyName;
        medians[row.n][series].add(busy, row.median_ms);
        p90s[row.n][series].add(busy, row.p90_ms);
      }
    }
    for (pid_t loop : loops) stopBusyLoop(loop);
  }
  std::vector<Panel> panels;
  for (auto* stat : {&medians, &p90s}) {
    for (auto& [n, byName] : *stat) {
      Panel panel(
          (stat == &medians ? "Median frame, n=" : "90th percentile frame, n=") + fmtSize(n),
          "busy loops", "ms per frame", false, true, PlotStyle::kLinesPoints);
      panel.xrange = "[-0.2:" + std::to_string(kMaxBusyLoops) + ".2]";
      for (int busy = 0; busy <= kMaxBusyLoops; ++busy)
        panel.xtics.push_back({busy, std::to_string(busy)});
      for (auto& [name, series] : byName) {
        series.title = name;
        panel.series.push_back(series);
      }
      panels.push_back(panel);
    }
  }
  publish(inOptions, table, "busy", {Figure{"busy", panels, 2}});
}

}  // namespace sap_bench
