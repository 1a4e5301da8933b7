// Speedup per phase of the parallel engine on 1 thread against all cores (2 here), and of
// all cores against the sequential engine.
#include "bench_output.h"
#include "bench_scenes.h"
#include "engine_runner.h"
#include "experiments.h"

namespace sap_bench {

using sap_broadphase::FrameReport;

namespace {

struct PhaseColumn {
  const char* name;
  double FrameReport::*field;
};

const PhaseColumn kPhases[] = {{"keys", &FrameReport::ms_keys},
                               {"sort", &FrameReport::ms_sort},
                               {"candidates", &FrameReport::ms_candidates},
                               {"pairing", &FrameReport::ms_pairing},
                               {"output", &FrameReport::ms_output},
                               {"total", &FrameReport::ms_total}};

/// 1, 2, 4, ... up to and including inMax.
std::vector<int> threadCounts(int inMax) {
  std::vector<int> counts;
  for (int t = 1; t < inMax; t *= 2) counts.push_back(t);
  counts.push_back(inMax);
  return counts;
}

}  // namespace

void runThreads(const Options& inOptions) {
  const std::vector<double> densities = {0.05, 0.35};
  const auto sizes = inOptions.sizes({1u << 17, 1u << 19, 1u << 20}, {1u << 13, 1u << 15});
  const int runs = inOptions.runsOr(3);
  const int frames = inOptions.framesOr(10, 4);
  const int maxThreads = sap_broadphase::resolveThreadCount(inOptions.threads);
  std::vector<EngineSpec> engines = {{"sequential", sequentialConfig()}};
  for (int t : threadCounts(maxThreads)) {
    engines.push_back({"parallel t=" + std::to_string(t), parallelConfig(t)});
  }
  std::vector<std::string> columns = {"n", "d", "engine", "threads"};
  for (const auto& phase : kPhases) columns.push_back(std::string(phase.name) + "_ms");
  for (const auto& phase : kPhases) columns.push_back(std::string(phase.name) + "_speedup_vs_t1");
  columns.push_back("total_speedup_vs_seq");
  columns.push_back("check");
  Table table("Threads: phase times (ms, median) and speedup over the parallel engine on 1 thread",
              columns);
  Panel panel{"Speedup, " + std::to_string(maxThreads) + " threads over 1", "n (boxes)", "speedup",
              true, false};
  std::vector<Series> series;
  for (double density : densities) {
    for (const auto& phase : kPhases) {
      series.push_back({std::string(phase.name) + " d=" + fmt(density, 2), {}, {}});
    }
  }
  Progress progress("threads", densities.size() * sizes.size() * runs * frames);
  for (std::size_t di = 0; di < densities.size(); ++di) {
    for (std::size_t n : sizes) {
      const SceneRun run = runScene(uniformScene(n, densities[di], inOptions.seed), engines, runs,
                                    frames, 0, &progress);
      const double seqTotal = steadyMedian(run, 0, statField(&FrameReport::ms_total));
      for (std::size_t e = 0; e < engines.size(); ++e) {
        std::vector<std::string> row = {fmtSize(n), fmt(densities[di], 2), engines[e].label,
                                        std::to_string(engines[e].config.threads)};
        for (const auto& phase : kPhases)
          row.push_back(fmt(steadyMedian(run, e, statField(phase.field))));
        for (std::size_t p = 0; p < std::size(kPhases); ++p) {
          const double base = steadyMedian(run, 1, statField(kPhases[p].field));
          const double here = steadyMedian(run, e, statField(kPhases[p].field));
          row.push_back(e == 0 ? "-" : fmtRatio(base, here));
          if (e + 1 == engines.size()) {
            series[di * std::size(kPhases) + p].add(static_cast<double>(n), base / here);
          }
        }
        row.push_back(fmtRatio(seqTotal, steadyMedian(run, e, statField(&FrameReport::ms_total))));
        row.push_back(countCheck(run));
        table.addRow(row);
      }
    }
  }
  panel.series = series;
  publish(inOptions, table, "threads", {Figure{"threads", {panel}}});
}

}  // namespace sap_bench
