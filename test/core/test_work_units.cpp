// The work-unit runner (work_units.h): every unit runs exactly once at any thread count, folds
// do not depend on the threads, a pass of one unit opens no parallel region, and a frame small
// enough for one unit per pass never waits for a second thread, whatever the configured count.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "core/axis_spread.h"
#include "core/work_units.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/scenes.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

TEST(WorkUnits, EveryItemRunsOnceAtAnyThreadCountAndUnitSize) {
  for (std::size_t items : {0u, 1u, 7u, 64u, 1000u}) {
    for (std::size_t unit_items : {1u, 3u, 64u, 4096u}) {
      for (int threads = 1; threads <= 4; ++threads) {
        std::vector<std::atomic<int>> runs(items);
        runOverItems(WorkUnits{items, unit_items}, threads,
                     [&](std::size_t inBegin, std::size_t inEnd) {
                       for (std::size_t i = inBegin; i < inEnd; ++i) runs[i].fetch_add(1);
                     });
        for (std::size_t i = 0; i < items; ++i)
          ASSERT_EQ(runs[i].load(), 1) << "item " << i << " of " << items << ", units of "
                                       << unit_items << ", " << threads << " threads";
      }
    }
  }
}

TEST(WorkUnits, FoldsInUnitOrderWhateverTheThreads) {
  // A floating-point sum whose value depends on how its additions are grouped: per-unit sums
  // folded in unit order give one value for every thread count.
  std::vector<double> values(10000);
  test_support::TestRandom random(7);
  for (double& value : values) value = random.between(-1.0, 1.0) * 1e10 + random.unit();
  const WorkUnits units{values.size(), 97};
  auto sumOf = [&](int inThreads) {
    return reduceOverItems(
        units, inThreads, 0.0,
        [&](std::size_t inBegin, std::size_t inEnd) {
          double sum = 0.0;
          for (std::size_t i = inBegin; i < inEnd; ++i) sum += values[i];
          return sum;
        },
        [](double& ioTotal, double inUnit) { ioTotal += inUnit; });
  };
  const double one_thread = sumOf(1);
  for (int threads = 2; threads <= 4; ++threads)
    for (int repeat = 0; repeat < 20; ++repeat) ASSERT_EQ(sumOf(threads), one_thread) << threads;
}

TEST(WorkUnits, OneUnitOrOneThreadOpensNoRegion) {
  const uint64_t before = parallelRegionsOpened();
  int ran = 0;
  runUnits(1, 4, [&](std::size_t) { ++ran; });
  runUnits(5, 1, [&](std::size_t) { ++ran; });
  EXPECT_EQ(ran, 6);
  EXPECT_EQ(parallelRegionsOpened(), before);
  std::atomic<int> parallel_ran{0};
  runUnits(8, 2, [&](std::size_t) { parallel_ran.fetch_add(1); });
  EXPECT_EQ(parallel_ran.load(), 8);
  EXPECT_EQ(parallelRegionsOpened(), before + 1);
}

TEST(WorkUnits, TheSpreadIsTheSameOnAnyThreadCount) {
  const BoxColumns boxes =
      columnsOf(test_support::randomBoxes(5 * kUnitBoxes + 123, 1000.0, 3.0, 11));
  for (int axis = 0; axis < 3; ++axis) {
    const AxisSpread one = measureAxisSpread(boxes, axis, 1);
    for (int threads = 2; threads <= 4; ++threads) {
      const AxisSpread many = measureAxisSpread(boxes, axis, threads);
      EXPECT_EQ(many.lowest, one.lowest);
      EXPECT_EQ(many.highest, one.highest);
      EXPECT_EQ(many.extent_sum, one.extent_sum) << "axis " << axis << ", " << threads;
      EXPECT_EQ(many.finite_boxes, one.finite_boxes);
    }
  }
}

// A small frame on an engine allowed four threads (and on the default, all cores): its plan
// runs on one thread, the kernel's or its kept candidates', and no pass of the frame (history,
// spread, copies) opens a parallel region, so no other core's availability can delay it. A large
// frame does open regions (the count is not stuck at zero).
TEST(WorkUnits, SmallFramesOpenNoParallelRegion) {
  for (int threads : {0, 2, 4}) {
    SceneConfig scene = test_support::movingScene(SceneKind::kUniform, 5, 4096, 0.35, 12);
    scene.speed = 0.01;
    SceneSimulator simulator(scene);
    BroadphaseConfig config;
    config.threads = threads;
    Broadphase engine(config);
    for (int frame = 0; frame < 12; ++frame) {
      if (frame > 0) simulator.step();
      const std::string label =
          "threads " + std::to_string(threads) + ", frame " + std::to_string(frame);
      const uint64_t before = parallelRegionsOpened();
      const PairList& pairs = engine.update(simulator.boxes());
      EXPECT_EQ(parallelRegionsOpened(), before) << label;
      EXPECT_TRUE(engine.stats().path == FramePath::kSmallFrame ||
                  engine.stats().path == FramePath::kSkin)
          << label << ": " << framePathName(engine.stats().path);
      EXPECT_EQ(engine.stats().threads, 1) << label;
      EXPECT_TRUE(test_support::samePairs(bruteForcePairs(simulator.boxes()), pairs)) << label;
    }
  }
  BroadphaseConfig config;
  config.threads = 4;
  config.method = Method::kParallel;
  Broadphase engine(config);
  const uint64_t before = parallelRegionsOpened();
  engine.update(test_support::randomBoxes(8 * kUnitBoxes, 1000.0, 3.0, 3));
  EXPECT_GT(parallelRegionsOpened(), before);
}

}  // namespace
}  // namespace sap_broadphase
