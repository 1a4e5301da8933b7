// What each of the engine's skips saves: boxes filtered out before the sweep, declared
// scenery, unchanged frames, the sequential path
// for small frames, and skin reuse at several motion speeds; and what large-world coordinates
// cost. Every row checks its pairs against the plain engine on the same frame (declared
// scenery: minus the scenery x scenery pairs it does not report; far-away sites: against the
// same site at the origin).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bench_output.h"
#include "core/frame/box_columns.h"
#include "core/frame/frame_plan.h"
#include "core/strategies/small_frame.h"
#include "core/tools/random.h"
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

// inTarget and inNote are the last columns, so the CSV keeps the columns it had before them.
void addRow(Table& ioTable, const std::string& inSkip, const std::string& inCase,
            const std::string& inSetting, double inMs, double inBaselineMs,
            const std::string& inPath, bool inMatches, const std::string& inTarget = "-",
            const std::string& inNote = "-") {
  ioTable.addRow({inSkip, inCase, inSetting, fmt(inMs), fmt(inBaselineMs),
                  fmtRatio(inBaselineMs, inMs), inPath, inMatches ? "ok" : "MISMATCH", inTarget,
                  inNote});
}

// The rows with a target run on 2 threads (the target is stated for 2), or on --threads.
BroadphaseConfig targetConfig(const Options& inOptions) {
  BroadphaseConfig config;
  config.threads = inOptions.threads > 0 ? inOptions.threads : 2;
  return config;
}

std::string verdict(bool inMet) {
  return inMet ? "met" : "missed";
}

// Copies the bounds of inFrom's boxes inFirst.. into ioTo's boxes inToFirst.. .
void copyBounds(const BoxSet& inFrom, std::size_t inFirst, BoxSet& ioTo, std::size_t inToFirst) {
  std::copy(inFrom.bounds.begin() + sap_broadphase::kBoundsPerBox * inFirst, inFrom.bounds.end(),
            ioTo.bounds.begin() + sap_broadphase::kBoundsPerBox * inToFirst);
}

// The engine without its coherence skips (no skin, no reuse of an identical frame): every
// frame swept, so that a row measures its own skip and nothing else.
BroadphaseConfig sweptEveryFrame() {
  BroadphaseConfig config;
  config.skin = 0.0;
  config.reuse_unchanged_frames = false;
  return config;
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
  Broadphase engine{sweptEveryFrame()}, baseline{sweptEveryFrame()};
  const double ms = timeFrames(
      engine, frames, [&](int) -> const BoxSet& { return boxes; }, matches, path);
  const double base = timeFrames(
      baseline, frames, [&](int) -> const BoxSet& { return unfiltered; }, baseline_matches,
      baseline_path);
  addRow(ioTable, "filters", "uniform n=" + fmtSize(n) + ", half with group 0",
         "filters tested in every strategy", ms, base, path, matches);
}

// Declared scenery: a uniform scene whose resting boxes are given once to setStaticBoxes() and
// only the movers to update(). Baseline: every box to update() each frame with the default
// configuration. The declared engine must report the baseline's pairs minus the scenery x
// scenery ones.
void declaredRows(const Options& inOptions, Table& ioTable) {
  const std::size_t resting = inOptions.size(1000000, 20000);
  const std::size_t moving = inOptions.size(1000, 200);
  SceneSimulator motion(uniform(resting + moving, 0.1, inOptions.seed));
  BoxSet everything = motion.boxes();
  BoxSet scenery, movers;
  scenery.reserve(resting);
  movers.reserve(moving);
  for (std::size_t i = 0; i < everything.size(); ++i) {
    const double lo[3] = {everything.lo(0, i), everything.lo(1, i), everything.lo(2, i)};
    const double hi[3] = {everything.hi(0, i), everything.hi(1, i), everything.hi(2, i)};
    (i < resting ? scenery : movers).add(everything.ids[i], lo, hi);
  }
  const BroadphaseConfig config = targetConfig(inOptions);
  Broadphase declared(config), baseline(config);
  const double declare_ms = millisecondsOf([&] { declared.setStaticBoxes(scenery); });
  const int frames = inOptions.framesOr(20, 3);
  std::vector<double> times, baseline_times;
  bool matches = true;
  std::size_t pairs_checked = 0;
  for (int f = 0; f <= frames; ++f) {
    if (f > 0) {
      motion.step();
      copyBounds(motion.boxes(), resting, movers, 0);
      copyBounds(motion.boxes(), resting, everything, resting);
    }
    PairList pairs;
    const double ms = millisecondsOf([&] { pairs = declared.update(movers); });
    PairList expected;
    const double base_ms = millisecondsOf([&] { expected = baseline.update(everything); });
    // The scene's ids are 0..n-1 with the scenery first, so a pair (a < b) is scenery x
    // scenery exactly when b < resting.
    expected.erase(
        std::remove_if(expected.begin(), expected.end(),
                       [&](const sap_broadphase::IdPair& inPair) { return inPair.b < resting; }),
        expected.end());
    matches = matches && pairs == expected;
    pairs_checked += expected.size();
    // Frame 0 is the first update() after the declaration: warm-up, as in every row.
    if (f > 0) {
      times.push_back(ms);
      baseline_times.push_back(base_ms);
    }
  }
  const double ms = median(times);
  addRow(ioTable, "declared scenery",
         fmtSize(resting) + " declared static + " + fmtSize(moving) + " moving",
         "setStaticBoxes once, movers to update()", ms, median(baseline_times),
         sap_broadphase::framePathName(declared.stats().path), matches,
         "<= 1 ms/frame on " + std::to_string(config.threads) + " threads: " + verdict(ms <= 1.0),
         "setStaticBoxes " + fmt(declare_ms) +
             " ms once; baseline all boxes to update(), "
             "default config; " +
             fmtCount(pairs_checked) + " pairs checked over " + std::to_string(frames + 1) +
             " frames");
}

