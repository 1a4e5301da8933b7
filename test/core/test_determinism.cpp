// Determinism: a fixed sequence of frames gives pair lists whose hash is pinned below, for
// every thread count 1..7, every axis pair and every path the engine can take (sequential,
// parallel, brute, reused, skin kept fixed or chosen automatically, declared
// scenery). The oracle agrees with the pinned hash too, so a change in the results is
// caught even where the oracle and the engine would change together (a scene or filter rule).
#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/scenes.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::engineConfig;
using test_support::firstDifference;
using test_support::hashPairSequence;
using test_support::PathCounts;

// hashPairSequence of bruteForcePairs over determinismFrames(), computed once from the oracle
// and pinned: a different value means the scenes, the filters or the pair order changed.
constexpr uint64_t kPinnedSequenceHash = 0x118A34B2399C2953ull;

constexpr std::size_t kBoxes = 6000;
constexpr std::size_t kResting = 4500;  // boxes 0..4499 rest: scenery, pairs with movers only
constexpr uint32_t kSceneryGroup = 0x2;
constexpr uint32_t kMoverGroup = 0x1;

// The boxes of frame inFrame of a uniform scene: the first kResting keep their frame-0 bounds
// and pair only with movers (the static index's case); every 50th mover collides with
// nothing (group 0 or mask 0).
BoxSet determinismFrame(SceneSimulator& ioScene, const BoxSet& inFirst) {
  BoxSet boxes = ioScene.boxes();
  boxes.groups.assign(boxes.size(), kMoverGroup);
  boxes.masks.assign(boxes.size(), kDefaultMask);
  for (std::size_t i = 0; i < kResting; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      boxes.lo(axis, i) = inFirst.lo(axis, i);
      boxes.hi(axis, i) = inFirst.hi(axis, i);
    }
    boxes.groups[i] = kSceneryGroup;
    boxes.masks[i] = kMoverGroup;
  }
  for (std::size_t i = kResting; i < boxes.size(); i += 50) {
    if (i % 100 == 0)
      boxes.groups[i] = 0;
    else
      boxes.masks[i] = 0;
  }
  return boxes;
}

// Five frames: the scene moving, with frame 1 given twice (an unchanged frame).
std::vector<BoxSet> determinismFrames() {
  SceneConfig config;
  config.kind = SceneKind::kUniform;
  config.n = kBoxes;
  config.density = 0.25;
  config.seed = 99;
  SceneSimulator scene(config);
  const BoxSet first = scene.boxes();
  std::vector<BoxSet> frames;
  for (int step = 0; step < 4; ++step) {
    frames.push_back(determinismFrame(scene, first));
    if (step == 1) frames.push_back(frames.back());
    scene.step();
  }
  return frames;
}

// The boxes from kResting on: what update() gets once the resting ones are declared scenery.
BoxSet movers(const BoxSet& inBoxes) {
  BoxSet moving;
  for (std::size_t i = kResting; i < inBoxes.size(); ++i) {
    const double lo[3] = {inBoxes.lo(0, i), inBoxes.lo(1, i), inBoxes.lo(2, i)};
    const double hi[3] = {inBoxes.hi(0, i), inBoxes.hi(1, i), inBoxes.hi(2, i)};
    moving.add(inBoxes.ids[i], lo, hi, inBoxes.group(i), inBoxes.mask(i));
  }
  return moving;
}

BoxSet scenery(const BoxSet& inBoxes) {
  BoxSet resting = inBoxes;
  resting.bounds.resize(kBoundsPerBox * kResting);
  resting.ids.resize(kResting);
  resting.groups.resize(kResting);
  resting.masks.resize(kResting);
  return resting;
}

// One way of running the engine over the frames, and the path it must take at least once
// (nothing for the automatic skin: whether a skin pays is the engine's choice per frame, and
// the hash must be the same whichever it makes).
struct PathCase {
  std::string name;
  std::optional<FramePath> path;
  std::function<void(BroadphaseConfig&)> configure;
  bool declared_scenery = false;
};

std::vector<PathCase> pathCases() {
  const auto method = [](Method inMethod) {
    return [inMethod](BroadphaseConfig& ioConfig) {
      ioConfig.method = inMethod;
      ioConfig.skin = 0.0;
    };
  };
  return {
      {"sequential", FramePath::kSequential, method(Method::kSequential)},
      {"parallel", FramePath::kParallel, method(Method::kParallel)},
      {"brute", FramePath::kBruteForce, method(Method::kBruteForce)},
      {"reused", FramePath::kReused,
       [](BroadphaseConfig& ioConfig) {
         ioConfig.skin = 0.0;
         ioConfig.reuse_unchanged_frames = true;
       }},
      {"fixed skin", FramePath::kSkin, [](BroadphaseConfig& ioConfig) { ioConfig.skin = 0.6; }},
      {"automatic skin", std::nullopt, [](BroadphaseConfig& ioConfig) { ioConfig.skin.reset(); }},
      {"declared scenery", FramePath::kParallel, method(Method::kParallel), true},
  };
}

