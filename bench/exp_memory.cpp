// Memory of the engine, two tables.
//
// memory.csv: the peak of the default engine in steady use (uniform scene moving 1 % of a mean
// edge a frame, enough frames for the kept candidates to be rebuilt at least once), against the
// target of 120 bytes per box plus 8 per pair. The peak resident set (VmHWM) is reset through
// /proc/self/clear_refs after the scene exists, so the growth during the engine's frames is the
// engine's own (buffers and pair output).
//
// memory_parts.csv: bytes per box of each structure the default holds, measured on the same
// scene with the engine's parts run one after the other on one thread, as a sweep frame with the
// engine's chosen skin runs them: the history (the engine's copy of the frame and its change
// flags), the sweep's working buffers (keys, ranks, candidate ranges, sort and pairing scratch:
// the resident growth of one plain sweep beyond its pair list), one pair list, the grown boxes,
// the kept candidates, a kept-candidate pass's buffers and the skin's sorting scratch. Capacities
// where the engine's part can tell them (history, skin), resident growth for the sweep.
#include <algorithm>
#include <utility>

#include "bench_memory.h"
#include "bench_output.h"
#include "bench_scenes.h"
#include "core/frame/frame_history.h"
#include "core/strategies/skin_list.h"
#include "core/sweep/axis_spread.h"
#include "core/sweep/sweep_and_prune.h"
#include "engine_runner.h"
#include "experiments.h"

namespace sap_bench {
namespace {

using sap_broadphase::BoxColumns;
using sap_broadphase::PairList;

/// Motion a frame, in mean box edges, as in the size sweep (exp_sizes.cpp).
constexpr double kSpeed = 0.01;

sap_broadphase::SceneConfig movingScene(std::size_t inCount, double inDensity, uint64_t inSeed) {
  sap_broadphase::SceneConfig scene = uniformScene(inCount, inDensity, inSeed);
  scene.speed = kSpeed;
  return scene;
}

std::string perBox(std::size_t inBytes, std::size_t inBoxes) {
  return fmt(static_cast<double>(inBytes) / static_cast<double>(inBoxes), 3);
}

/// The skin the default chooses for this scene: the engine run for a few frames.
double chosenSkin(const sap_broadphase::SceneConfig& inScene, int inThreads) {
  sap_broadphase::SceneSimulator simulator(inScene);
  sap_broadphase::BroadphaseConfig config;
  config.threads = inThreads;
  sap_broadphase::Broadphase engine(config);
  double skin = 0.0;
  for (int f = 0; f < 4 && skin == 0.0; ++f) {
    if (f > 0) simulator.step();
    engine.update(simulator.boxes());
    skin = engine.stats().skin;
  }
  return skin;
}

/// One row per structure of the parts table.
void addParts(const sap_broadphase::SceneConfig& inScene, double inSkin, Table& ioTable) {
  using namespace sap_broadphase;
  SceneSimulator simulator(inScene);
  const std::size_t n = inScene.n;
  FrameHistory history;
  std::optional<ValidationError> problem;
  history.load(simulator.boxes(), problem);
  const BoxColumns& boxes = history.loaded();
  BroadphaseConfig config;
  SweepAndPrune sweep(config);
  FrameReport report;
  PairList pairs;
  PeakMeter meter;
  meter.start();
  {
    FrameSpread spread(boxes);
    sweep.run(boxes, spread, FramePath::kParallel, report, pairs);
  }
  const std::size_t pair_bytes = pairs.capacity() * sizeof(IdPair);
  const std::size_t sweep_bytes =
      meter.grownBytes() > pair_bytes ? meter.grownBytes() - pair_bytes : 0;
  const std::size_t frame_pairs = pairs.size();
  SkinList kept;
  const BoxColumns& grown = kept.inflate(boxes, inSkin);
  {
    FrameSpread grown_spread(grown);
    sweep.run(grown, grown_spread, FramePath::kParallel, report, pairs);
  }
  const std::size_t candidates = pairs.size();
  kept.adopt(boxes, std::move(pairs));
  if (kept.gather(boxes, 1)) kept.collectGathered(1, pairs);
  const SkinList::MemoryUse skin = kept.memoryUse();
  const auto row = [&](const std::string& inPart, std::size_t inBytes, const std::string& inHow) {
    ioTable.addRow({fmtSize(n), fmt(inScene.density, 2), fmt(inSkin, 3), fmtCount(frame_pairs),
                    fmtCount(candidates), inPart, fmtCount(inBytes), perBox(inBytes, n), inHow});
  };
  row("history", history.bytesHeld(), "capacity");
  row("sweep_buffers", sweep_bytes, "resident growth");
  row("pair_list", frame_pairs * sizeof(IdPair), "size");
  row("grown_boxes", skin.reference, "capacity");
  row("kept_candidates", skin.candidates, "capacity");
  row("pass_buffers", skin.pass, "capacity");
  row("skin_scratch", skin.scratch, "capacity");
}

}  // namespace

void runMemory(const Options& inOptions) {
  const auto sizes = inOptions.sizes({1u << 17, 1u << 20}, {1u << 14, 1u << 16});
  const int frames = inOptions.framesOr(40, 3);
  const int threads = sap_broadphase::resolveThreadCount(inOptions.threads);
  Table table(
      "Peak memory of the default engine over steady frames at 1 % motion (bytes; target "
      "120/box + 8/pair)",
      {"n", "d", "pairs", "frames", "grown_sweeps", "engine_peak_bytes", "bytes_per_box",
       "budget_bytes", "within_budget", "process_peak_bytes", "peak_reset"});
  Table parts(
      "Bytes per box of each structure of the default (one thread; sweep frame with the "
      "chosen skin)",
      {"n", "d", "skin", "pairs", "candidates", "structure", "bytes", "bytes_per_box",
       "measured_as"});
  for (std::size_t n : sizes) {
    for (double density : {0.05, 0.35}) {
      const sap_broadphase::SceneConfig scene = movingScene(n, density, inOptions.seed);
      sap_broadphase::SceneSimulator simulator(scene);
      PeakMeter meter;
      meter.start();
      std::size_t pairs = 0;
      int grown_sweeps = 0;
      {
        sap_broadphase::BroadphaseConfig config;
        config.threads = threads;
        sap_broadphase::Broadphase engine(config);
        for (int f = 0; f < frames; ++f) {
          if (f > 0) simulator.step();
          pairs = std::max(pairs, engine.update(simulator.boxes()).size());
          const auto& stats = engine.stats();
          grown_sweeps += f > 0 && stats.path != sap_broadphase::FramePath::kSkin &&
                          stats.skin_choice == sap_broadphase::SkinChoice::kChosen;
        }
      }
      const std::size_t used = meter.grownBytes();
      const std::size_t budget = 120 * n + 8 * pairs;
      table.addRow({fmtSize(n), fmt(density, 2), fmtCount(pairs), std::to_string(frames),
                    std::to_string(grown_sweeps), fmtCount(used),
                    fmt(static_cast<double>(used) / n), fmtCount(budget),
                    used <= budget ? "yes" : "NO", fmtCount(meter.processPeakBytes()),
                    meter.peakReset() ? "yes" : "no"});
      const double skin = chosenSkin(scene, threads);
      if (skin > 0.0) addParts(scene, skin, parts);
    }
  }
  publish(inOptions, table, "memory");
  publish(inOptions, parts, "memory_parts");
}

}  // namespace sap_bench
