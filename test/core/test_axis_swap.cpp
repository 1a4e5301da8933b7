// Dynamic axis choice (§5): on the plane-cluster scene with u a sweep axis, the dispersion D of
// that axis rises as the boxes flatten onto u = 0, the engine swaps it for the unused axis, and
// every frame's pairs stay exact.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/scenes.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::engineConfig;
using test_support::samePairs;

/// Runs the plane scene (u = inPlaneAxis) through mid-run with sweep axes inPrimary/inSecondary;
/// returns the frames on which a swap happened. Pairs are checked every frame against a
/// sequential engine on fixed axes, and against the oracle around swaps and periodically.
std::set<int> runPlaneScene(int inPlaneAxis, int inPrimary, int inSecondary,
                            bool inSwapping = true) {
  SceneConfig scene;
  scene.kind = SceneKind::kPlaneCluster;
  scene.n = 100 * 100;
  scene.seed = 6;
  scene.plane_axis = inPlaneAxis;
  scene.frames = 120;
  SceneSimulator simulator(scene);
  BroadphaseConfig config = engineConfig(Method::kParallel, 4, inPrimary, inSecondary);
  config.axis_swapping = inSwapping;
  Broadphase engine(config);
  // The reference sweeps the two axes that are not u, and never swaps.
  BroadphaseConfig referenceConfig =
      engineConfig(Method::kSequential, 1, (inPlaneAxis + 1) % 3, (inPlaneAxis + 2) % 3);
  referenceConfig.axis_swapping = false;
  Broadphase reference(referenceConfig);
  std::set<int> swapFrames;
  bool checkNextWithOracle = false;
  for (int frame = 0; frame <= 75; ++frame) {
    const BoxSet& boxes = simulator.boxes();
    const PairList& pairs = engine.update(boxes);
    const FrameReport& stats = engine.stats();
    EXPECT_NE(stats.primary_axis, stats.secondary_axis);
    EXPECT_TRUE(samePairs(reference.update(boxes), pairs)) << "frame " << frame;
    if (stats.axes_swapped || checkNextWithOracle || frame % 25 == 0 || frame == 60) {
      EXPECT_TRUE(samePairs(bruteForcePairs(boxes), pairs)) << "oracle, frame " << frame;
    }
    checkNextWithOracle = stats.axes_swapped;
    if (stats.axes_swapped) swapFrames.insert(frame);
    simulator.step();
  }
  // config() is what was set; the axes in force are the report's.
  EXPECT_TRUE(sameConfig(engine.config(), config)) << describeConfig(engine.config());
  const FrameReport& after = engine.stats();
  EXPECT_NE(after.primary_axis, after.secondary_axis);
  if (inSwapping && !swapFrames.empty()) {
    EXPECT_TRUE(after.primary_axis != inPlaneAxis && after.secondary_axis != inPlaneAxis)
        << "axes after the run: " << after.primary_axis << "/" << after.secondary_axis;
  }
  return swapFrames;
}

TEST(AxisSwap, ClusteredPrimaryAxisIsSwappedAndResultsStayExact) {
  const std::set<int> swaps = runPlaneScene(0, 0, 1);
  ASSERT_FALSE(swaps.empty()) << "no axis swap on the plane-cluster scene with u = primary";
  EXPECT_GT(*swaps.begin(), 0) << "a first frame has no coherent D to act on";
  EXPECT_LT(*swaps.begin(), 61) << "the swap should come before the boxes spread again";
}

TEST(AxisSwap, ClusteredSecondaryAxisIsSwappedAndResultsStayExact) {
  const std::set<int> swaps = runPlaneScene(1, 0, 1);
  ASSERT_FALSE(swaps.empty()) << "no axis swap on the plane-cluster scene with u = secondary";
}

TEST(AxisSwap, UnusedAxisClusteringNeedsNoSwap) {
  // u = z is not swept: results stay exact whether or not the heuristic fires.
  runPlaneScene(2, 0, 1);
}

TEST(AxisSwap, DisabledSwappingKeepsTheAxes) {
  const std::set<int> swaps = runPlaneScene(0, 0, 1, false);
  EXPECT_TRUE(swaps.empty());
}

}  // namespace
}  // namespace sap_broadphase
