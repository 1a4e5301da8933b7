// Determinism: the same pair list, hashed, for every thread count 1..7, every axis pair and
// every method, frame after frame.
#include <gtest/gtest.h>

#include <vector>

#include "sap_broadphase/core/brute_force.h"
#include "sap_broadphase/core/scenes.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::allAxisPairs;
using test_support::engineConfig;
using test_support::hashPairs;

TEST(Determinism, PairHashIsTheSameForEveryThreadCountAndAxisPair) {
  SceneConfig scene;
  scene.kind = SceneKind::kUniform;
  scene.n = 6000;
  scene.density = 0.25;
  scene.seed = 99;
  std::vector<BoxSet> frames;
  SceneSimulator simulator(scene);
  for (int f = 0; f < 4; ++f) {
    frames.push_back(simulator.boxes());
    simulator.step();
  }
  std::vector<uint64_t> expected;
  for (const BoxSet& frame : frames) expected.push_back(hashPairs(bruteForcePairs(frame)));
  for (const auto& [primary, secondary] : allAxisPairs()) {
    for (int threads = 1; threads <= 7; ++threads) {
      for (Method method : {Method::kParallel, Method::kAuto}) {
        Broadphase broadphase(engineConfig(method, threads, primary, secondary));
        for (std::size_t f = 0; f < frames.size(); ++f) {
          ASSERT_EQ(hashPairs(broadphase.update(frames[f])), expected[f])
              << "frame " << f << ", " << test_support::describe(broadphase.config());
        }
      }
    }
    Broadphase sequential(engineConfig(Method::kSequential, 1, primary, secondary));
    for (std::size_t f = 0; f < frames.size(); ++f)
      ASSERT_EQ(hashPairs(sequential.update(frames[f])), expected[f]);
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
