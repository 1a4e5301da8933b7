// What every added thread buys on whole frames: per frame and thread count, the frame time
// and its speedup over one thread, the CPU time the frame burns (work plus spinning; waiting
// threads that sleep cost none), a fresh engine's first frame, and each phase with the time
// no phase reports. Skin off, so that every frame is swept; the engine's own path choice
// (Method::kAuto) on t threads, beside the parallel algorithm forced onto one thread, whose
// extra work over the one-thread default is what the parallel algorithm adds.
#include "bench_output.h"
#include "bench_scenes.h"
#include "engine_runner.h"
#include "experiments.h"

namespace sap_bench {

using sap_broadphase::BroadphaseConfig;
using sap_broadphase::FrameReport;
using sap_broadphase::Method;
using sap_broadphase::SceneConfig;

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
                               {"history", &FrameReport::ms_history},
                               {"skin", &FrameReport::ms_skin},
                               {"static", &FrameReport::ms_static},
                               {"plan", &FrameReport::ms_plan}};

// ms_total less every phase: what the engine spends where no phase timer runs.
double unreportedMs(const FrameSample& inSample) {
  double phases = 0.0;
  for (const auto& phase : kPhases) phases += inSample.stats.*phase.field;
  return inSample.stats.ms_total - phases;
}

/// 1, 2, 4, ... up to and including inMax.
std::vector<int> threadCounts(int inMax) {
  std::vector<int> counts;
  for (int t = 1; t < inMax; t *= 2) counts.push_back(t);
  counts.push_back(inMax);
  return counts;
}

BroadphaseConfig skinOff(Method inMethod, int inThreads) {
  BroadphaseConfig config;
  config.method = inMethod;
  config.threads = inThreads;
  config.skin = 0.0;
  return config;
}

struct ThreadsScene {
  std::string name;
  SceneConfig scene;
  int first_frame = 0;
};

std::vector<ThreadsScene> threadsScenes(const Options& inOptions) {
  std::vector<ThreadsScene> scenes;
  const auto sizes = inOptions.sizes({1u << 17, 1u << 20}, {1u << 13, 1u << 15});
  for (std::size_t n : sizes)
    for (double density : {0.05, 0.35})
      scenes.push_back({"uniform d=" + fmt(density, 2), uniformScene(n, density, inOptions.seed)});
  // The paper's clustered frames (§7), at 2^17 boxes (2^13 with --quick): the most intense
  // stretch of the ball run, and the plane crossing.
  const std::size_t clustered = inOptions.size(1u << 17, 1u << 13);
  const int run_frames = 500;
  scenes.push_back(
      {"ball", ballScene(clustered, run_frames, inOptions.seed), ballIntenseBegin(run_frames)});
  std::size_t side = 1;
  while ((side + 1) * (side + 1) <= clustered) ++side;
  scenes.push_back(
      {"plane u=y", planeScene(side, 1, run_frames, inOptions.seed), planeCrossBegin(run_frames)});
  return scenes;
}

}  // namespace

void runThreads(const Options& inOptions) {
  const int runs = inOptions.runsOr(3);
  const int frames = inOptions.framesOr(8, 4);
  const int max_threads = sap_broadphase::resolveThreadCount(inOptions.threads);
  const std::vector<int> thread_counts = threadCounts(max_threads);
  std::vector<EngineSpec> engines;
  for (int t : thread_counts)
    engines.push_back({"auto t=" + std::to_string(t), skinOff(Method::kAuto, t)});
  engines.push_back({"parallel t=1", skinOff(Method::kParallel, 1)});

  std::vector<std::string> columns = {
      "scene",         "n",      "engine",       "threads",  "total_ms",
      "speedup_vs_t1", "cpu_ms", "cpu_per_wall", "first_ms", "first_over_steady",
      "first_cpu_ms"};
  for (const auto& phase : kPhases) columns.push_back(std::string(phase.name) + "_ms");
  columns.push_back("unreported_ms");
  columns.push_back("first_unreported_ms");
  columns.push_back("check");
  Table table(
      "Threads: whole frames, skin off (steady: median of frames 2.., first: a fresh engine's "
      "first frame; ms, medians over runs; each engine in runs of its own)",
      columns);

  Panel speedup{"Whole-frame speedup over 1 thread (steady)", "threads", "speedup"};
  Panel first{"First frame of a fresh engine / steady frame", "threads", "ratio"};
  Progress progress("threads", threadsScenes(inOptions).size() * engines.size() * runs * frames);
  for (const ThreadsScene& scene : threadsScenes(inOptions)) {
    const SceneRun run =
        runSceneIsolated(scene.scene, engines, runs, frames, scene.first_frame, &progress);
    const std::size_t n = scene.scene.n;
    const std::string label = scene.name + " n=" + fmtSize(n);
    Series speedup_series{label, {}, {}};
    Series first_series{label, {}, {}};
    const double one_thread = steadyMedian(run, 0, statField(&FrameReport::ms_total));
    for (std::size_t e = 0; e < engines.size(); ++e) {
      const int threads = engines[e].config.threads;
      const double total = steadyMedian(run, e, statField(&FrameReport::ms_total));
      const double cpu = steadyMedian(run, e, cpuMs());
      const double wall = steadyMedian(run, e, wallMs());
      const double first_total = firstFrameMedian(run, e, statField(&FrameReport::ms_total));
      std::vector<std::string> row = {scene.name,
                                      fmtSize(n),
                                      engines[e].label,
                                      std::to_string(threads),
                                      fmt(total),
                                      fmtRatio(one_thread, total),
                                      fmt(cpu),
                                      fmtRatio(cpu, wall),
                                      fmt(first_total),
                                      fmtRatio(first_total, total),
                                      fmt(firstFrameMedian(run, e, cpuMs()))};
      for (const auto& phase : kPhases)
        row.push_back(fmt(steadyMedian(run, e, statField(phase.field))));
      row.push_back(fmt(steadyMedian(run, e, unreportedMs)));
      row.push_back(fmt(firstFrameMedian(run, e, unreportedMs)));
      row.push_back(countCheck(run));
      table.addRow(row);
      if (engines[e].config.method == Method::kAuto) {
        speedup_series.add(threads, one_thread / total);
        first_series.add(threads, first_total / total);
      }
    }
    speedup.series.push_back(speedup_series);
    first.series.push_back(first_series);
  }
  publish(inOptions, table, "threads", {Figure{"threads", {speedup, first}}});
}

}  // namespace sap_bench
