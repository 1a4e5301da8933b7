// Running scenes through engines.
#include "engine_runner.h"

#include <iostream>

#include "bench_stats.h"

namespace sap_bench {

using sap_broadphase::Broadphase;
using sap_broadphase::BroadphaseConfig;
using sap_broadphase::FrameReport;
using sap_broadphase::Method;
using sap_broadphase::SceneConfig;
using sap_broadphase::SceneSimulator;

BroadphaseConfig sequentialConfig() {
  BroadphaseConfig config;
  config.method = Method::kSequential;
  config.threads = 1;
  return config;
}

BroadphaseConfig parallelConfig(int inThreads) {
  BroadphaseConfig config;
  config.method = Method::kParallel;
  config.threads = inThreads;
  return config;
}

SceneRun runScene(const SceneConfig& inScene, const std::vector<EngineSpec>& inEngines, int inRuns,
                  int inFrames, int inFirstFrame, Progress* ioProgress) {
  SceneRun result;
  result.samples.assign(inEngines.size(), {});
  for (int run = 0; run < inRuns; ++run) {
    SceneSimulator simulator(inScene);
    simulator.advanceTo(inFirstFrame);
    std::vector<Broadphase> engines;
    for (const EngineSpec& spec : inEngines) engines.emplace_back(spec.config);
    for (auto& perEngine : result.samples) perEngine.emplace_back();
    for (int frame = 0; frame < inFrames; ++frame) {
      if (frame > 0) simulator.step();
      std::size_t firstCount = 0;
      bool mismatch = false;
      for (std::size_t e = 0; e < engines.size(); ++e) {
        Stopwatch clock;
        const std::size_t count = engines[e].update(simulator.boxes()).size();
        FrameSample sample{engines[e].stats(), clock.ms()};
        result.samples[e].back().push_back(sample);
        if (e == 0) firstCount = count;
        mismatch = mismatch || count != firstCount;
      }
      if (mismatch) ++result.count_mismatches;
      if (ioProgress) ioProgress->step();
    }
  }
  if (result.count_mismatches > 0) {
    std::cerr << "sap_bench: WARNING: engines disagreed on the pair count in "
              << result.count_mismatches << " frame(s)\n";
  }
  return result;
}

Metric statField(double FrameReport::*inField) {
  return [inField](const FrameSample& inSample) { return inSample.stats.*inField; };
}

Metric wallMs() {
  return [](const FrameSample& inSample) { return inSample.wall_ms; };
}

double steadyMedian(const SceneRun& inRun, std::size_t inEngine, const Metric& inMetric) {
  std::vector<double> perRun;
  for (const auto& frames : inRun.samples[inEngine]) {
    std::vector<double> values;
    const std::size_t first = frames.size() > 1 ? 1 : 0;
    for (std::size_t f = first; f < frames.size(); ++f) values.push_back(inMetric(frames[f]));
    perRun.push_back(median(values));
  }
  return median(perRun);
}

std::vector<double> perFrameMedian(const SceneRun& inRun, std::size_t inEngine,
                                   const Metric& inMetric) {
  const auto& runs = inRun.samples[inEngine];
  std::vector<double> result;
  if (runs.empty()) return result;
  for (std::size_t f = 0; f < runs.front().size(); ++f) {
    std::vector<double> values;
    for (const auto& frames : runs) values.push_back(inMetric(frames[f]));
    result.push_back(median(values));
  }
  return result;
}

std::string countCheck(const SceneRun& inRun) {
  if (inRun.count_mismatches == 0) return "ok";
  return "MISMATCH(" + std::to_string(inRun.count_mismatches) + ")";
}

}  // namespace sap_bench