// Runs inCase with inThreads threads over inFrames: every frame's pairs, the paths counted.
std::vector<PairList> runCase(const PathCase& inCase, int inThreads,
                              const std::vector<BoxSet>& inFrames, PathCounts& outPaths) {
  BroadphaseConfig config = engineConfig(Method::kAuto, inThreads, 0, 1);
  config.parallel_min_boxes = 1000;
  inCase.configure(config);
  Broadphase engine(config);
  if (inCase.declared_scenery) engine.setStaticBoxes(scenery(inFrames.front()));
  std::vector<PairList> pairs;
  for (const BoxSet& frame : inFrames) {
    pairs.push_back(engine.update(inCase.declared_scenery ? movers(frame) : frame));
    outPaths.add(engine.stats());
    if (inCase.declared_scenery) {
      EXPECT_EQ(engine.stats().static_boxes, kResting) << inCase.name;
    }
  }
  return pairs;
}

std::vector<PairList> oraclePairs(const std::vector<BoxSet>& inFrames) {
  std::vector<PairList> pairs;
  for (const BoxSet& frame : inFrames) pairs.push_back(bruteForcePairs(frame));
  return pairs;
}

// The first frame and pair where inActual departs from the oracle, for failure messages.
std::string whereItDiffers(const std::vector<PairList>& inOracle,
                           const std::vector<PairList>& inActual) {
  for (std::size_t f = 0; f < inOracle.size(); ++f) {
    const std::string difference = firstDifference(inOracle[f], inActual[f]);
    if (!difference.empty()) return "frame " + std::to_string(f) + ", " + difference;
  }
  return "every frame equals the oracle";
}

TEST(Determinism, OracleGivesThePinnedHash) {
  EXPECT_EQ(hashPairSequence(oraclePairs(determinismFrames())), kPinnedSequenceHash)
      << "the scene sequence or the oracle changed: recompute the pinned hash only if that "
         "change is meant";
}

TEST(Determinism, EveryPathAndThreadCountGivesThePinnedHash) {
  const std::vector<BoxSet> frames = determinismFrames();
  const std::vector<PairList> oracle = oraclePairs(frames);
  for (const PathCase& path_case : pathCases()) {
    for (int threads = 1; threads <= 7; ++threads) {
      PathCounts paths;
      const std::vector<PairList> pairs = runCase(path_case, threads, frames, paths);
      EXPECT_EQ(hashPairSequence(pairs), kPinnedSequenceHash)
          << path_case.name << ", " << threads
          << " threads; first difference from the oracle: " << whereItDiffers(oracle, pairs);
      if (path_case.path) {
        EXPECT_GT(paths[*path_case.path], 0)
            << path_case.name << ", " << threads << " threads took " << paths.summary();
      }
    }
  }
}

TEST(Determinism, EveryAxisPairGivesThePinnedHash) {
  const std::vector<BoxSet> frames = determinismFrames();
  const std::vector<PairList> oracle = oraclePairs(frames);
  for (const auto& [primary, secondary] : test_support::allAxisPairs()) {
    for (int threads : {1, 2, 5}) {
      for (Method method : {Method::kParallel, Method::kSequential}) {
        Broadphase engine(engineConfig(method, threads, primary, secondary));
        std::vector<PairList> pairs;
        for (const BoxSet& frame : frames) pairs.push_back(engine.update(frame));
        EXPECT_EQ(hashPairSequence(pairs), kPinnedSequenceHash)
            << test_support::describe(engineConfig(method, threads, primary, secondary))
            << "; first difference from the oracle: " << whereItDiffers(oracle, pairs);
      }
    }
  }
}

TEST(Determinism, RepeatedRunsGiveIdenticalOutput) {
  const BoxSet boxes = test_support::latticeBoxes(8000, 30, 2, 5);
  Broadphase first(engineConfig(Method::kParallel, 7, 0, 1));
  const PairList reference = first.update(boxes);
  for (int run = 0; run < 5; ++run) {
    Broadphase again(engineConfig(Method::kParallel, 7, 0, 1));
    ASSERT_EQ(again.update(boxes), reference) << "run " << run;
    ASSERT_EQ(first.update(boxes), reference) << "reused, run " << run;
  }
}

}  // namespace
}  // namespace sap_broadphase
