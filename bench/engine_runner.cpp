// Running scenes through engines.
#include "engine_runner.h"

#include <algorithm>
#include <ctime>
#include <functional>
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
  config.skin = 0.0;  // the paper's sweep on every frame, not answers from kept candidates
  return config;
}

BroadphaseConfig parallelConfig(int inThreads) {
  BroadphaseConfig config;
  config.method = Method::kParallel;
  config.threads = inThreads;
  config.skin = 0.0;  // the paper's sweep on every frame, not answers from kept candidates
  return config;
}

namespace {

double processCpuMs() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

FrameSample timedUpdate(Broadphase& ioEngine, const sap_broadphase::BoxSet& inBoxes,
                        std::size_t& outPairs) {
  const double cpu_start = processCpuMs();
  Stopwatch clock;
  outPairs = ioEngine.update(inBoxes).size();
  const double wall = clock.ms();
  return FrameSample{ioEngine.stats(), wall, processCpuMs() - cpu_start};
}

}  // namespace

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
        std::size_t count = 0;
        result.samples[e].back().push_back(timedUpdate(engines[e], simulator.boxes(), count));
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

SceneRun runSceneIsolated(const SceneConfig& inScene, const std::vector<EngineSpec>& inEngines,
                          int inRuns, int inFrames, int inFirstFrame, Progress* ioProgress) {
  SceneRun result;
  result.samples.assign(inEngines.size(), {});
  std::vector<std::vector<std::size_t>> counts(inFrames);  // [frame][engine, run]
  for (std::size_t e = 0; e < inEngines.size(); ++e) {
    for (int run = 0; run < inRuns; ++run) {
      SceneSimulator simulator(inScene);
      simulator.advanceTo(inFirstFrame);
      Broadphase engine(inEngines[e].config);
      result.samples[e].emplace_back();
      for (int frame = 0; frame < inFrames; ++frame) {
        if (frame > 0) simulator.step();
        std::size_t count = 0;
        result.samples[e].back().push_back(timedUpdate(engine, simulator.boxes(), count));
        counts[frame].push_back(count);
        if (ioProgress) ioProgress->step();
      }
    }
  }
  for (const auto& perFrame : counts) {
    if (std::adjacent_find(perFrame.begin(), perFrame.end(), std::not_equal_to<>()) !=
        perFrame.end())
      ++result.count_mismatches;
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

Metric cpuMs() {
  return [](const FrameSample& inSample) { return inSample.cpu_ms; };
}

double firstFrameMedian(const SceneRun& inRun, std::size_t inEngine, const Metric& inMetric) {
  std::vector<double> perRun;
  for (const auto& frames : inRun.samples[inEngine])
    if (!frames.empty()) perRun.push_back(inMetric(frames.front()));
  return median(perRun);
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
