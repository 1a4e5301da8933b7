// Work the engine skips must not change a single pair: unchanged frames (reused), skin reuse
// over moving frames, and boxes whose group or mask is 0 (never swept).
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <vector>

#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/scenes.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::engineConfig;
using test_support::movingScene;

TEST(UnchangedFrame, SecondIdenticalFrameIsReusedAndExact) {
  SceneSimulator scene(movingScene(SceneKind::kUniform, 5));
  BroadphaseConfig config = engineConfig(Method::kAuto, 2, 0, 1);
  config.reuse_unchanged_frames = true;
  Broadphase broadphase(config);
  const PairList first = broadphase.update(scene.boxes());
  EXPECT_NE(broadphase.stats().path, FramePath::kReused);
  EXPECT_EQ(broadphase.update(scene.boxes()), first);
  EXPECT_EQ(broadphase.stats().path, FramePath::kReused);
  scene.step();
  EXPECT_EQ(broadphase.update(scene.boxes()), bruteForcePairs(scene.boxes()));
  EXPECT_NE(broadphase.stats().path, FramePath::kReused);
}

TEST(UnchangedFrame, OnByDefaultAndCanBeTurnedOff) {
  SceneSimulator scene(movingScene(SceneKind::kUniform, 6));
  Broadphase by_default(engineConfig(Method::kAuto, 2, 0, 1));
  by_default.update(scene.boxes());
  by_default.update(scene.boxes());
  EXPECT_EQ(by_default.stats().path, FramePath::kReused);
  BroadphaseConfig config = engineConfig(Method::kAuto, 2, 0, 1);
  config.reuse_unchanged_frames = false;
  Broadphase without_reuse(config);
  without_reuse.update(scene.boxes());
  without_reuse.update(scene.boxes());
  EXPECT_NE(without_reuse.stats().path, FramePath::kReused);
}

// Every frame of every scene exact, with boxes added and jumping now and then, for skins
// too small to ever reuse, medium and large; a large skin must reuse most uniform frames.
TEST(SkinReuse, ExactOverMovingFramesAndReusesWhenBoxesStayInside) {
  const std::vector<int> thread_counts = {1, 2, 3};
  for (SceneKind kind : {SceneKind::kUniform, SceneKind::kBallCluster, SceneKind::kPlaneCluster}) {
    for (double skin : {0.05, 0.3, 1.0}) {
      SceneSimulator scene(movingScene(kind, 7));
      std::vector<Broadphase> engines;
      for (int threads : thread_counts) {
        BroadphaseConfig config = engineConfig(Method::kAuto, threads, 0, 1);
        config.skin = skin;
        config.parallel_min_boxes = 1000;
        config.reuse_unchanged_frames = threads == 2;
        engines.emplace_back(config);
      }
      std::vector<int> skin_frames(engines.size(), 0);
      for (int frame = 0; frame < 40; ++frame) {
        BoxSet boxes = scene.boxes();
        if (frame % 17 == 5) {
          const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
          boxes.add(900000 + frame, lo, hi);
        }
        if (frame % 13 == 7) boxes.hi(0, 3) += 10.0;  // one box jumps out of its skin
        const PairList oracle = bruteForcePairs(boxes);
        for (std::size_t e = 0; e < engines.size(); ++e) {
          ASSERT_EQ(engines[e].update(boxes), oracle)
              << "scene " << int(kind) << " skin " << skin << " threads " << thread_counts[e]
              << " frame " << frame << " path " << framePathName(engines[e].stats().path);
          skin_frames[e] += engines[e].stats().path == FramePath::kSkin;
        }
        scene.step();
      }
      if (kind == SceneKind::kUniform && skin == 1.0) {
        for (int count : skin_frames) EXPECT_GT(count, 20);
      }
    }
  }
}

TEST(SkinReuse, RejectsNegativeOrInfiniteSkin) {
  BroadphaseConfig config;
  config.skin = -1.0;
  EXPECT_THROW(Broadphase{config}, std::invalid_argument);
  config.skin = std::numeric_limits<double>::infinity();
  EXPECT_THROW(Broadphase{config}, std::invalid_argument);
}

// Boxes with group 0 or mask 0 can pair with nothing: they are dropped before the sweep.
TEST(Filters, BoxesThatCollideWithNothingAreLeftOut) {
  SceneSimulator scene(movingScene(SceneKind::kUniform, 9));
  BoxSet boxes = scene.boxes();
  boxes.groups.assign(boxes.size(), 0x1);
  boxes.masks.assign(boxes.size(), 0xFFFFFFFF);
  for (std::size_t i = 0; i < boxes.size(); i += 7) boxes.groups[i] = 0;
  for (std::size_t i = 3; i < boxes.size(); i += 11) boxes.masks[i] = 0;
  for (int threads : {1, 2, 3}) {
    Broadphase broadphase(engineConfig(Method::kAuto, threads, 0, 1));
    EXPECT_EQ(broadphase.update(boxes), bruteForcePairs(boxes));
    EXPECT_GT(broadphase.stats().boxes_filtered_out, 0u);
    EXPECT_EQ(broadphase.stats().boxes, boxes.size());
  }
}

// With threads and method left to the engine, each frame's threads are the plan's (frameThreads:
// one below the cut-off, every core above it), the kernel's cells and the sweep's passes handed
// to whichever worker is free: the pairs are the oracle's on every frame, whatever ran where.
TEST(DefaultThreads, ExactOnThePlannedThreads) {
  for (bool skin_off : {false, true}) {
    BroadphaseConfig config;  // threads 0, Method::kAuto
    config.parallel_min_boxes = 500;
    if (skin_off) config.skin = 0.0;
    Broadphase engine(config);
    SceneSimulator scene(movingScene(SceneKind::kUniform, 41, 1500, 0.2, 150));
    for (int frame = 0; frame < 150; ++frame) {
      ASSERT_EQ(engine.update(scene.boxes()), bruteForcePairs(scene.boxes()))
          << "skin_off " << skin_off << " frame " << frame << " path "
          << framePathName(engine.stats().path) << " threads " << engine.stats().threads;
      scene.step();
    }
  }
}

}  // namespace
}  // namespace sap_broadphase
