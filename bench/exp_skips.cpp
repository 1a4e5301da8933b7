// What each of the engine's skips saves: boxes filtered out before the sweep, a
// static index for resting scenery, unchanged frames, the sequential path for small frames,
// and skin reuse at several motion speeds. Every row checks its pairs against the plain
// engine on the same frame.
#include <algorithm>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "bench_output.h"
#include "experiments.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/scenes.h"

namespace sap_bench {
namespace {

using sap_broadphase::BoxSet;
using sap_broadphase::Broadphase;
using sap_broadphase::BroadphaseConfig;
using sap_broadphase::PairList;
using sap_broadphase::SceneConfig;
using sap_broadphase::SceneSimulator;

double millisecondsOf(const std::function<void()>& inWork) {
  const auto start = std::chrono::steady_clock::now();
  inWork();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

double median(std::vector<double> inValues) {
  if (inValues.empty()) return 0.0;
  std::sort(inValues.begin(), inValues.end());
  return inValues[inValues.size() / 2];
}

SceneConfig uniform(std::size_t inBoxes, double inDensity, uint64_t inSeed) {
  SceneConfig scene;
  scene.n = inBoxes;
  scene.density = inDensity;
  scene.seed = inSeed;
  return scene;
}

// Median ms per frame of inEngine over inFrames frames made by inFrame(f), after one warm-up
// frame; also checks every frame's pairs against a plain engine. outMatches turns false on a
// difference.
double timeFrames(Broadphase& ioEngine, int inFrames,
                  const std::function<const BoxSet&(int)>& inFrame, bool& outMatches,
                  std::string& outPath) {
  Broadphase reference{BroadphaseConfig()};
  std::vector<double> times;
  outMatches = true;
  for (int f = 0; f <= inFrames; ++f) {
    const BoxSet& boxes = inFrame(f);
    PairList pairs;
    const double ms = millisecondsOf([&] { pairs = ioEngine.update(boxes); });
    if (f > 0) times.push_back(ms);
    outMatches = outMatches && pairs == reference.update(boxes);
  }
  outPath = sap_broadphase::framePathName(ioEngine.stats().path);
  return median(times);
}

void addRow(Table& ioTable, const std::string& inSkip, const std::string& inCase,
            const std::string& inSetting, double inMs, double inBaselineMs,
            const std::string& inPath, bool inMatches) {
  ioTable.addRow({inSkip, inCase, inSetting, fmt(inMs), fmt(inBaselineMs),
                  fmtRatio(inBaselineMs, inMs), inPath, inMatches ? "ok" : "MISMATCH"});
}

// Half the boxes carry group 0 (they can pair with nothing).
void filterRows(const Options& inOptions, Table& ioTable) {
  const std::size_t n = inOptions.size(std::size_t{1} << 18, std::size_t{1} << 13);
  BoxSet boxes = SceneSimulator(uniform(n, 0.2, inOptions.seed)).boxes();
  boxes.groups.assign(n, 0x1);
  boxes.masks.assign(n, 0xFFFFFFFF);
  for (std::size_t i = 0; i < n; i += 2) boxes.groups[i] = 0;
  BoxSet unfiltered = boxes;
  unfiltered.groups.clear();
  unfiltered.masks.clear();
  const int frames = inOptions.framesOr(5, 3);
  bool matches = false, baseline_matches = false;
  std::string path, baseline_path;
  Broadphase engine{BroadphaseConfig()}, baseline{BroadphaseConfig()};
  const double ms = timeFrames(
      engine, frames, [&](int) -> const BoxSet& { return boxes; }, matches, path);
  const double base = timeFrames(
      baseline, frames, [&](int) -> const BoxSet& { return unfiltered; }, baseline_matches,
      baseline_path);
  addRow(ioTable, "filters", "uniform n=" + fmtSize(n) + ", half with group 0",
         "group-0 boxes dropped", ms, base, path, matches);
}

// Resting scenery (group 0x2, mask 0x1) and a few movers; baseline: the plain sweep.
void staticRows(const Options& inOptions, Table& ioTable) {
  const std::size_t resting = inOptions.size(1000000, 20000);
  const std::size_t moving = inOptions.size(1000, 200);
  SceneSimulator motion(uniform(resting + moving, 0.1, inOptions.seed));
  BoxSet frame = motion.boxes();
  frame.groups.assign(frame.size(), 0x1);
  frame.masks.assign(frame.size(), 0xFFFFFFFF);
  for (std::size_t i = 0; i < resting; ++i) {
    frame.groups[i] = 0x2;
    frame.masks[i] = 0x1;
  }
  const auto makeFrame = [&](int) -> const BoxSet& {
    motion.step();
    for (std::size_t i = resting; i < frame.size(); ++i)
      for (int axis = 0; axis < 3; ++axis) {
        frame.lo[axis][i] = motion.boxes().lo[axis][i];
        frame.hi[axis][i] = motion.boxes().hi[axis][i];
      }
    return frame;
  };
  const int frames = inOptions.framesOr(6, 3);
  BroadphaseConfig indexed;
  indexed.index_static_boxes = true;
  Broadphase engine(indexed), baseline{BroadphaseConfig()};
  bool matches = false, baseline_matches = false;
  std::string path, baseline_path;
  // The first frame builds the index; the median covers the steady frames after it.
  const double ms = timeFrames(engine, frames + 1, makeFrame, matches, path);
  const double base = timeFrames(baseline, frames, makeFrame, baseline_matches, baseline_path);
  addRow(ioTable, "static boxes", fmtSize(resting) + " resting + " + fmtSize(moving) + " moving",
         "index_static_boxes", ms, base, path, matches);
}

// The same frame twice in a row.
void unchangedRows(const Options& inOptions, Table& ioTable) {
  const std::size_t n = inOptions.size(std::size_t{1} << 18, std::size_t{1} << 13);
  const BoxSet boxes = SceneSimulator(uniform(n, 0.2, inOptions.seed)).boxes();
  BroadphaseConfig reusing;
  reusing.reuse_unchanged_frames = true;
  Broadphase engine(reusing), baseline{BroadphaseConfig()};
  bool matches = false, baseline_matches = false;
  std::string path, baseline_path;
  const int frames = inOptions.framesOr(5, 3);
  const auto same = [&](int) -> const BoxSet& { return boxes; };
  const double ms = timeFrames(engine, frames, same, matches, path);
  const double base = timeFrames(baseline, frames, same, baseline_matches, baseline_path);
  addRow(ioTable, "unchanged frame", "uniform n=" + fmtSize(n) + ", same frame again",
         "reuse_unchanged_frames", ms, base, path, matches);
}

// Sequential against parallel for small frames: where the parallel path starts to pay.
void smallFrameRows(const Options& inOptions, Table& ioTable) {
  const int frames = inOptions.framesOr(30, 5);
  for (std::size_t n : {256u, 1024u, 2048u, 4096u, 8192u, 16384u, 32768u}) {
    SceneSimulator scene(uniform(n, 0.2, inOptions.seed));
    std::vector<BoxSet> moving_frames;
    for (int f = 0; f <= frames; ++f, scene.step()) moving_frames.push_back(scene.boxes());
    BroadphaseConfig sequential, parallel;
    sequential.method = sap_broadphase::Method::kSequential;
    parallel.method = sap_broadphase::Method::kParallel;
    Broadphase engine(sequential), baseline(parallel);
    bool matches = false, baseline_matches = false;
    std::string path, baseline_path;
    const auto frame = [&](int f) -> const BoxSet& { return moving_frames[f]; };
    const double ms = timeFrames(engine, frames, frame, matches, path);
    const double base = timeFrames(baseline, frames, frame, baseline_matches, baseline_path);
    addRow(ioTable, "small frame", "uniform n=" + fmtSize(n), "sequential vs parallel", ms, base,
           path, matches && baseline_matches);
  }
}

// Skin reuse at three motion speeds (mean box edges per frame) and four skins.
void skinRows(const Options& inOptions, Table& ioTable) {
  const std::size_t n = inOptions.size(std::size_t{1} << 17, std::size_t{1} << 12);
  const int frames = inOptions.framesOr(40, 10);
  for (double speed : {0.01, 0.05, 0.2}) {
    SceneConfig scene_config = uniform(n, 0.2, inOptions.seed);
    scene_config.speed = speed;
    SceneSimulator scene(scene_config);
    std::vector<BoxSet> moving_frames;
    for (int f = 0; f <= frames; ++f, scene.step()) moving_frames.push_back(scene.boxes());
    const auto frame = [&](int f) -> const BoxSet& { return moving_frames[f]; };
    Broadphase baseline{BroadphaseConfig()};
    bool baseline_matches = false;
    std::string baseline_path;
    const double base = timeFrames(baseline, frames, frame, baseline_matches, baseline_path);
    for (double skin : {0.05, 0.2, 0.5, 1.0}) {
      BroadphaseConfig config;
      config.skin = skin;
      Broadphase engine(config);
      bool matches = false;
      std::string path;
      std::vector<double> times;
      Broadphase reference{BroadphaseConfig()};
      int skin_frames = 0;
      for (int f = 0; f <= frames; ++f) {
        PairList pairs;
        const double ms = millisecondsOf([&] { pairs = engine.update(moving_frames[f]); });
        skin_frames += engine.stats().path == sap_broadphase::FramePath::kSkin;
        if (f > 0) times.push_back(ms);
        matches = (f == 0 || matches) && pairs == reference.update(moving_frames[f]);
      }
      // Mean, not median: the point is the average over sweep frames and reuse frames.
      double total = 0.0;
      for (double t : times) total += t;
      addRow(ioTable, "skin", "uniform n=" + fmtSize(n) + ", speed " + fmt(speed, 2),
             "skin " + fmt(skin, 2) + " (" + std::to_string(skin_frames) + "/" +
                 std::to_string(frames + 1) + " frames reused)",
             total / times.size(), base, "mean over frames", matches);
    }
  }
}

}  // namespace

void runSkips(const Options& inOptions) {
  Table table("Skips: ms per frame with the skip and without it (median unless said)",
              {"skip", "case", "setting", "ms", "baseline_ms", "speedup", "path", "check"});
  filterRows(inOptions, table);
  unchangedRows(inOptions, table);
  smallFrameRows(inOptions, table);
  skinRows(inOptions, table);
  staticRows(inOptions, table);
  publish(inOptions, table, "skips");
}

}  // namespace sap_bench
