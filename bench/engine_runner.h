// Drives scene frames through one or more engine configurations and keeps per-frame stats.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "bench_progress.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/scenes.h"

namespace sap_bench {

/// A named engine configuration.
struct EngineSpec {
  std::string label;
  sap_broadphase::BroadphaseConfig config;
};

/// The paper's sequential baseline: Algorithm 1 on one thread.
sap_broadphase::BroadphaseConfig sequentialConfig();
/// The parallel algorithm on inThreads threads (0 = all cores).
sap_broadphase::BroadphaseConfig parallelConfig(int inThreads);

/// What one engine did on one frame.
struct FrameSample {
  sap_broadphase::FrameReport stats;
  double wall_ms = 0.0;  ///< wall clock around update(), measured by the harness
  double cpu_ms = 0.0;   ///< CPU time of the whole process (every thread) during update()
};

/// Samples of a scene run, indexed [engine][run][frame].
struct SceneRun {
  std::vector<std::vector<std::vector<FrameSample>>> samples;
  std::size_t count_mismatches = 0;  ///< frames where the engines reported different counts
};

/// Runs inRuns runs of inFrames frames (starting at scene frame inFirstFrame) through every
/// engine; each frame's boxes go to all engines, each run starts with fresh engines.
SceneRun runScene(const sap_broadphase::SceneConfig& inScene,
                  const std::vector<EngineSpec>& inEngines, int inRuns, int inFrames,
                  int inFirstFrame = 0, Progress* ioProgress = nullptr);
/// The same with every engine in a run of its own: engine e's runs see only engine e, so a
/// fresh engine's first frame is not warmed by another engine's pages and caches.
SceneRun runSceneIsolated(const sap_broadphase::SceneConfig& inScene,
                          const std::vector<EngineSpec>& inEngines, int inRuns, int inFrames,
                          int inFirstFrame = 0, Progress* ioProgress = nullptr);

/// A number taken from a sample.
using Metric = std::function<double(const FrameSample&)>;
/// Metric reading one FrameReport field.
Metric statField(double sap_broadphase::FrameReport::*inField);
/// Metric reading the harness's wall clock.
Metric wallMs();
/// Metric reading the process CPU time spent in update().
Metric cpuMs();
/// Median over runs of a run's first frame (a fresh engine's).
double firstFrameMedian(const SceneRun& inRun, std::size_t inEngine, const Metric& inMetric);

/// Median over runs of the median over steady-state frames (all but the first frame of each
/// run, when a run has more than one).
double steadyMedian(const SceneRun& inRun, std::size_t inEngine, const Metric& inMetric);
/// Per frame: the median over runs.
std::vector<double> perFrameMedian(const SceneRun& inRun, std::size_t inEngine,
                                   const Metric& inMetric);
/// "ok" when all engines agreed on every frame's pair count, else "MISMATCH(k)".
std::string countCheck(const SceneRun& inRun);

}  // namespace sap_bench