// A dense small site far from the origin: 5 cm cubes at the stress test's density
// (StressMagnitudes.SmallBoxesAtEarthScaleCoordinates: 5000 boxes in a 10 m cube), each
// drifting up to 1 mm an axis per frame. Every coordinate is a multiple of 2^-20 m below 2^5 m
// and every offset a multiple of 2^-1 below 2^30, so each shifted coordinate needs at most
// 51 significant bits: the shift is exact (checked below) and a far site must report exactly
// the pairs of the site at the origin.
class DriftingSite {
 public:
  DriftingSite(std::size_t inCount, uint64_t inSeed) {
    constexpr double kStressDensity = 5000.0 / (10.0 * 10.0 * 10.0);  // boxes per m^3
    constexpr int64_t kUnitsPerMetre = int64_t{1} << 20;
    side_ = std::cbrt(static_cast<double>(inCount) / kStressDensity);
    sap_broadphase::SplitMix64 random(inSeed);
    const auto site_units = static_cast<uint64_t>(side_ * kUnitsPerMetre);
    const uint64_t drift_units = kUnitsPerMetre / 1000;  // 1 mm
    for (int axis = 0; axis < 3; ++axis) {
      start_[axis].resize(inCount);
      velocity_[axis].resize(inCount);
      for (std::size_t i = 0; i < inCount; ++i) {
        start_[axis][i] = static_cast<int64_t>(random.below(site_units));
        velocity_[axis][i] =
            static_cast<int64_t>(random.below(2 * drift_units + 1)) - int64_t(drift_units);
      }
    }
    edge_units_ = kUnitsPerMetre / 20;  // 5 cm
  }
  double side() const { return side_; }
  /// Frame inFrame shifted by inOffset into ioBoxes; false when a shift was not exact.
  bool frame(int inFrame, const double inOffset[3], BoxSet& ioBoxes) const {
    constexpr double kMetresPerUnit = 0x1p-20;
    const std::size_t count = start_[0].size();
    if (ioBoxes.size() != count) {
      ioBoxes.clear();
      const double zero[3] = {0.0, 0.0, 0.0};
      for (std::size_t i = 0; i < count; ++i) ioBoxes.add(static_cast<uint32_t>(i), zero, zero);
    }
    bool exact = true;
    for (int axis = 0; axis < 3; ++axis) {
      const double offset = inOffset[axis];
      for (std::size_t i = 0; i < count; ++i) {
        const int64_t lo_units = start_[axis][i] + velocity_[axis][i] * inFrame;
        const double lo = static_cast<double>(lo_units) * kMetresPerUnit;
        const double hi = static_cast<double>(lo_units + edge_units_) * kMetresPerUnit;
        ioBoxes.lo(axis, i) = lo + offset;
        ioBoxes.hi(axis, i) = hi + offset;
        // Undoing the shift is exact (Sterbenz: the sum and the offset are within a factor
        // of 2), so getting the origin's value back proves the sum was not rounded.
        exact = exact && ioBoxes.lo(axis, i) - offset == lo && ioBoxes.hi(axis, i) - offset == hi;
      }
    }
    return exact;
  }

