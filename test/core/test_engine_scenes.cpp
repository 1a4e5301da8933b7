// The engine against the oracle on the paper's scenes, and over frame sequences: one Broadphase
// reused while boxes move, and while boxes are added, removed, reordered and renamed.
#include <gtest/gtest.h>
#include <omp.h>

#include <string>
#include <vector>

#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/scenes.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::describe;
using test_support::engineConfig;
using test_support::samePairs;

/// Engines that persist across frames: parallel at several thread counts and axes, sequential,
/// and the adaptive default.
std::vector<BroadphaseConfig> persistentConfigs() {
  return {
      engineConfig(Method::kParallel, 1, 0, 1),    engineConfig(Method::kParallel, 2, 1, 2),
      engineConfig(Method::kParallel, 3, 2, 0),    engineConfig(Method::kParallel, 4, 0, 2),
      engineConfig(Method::kParallel, 7, 2, 1),    engineConfig(Method::kSequential, 1, 1, 0),
      engineConfig(Method::kAuto, 2, 0, 1),        engineConfig(Method::kParallel, 2, 0, 1, 1),
      engineConfig(Method::kParallel, 3, 1, 0, 9), engineConfig(Method::kSequential, 1, 0, 1, 64)};
}

/// Feeds every frame of inFrames to one engine per config, expecting the oracle every time.
void expectFramesMatch(const std::vector<BoxSet>& inFrames, const std::string& inLabel) {
  std::vector<PairList> oracles;
  for (const BoxSet& frame : inFrames) oracles.push_back(bruteForcePairs(frame));
  for (const BroadphaseConfig& config : persistentConfigs()) {
    Broadphase broadphase(config);
    for (std::size_t f = 0; f < inFrames.size(); ++f) {
      ASSERT_TRUE(samePairs(oracles[f], broadphase.update(inFrames[f])))
          << inLabel << ", frame " << f << ", " << describe(config);
    }
  }
}

TEST(EngineScenes, UniformAtSeveralDensitiesWithMotion) {
  for (double density : {0.01, 0.1, 0.35, 1.0}) {
    SceneConfig config;
    config.kind = SceneKind::kUniform;
    config.n = 3000;
    config.density = density;
    config.seed = 11;
    config.speed = 0.5;  // fast, so frames differ a lot
    SceneSimulator scene(config);
    std::vector<BoxSet> frames;
    for (int f = 0; f < 6; ++f) {
      frames.push_back(scene.boxes());
      scene.step();
    }
    expectFramesMatch(frames, "uniform d=" + std::to_string(density));
  }
}

TEST(EngineScenes, BallClusterThroughContractionAndSpread) {
  SceneConfig config;
  config.kind = SceneKind::kBallCluster;
  config.n = 3000;
  config.seed = 3;
  config.frames = 200;
  std::vector<BoxSet> frames;
  for (int frame : {0, 20, 38, 40, 41, 44, 48, 49, 60, 100, 199})
    frames.push_back(makeSceneFrame(config, frame));
  expectFramesMatch(frames, "ball");
}

TEST(EngineScenes, PlaneClusterOnEveryAxisThroughMidRun) {
  for (int axis = 0; axis < 3; ++axis) {
    SceneConfig config;
    config.kind = SceneKind::kPlaneCluster;
    config.n = 55 * 55;
    config.seed = 4;
    config.plane_axis = axis;
    config.frames = 100;
    std::vector<BoxSet> frames;
    for (int frame : {0, 30, 45, 49, 50, 51, 55, 70, 99})
      frames.push_back(makeSceneFrame(config, frame));
    expectFramesMatch(frames, "plane u=" + std::to_string(axis));
  }
}

TEST(EngineScenes, ConsecutiveFramesOfEveryScene) {
  // Consecutive frames give the partition bounds real temporal coherence to work with.
  for (SceneKind kind : {SceneKind::kUniform, SceneKind::kBallCluster, SceneKind::kPlaneCluster}) {
    SceneConfig config;
    config.kind = kind;
    config.n = 4900;
    config.density = 0.2;
    config.seed = 21;
    config.frames = 60;
    SceneSimulator scene(config);
    scene.advanceTo(20);
    std::vector<BoxSet> frames;
    for (int f = 0; f < 12; ++f) {
      frames.push_back(scene.boxes());
      scene.step();
    }
    expectFramesMatch(frames, "consecutive kind " + std::to_string(static_cast<int>(kind)));
  }
}

