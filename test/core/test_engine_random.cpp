// The engine against the brute-force oracle on random boxes: sizes 0..20,000, several densities,
// every method, thread counts 1, 2, 3, 4, 7 and every ordered pair of sweep axes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sap_broadphase/core/brute_force.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::allAxisPairs;
using test_support::engineConfig;
using test_support::expectAllConfigsMatch;
using test_support::randomBoxes;
using test_support::samePairs;

/// Side of the world cube giving density inDensity for inCount boxes of mean edge 0.5.
double worldFor(std::size_t inCount, double inDensity) {
  const double meanVolume = 0.125;
  return std::cbrt(static_cast<double>(inCount) * meanVolume / inDensity) + 1e-9;
}

TEST(EngineVsOracle, SmallAndMediumSizesManySeeds) {
  const std::size_t kSizes[] = {0, 1, 2, 3, 5, 8, 17, 63, 64, 65, 130, 500, 1000};
  for (std::size_t n : kSizes) {
    for (uint64_t seed = 1; seed <= 4; ++seed) {
      const double density = seed == 1 ? 0.05 : (seed == 2 ? 0.5 : (seed == 3 ? 3.0 : 20.0));
      const BoxSet boxes = randomBoxes(n, worldFor(n, density), 1.0, seed * 1000 + n);
      expectAllConfigsMatch(boxes, "random n=" + std::to_string(n) + " seed=" +
                                       std::to_string(seed) + " d=" + std::to_string(density));
    }
  }
}

TEST(EngineVsOracle, ThousandsOfBoxesSeveralDensities) {
  for (double density : {0.01, 0.2, 1.0}) {
    // Above the default parallel_min_boxes, so kAuto goes parallel.
    const std::size_t n = BroadphaseConfig().parallel_min_boxes + 500;
    const BoxSet boxes = randomBoxes(n, worldFor(n, density), 1.0, 77);
    expectAllConfigsMatch(boxes, "random d=" + std::to_string(density));
  }
}

TEST(EngineVsOracle, TwentyThousandBoxes) {
  const std::size_t n = 20000;
  const BoxSet boxes = randomBoxes(n, worldFor(n, 0.3), 1.0, 2024);
  const PairList oracle = bruteForcePairs(boxes);
  ASSERT_GT(oracle.size(), n / 2);
  for (int threads : test_support::testThreadCounts()) {
    for (Method method : {Method::kParallel, Method::kAuto}) {
      const auto [primary, secondary] = allAxisPairs()[threads % 6];
      const BroadphaseConfig config = engineConfig(method, threads, primary, secondary);
      Broadphase broadphase(config);
      EXPECT_TRUE(samePairs(oracle, broadphase.update(boxes))) << test_support::describe(config);
    }
  }
  Broadphase sequential(engineConfig(Method::kSequential, 1, 2, 0));
  EXPECT_TRUE(samePairs(oracle, sequential.update(boxes)));
}

TEST(EngineVsOracle, LongThinBoxesSpanningTheWorld) {
  // Each box is long on one axis: candidate ranges on the primary axis span most ranks.
  test_support::TestRandom random(5);
  BoxSet boxes;
  for (uint32_t i = 0; i < 1500; ++i) {
    double lo[3];
    double hi[3];
    const int longAxis = static_cast<int>(random.below(3));
    for (int axis = 0; axis < 3; ++axis) {
      const double edge = axis == longAxis ? random.between(50.0, 100.0) : random.between(0, 1);
      lo[axis] = random.between(0.0, 100.0 - edge);
      hi[axis] = lo[axis] + edge;
    }
    boxes.add(i, lo, hi);
  }
  expectAllConfigsMatch(boxes, "long thin boxes");
}

TEST(EngineVsOracle, NegativeAndMixedMagnitudeCoordinates) {
  test_support::TestRandom random(11);
  BoxSet boxes;
  for (uint32_t i = 0; i < 1200; ++i) {
    double lo[3];
    double hi[3];
    const double scale = std::pow(10.0, static_cast<double>(random.below(9)) - 4.0);
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = random.between(-1.0, 1.0) * scale;
      hi[axis] = lo[axis] + random.between(0.0, 0.3) * scale;
    }
    boxes.add(i * 7919u + 3u, lo, hi);
  }
  expectAllConfigsMatch(boxes, "mixed magnitudes");
}

}  // namespace
}  // namespace sap_broadphase