 private:
  double side_ = 0.0;
  std::vector<int64_t> start_[3];     // lower corners at frame 0, in 2^-20 m
  std::vector<int64_t> velocity_[3];  // per frame, in 2^-20 m
  int64_t edge_units_ = 0;
};

// The same drifting site at the origin, at UTM and ECEF coordinates and 1e9 m on every axis;
// the sites take turns within each frame so a busy machine slows them alike.
void largeWorldRows(const Options& inOptions, Table& ioTable) {
  struct Place {
    const char* name;
    double offset[3];
  };
  // UTM as the stress test places it (easting 500 km and a half metre, northing 5400 km).
  const std::vector<Place> places = {{"origin", {0.0, 0.0, 0.0}},
                                     {"UTM", {500000.5, 5.4e6, 120.0}},
                                     {"ECEF", {4.2e6, 1.1e6, 4.7e6}},
                                     {"1e9 every axis", {1e9, 1e9, 1e9}}};
  const std::size_t n = inOptions.size(std::size_t{1} << 16, std::size_t{1} << 12);
  const DriftingSite site(n, inOptions.seed);
  // Steady frames take about 2 ms; many of them keep the median, and so the ratios, steady on
  // a shared machine.
  const int frames = inOptions.framesOr(60, 4);
  const BroadphaseConfig config = targetConfig(inOptions);
  // The origin's pairs are checked against Algorithm 1 with no skin, another code path.
  BroadphaseConfig independent = config;
  independent.method = sap_broadphase::Method::kSequential;
  independent.skin = 0.0;
  Broadphase reference(independent);
  std::vector<Broadphase> engines;
  for (std::size_t p = 0; p < places.size(); ++p) engines.emplace_back(config);
  std::vector<std::vector<double>> times(places.size());
  std::vector<bool> matches(places.size(), true), exact(places.size(), true);
  std::size_t pairs_checked = 0;
  BoxSet boxes;
  for (int f = 0; f <= frames; ++f) {
    PairList at_origin;
    for (std::size_t p = 0; p < places.size(); ++p) {
      exact[p] = site.frame(f, places[p].offset, boxes) && exact[p];
      PairList pairs;
      const double ms = millisecondsOf([&] { pairs = engines[p].update(boxes); });
      if (f > 0) times[p].push_back(ms);
      if (p == 0) {
        at_origin = pairs;
        matches[p] = matches[p] && pairs == reference.update(boxes);
        pairs_checked += pairs.size();
      } else {
        matches[p] = matches[p] && pairs == at_origin;
      }
    }
  }
  const double origin_ms = median(times[0]);
  const std::string scene = fmtSize(n) + " 5 cm cubes, " + fmt(site.side(), 3) + " m site";
  for (std::size_t p = 0; p < places.size(); ++p) {
    const double ms = median(times[p]);
    const auto& offset = places[p].offset;
    const std::string setting = std::string(places[p].name) +
                                (p == 0 ? ""
                                        : " (" + fmt(offset[0], 7) + ", " + fmt(offset[1], 7) +
                                              ", " + fmt(offset[2], 7) + ")");
    const std::string target = p == 0 ? "-" : "<= 1.25x origin: " + verdict(ms <= 1.25 * origin_ms);
    const std::string note =
        p == 0 ? fmtCount(pairs_checked) + " pairs over " + std::to_string(frames + 1) +
                     " frames, as Algorithm 1 without skin"
               : fmtRatio(ms, origin_ms) + "x origin; " +
                     (exact[p] ? "exact shift, pairs as at the origin" : "SHIFT NOT EXACT");
    addRow(ioTable, "large world", scene, setting, ms, origin_ms,
           sap_broadphase::framePathName(engines[p].stats().path), matches[p] && exact[p], target,
           note);
  }
}

// The same frame twice in a row.
void unchangedRows(const Options& inOptions, Table& ioTable) {
  const std::size_t n = inOptions.size(std::size_t{1} << 18, std::size_t{1} << 13);
  const BoxSet boxes = SceneSimulator(uniform(n, 0.2, inOptions.seed)).boxes();
  BroadphaseConfig reusing = sweptEveryFrame();
  reusing.reuse_unchanged_frames = true;
  Broadphase engine(reusing), baseline{sweptEveryFrame()};
  bool matches = false, baseline_matches = false;
  std::string path, baseline_path;
  const int frames = inOptions.framesOr(5, 3);
  const auto same = [&](int) -> const BoxSet& { return boxes; };
  const double ms = timeFrames(engine, frames, same, matches, path);
  const double base = timeFrames(baseline, frames, same, baseline_matches, baseline_path);
  addRow(ioTable, "unchanged frame", "uniform n=" + fmtSize(n) + ", same frame again",
         "reuse_unchanged_frames", ms, base, path, matches);
}