TEST(EngineScenes, BoxesAddedRemovedReorderedBetweenFrames) {
  SceneConfig config;
  config.kind = SceneKind::kUniform;
  config.n = 5000;
  config.density = 0.3;
  config.seed = 8;
  config.speed = 0.2;
  SceneSimulator scene(config);
  std::vector<BoxSet> frames;
  const double keep[] = {1.0, 0.9, 0.3, 0.95, 1.0, 0.0, 0.6, 1.0, 0.05, 0.99};
  for (int f = 0; f < 10; ++f) {
    // Stable ids (a box keeps its id while it exists), random order, varying counts.
    frames.push_back(test_support::shuffledSubset(scene.boxes(), keep[f], false, 100 + f));
    scene.step();
  }
  expectFramesMatch(frames, "subsets with stable ids");
  std::vector<BoxSet> renamed;
  for (int f = 0; f < 6; ++f) {
    // Fresh sparse random ids every frame: nothing about identity carries over.
    renamed.push_back(test_support::shuffledSubset(scene.boxes(), keep[f], true, 200 + f));
    scene.step();
  }
  expectFramesMatch(renamed, "subsets with sparse random ids");
}

TEST(EngineScenes, GrowingAndShrinkingAcrossTheAutoThreshold) {
  // kAuto switches between the sequential and parallel paths as n crosses parallel_min_boxes.
  const std::size_t threshold = BroadphaseConfig().parallel_min_boxes;
  std::vector<BoxSet> frames;
  for (std::size_t n : {std::size_t{100}, threshold + 900, threshold - 1, threshold, threshold + 1,
                        std::size_t{0}, threshold + 1900, std::size_t{1}, threshold + 900}) {
    frames.push_back(test_support::randomBoxes(n, 24.0, 1.0, n + 3));
  }
  expectFramesMatch(frames, "growing and shrinking");
}

TEST(EngineScenes, PairingLayoutOfTheLastFrameOutgrownAndReused) {
  // The parallel pairing scatters into segments sized from the last frame when its rank split
  // is the same: a nearly repeated frame fits, a frame far denser (candidate ranges many times
  // longer) outgrows them and is scattered again from counts, a sparser one fits loosely.
  // Same box count throughout, so the split stays the same; several partitions per thread. A
  // world of 0 repeats the last frame with one box moved (an unchanged frame is not swept).
  const std::size_t n = 6000;
  std::vector<BoxSet> frames;
  for (double world : {30.0, 0.0, 9.0, 0.0, 30.0, 60.0, 9.0, 5.0, 30.0, 0.0, 9.0}) {
    if (world > 0) {
      frames.push_back(test_support::randomBoxes(n, world, 1.5, static_cast<uint64_t>(world)));
    } else {
      frames.push_back(frames.back());
      frames.back().lo(0, 0) -= 0.25;
    }
  }
  std::vector<PairList> oracles;
  for (const BoxSet& frame : frames) oracles.push_back(bruteForcePairs(frame));
  for (int threads : {1, 2, 3, 4}) {
    Broadphase broadphase(engineConfig(Method::kParallel, threads, 0, 1));
    for (std::size_t f = 0; f < frames.size(); ++f) {
      ASSERT_TRUE(samePairs(oracles[f], broadphase.update(frames[f])))
          << "frame " << f << ", " << threads << " threads";
    }
  }
}

TEST(EngineScenes, UpdateInsideAnotherParallelRegion) {
  // Nested regions inactive (the default): every parallel phase gets a team of one thread
  // however many it asks for, and must still cover all of its slices.
  const int saved_levels = omp_get_max_active_levels();
  omp_set_max_active_levels(1);
  SceneConfig config;
  config.kind = SceneKind::kBallCluster;
  config.n = 6000;
  config.seed = 12;
  config.frames = 100;
  std::vector<BoxSet> frames;
  std::vector<PairList> oracles;
  for (int frame : {10, 11, 12, 30}) {
    frames.push_back(makeSceneFrame(config, frame));
    oracles.push_back(bruteForcePairs(frames.back()));
  }
  int mismatches = 0;
#pragma omp parallel num_threads(2) reduction(+ : mismatches)
  for (int threads : {2, 3}) {
    BroadphaseConfig engine = engineConfig(Method::kParallel, threads, 0, 1);
    engine.skin = 0.0;  // every frame swept
    Broadphase broadphase(engine);
    for (std::size_t f = 0; f < frames.size(); ++f)
      mismatches += !samePairs(oracles[f], broadphase.update(frames[f]));
  }
  omp_set_max_active_levels(saved_levels);
  EXPECT_EQ(mismatches, 0);
}

TEST(EngineScenes, ResetForgetsTemporalStateOnly) {
  const BoxSet first = test_support::randomBoxes(5000, 12.0, 1.0, 1);
  const BoxSet second = test_support::randomBoxes(5000, 12.0, 1.0, 2);
  Broadphase broadphase(engineConfig(Method::kParallel, 3, 0, 1));
  EXPECT_TRUE(samePairs(bruteForcePairs(first), broadphase.update(first)));
  broadphase.reset();
  EXPECT_TRUE(samePairs(bruteForcePairs(second), broadphase.update(second)));
  EXPECT_TRUE(samePairs(bruteForcePairs(first), broadphase.update(first)));
}

}  // namespace
}  // namespace sap_broadphase