// The small-frame path (small_frame.h) against the sweep on one thread (Algorithm 1) and on
// every thread (Algorithms 2-4), every frame swept (no skin, no reuse): where each crossover
// of Method::kAuto lies (takesSmallFrameKernel). The note says which path the default takes.
void smallFrameRows(const Options& inOptions, Table& ioTable) {
  const int frames = inOptions.framesOr(30, 5);
  for (std::size_t n : {256u, 1024u, 2048u, 4096u, 8192u, 16384u, 32768u, 65536u}) {
    SceneSimulator scene(uniform(n, 0.2, inOptions.seed));
    std::vector<BoxSet> moving_frames;
    for (int f = 0; f <= frames; ++f, scene.step()) moving_frames.push_back(scene.boxes());
    const auto frame = [&](int f) -> const BoxSet& { return moving_frames[f]; };
    // The small-frame path reads the engine's columns, as update() hands them to it.
    std::vector<sap_broadphase::BoxColumns> moving_columns;
    for (const BoxSet& boxes : moving_frames)
      moving_columns.push_back(sap_broadphase::columnsOf(boxes));
    std::vector<double> small_times;
    bool small_matches = true;
    sap_broadphase::SmallFrameWorkspace workspace;
    Broadphase reference{BroadphaseConfig()};
    for (int f = 0; f <= frames; ++f) {
      PairList pairs;
      const double ms = millisecondsOf(
          [&] { sap_broadphase::pairSmallFrame(moving_columns[f], workspace, pairs); });
      if (f > 0) small_times.push_back(ms);
      small_matches = small_matches && pairs == reference.update(frame(f));
    }
    const double small_ms = median(small_times);
    for (const sap_broadphase::Method method :
         {sap_broadphase::Method::kSequential, sap_broadphase::Method::kParallel}) {
      BroadphaseConfig sweep;
      sweep.method = method;
      sweep.threads = inOptions.threads;
      sweep.skin = 0.0;
      sweep.reuse_unchanged_frames = false;
      Broadphase engine(sweep);
      bool matches = false;
      std::string path;
      const double ms = timeFrames(engine, frames, frame, matches, path);
      const int threads = method == sap_broadphase::Method::kParallel
                              ? sap_broadphase::resolveThreadCount(inOptions.threads)
                              : 1;
      const bool takes_small =
          sap_broadphase::takesSmallFrameKernel(sap_broadphase::BroadphaseConfig(), n, threads);
      addRow(ioTable, "small frame", "uniform n=" + fmtSize(n) + ", d=0.2",
             "small-frame path vs " + path + " sweep", small_ms, ms, "small",
             matches && small_matches, "-",
             "default on " + std::to_string(threads) + " thread(s) takes the " +
                 (takes_small ? "small-frame path" : "sweep"));
    }
  }
}

// Skin reuse at three motion speeds (mean box edges per frame): four fixed skins and the
// automatic one against no skin.
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
    Broadphase baseline{sweptEveryFrame()};
    bool baseline_matches = false;
    std::string baseline_path;
    const double base = timeFrames(baseline, frames, frame, baseline_matches, baseline_path);
    // Fixed skins, then the default's automatic one (-1).
    for (double skin : {0.05, 0.2, 0.5, 1.0, -1.0}) {
      BroadphaseConfig config;
      if (skin >= 0.0) config.skin = skin;
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
             (skin >= 0.0 ? "skin " + fmt(skin, 2) : std::string("automatic skin (default)")) +
                 " (" + std::to_string(skin_frames) + "/" + std::to_string(frames + 1) +
                 " frames reused)",
             total / times.size(), base, "mean over frames", matches);
    }
  }
}

}  // namespace

void runSkips(const Options& inOptions) {
  Table table("Skips: ms per frame with the skip and without it (median unless said)",
              {"skip", "case", "setting", "ms", "baseline_ms", "speedup", "path", "check", "target",
               "note"});
  filterRows(inOptions, table);
  unchangedRows(inOptions, table);
  smallFrameRows(inOptions, table);
  skinRows(inOptions, table);
  declaredRows(inOptions, table);
  largeWorldRows(inOptions, table);
  publish(inOptions, table, "skips");
}

}  // namespace sap_bench
