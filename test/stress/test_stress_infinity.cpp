// Infinite coordinates: ground planes, half-spaces, slabs infinite on several axes, points at
// infinity, against the oracle and against hand-made expectations.
#include <gtest/gtest.h>

#include <limits>

#include "sap_broadphase/core/brute_force.h"
#include "stress_scenes.h"
#include "stress_support.h"
#include "test_support.h"

namespace sap_broadphase::stress {
namespace {

using test_support::randomBoxes;

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(StressInfinity, GroundPlaneAndHalfSpaces) {
  BoxSet boxes;
  addBox(boxes, 10, -kInf, -kInf, -kInf, kInf, kInf, 0.0);      // ground z <= 0
  addBox(boxes, 11, 5.0, -kInf, -kInf, kInf, kInf, kInf);       // half-space x >= 5
  addBox(boxes, 1, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0);               // rests on the ground
  addBox(boxes, 2, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0);               // floats above it
  addBox(boxes, 3, 4.0, 0.0, 0.5, 5.0, 1.0, 1.0);               // touches the half-space
  addBox(boxes, 4, 4.0, 0.0, 0.5, 4.999999999, 1.0, 1.0);       // just short of it
  addBox(boxes, 12, kInf, kInf, kInf, kInf, kInf, kInf);        // the point at +infinity
  addBox(boxes, 13, -kInf, -kInf, -kInf, -kInf, -kInf, -kInf);  // the point at -infinity
  const PairList expected = {{1, 2}, {1, 10}, {3, 4}, {3, 11}, {10, 11}, {10, 13}, {11, 12}};
  EXPECT_TRUE(samePairList(expected, bruteForcePairs(boxes)));
  expectStressMatch(boxes, expected, "ground plane and half-spaces");
}

TEST(StressInfinity, EverythingBoxMeetsAll) {
  BoxSet boxes = randomBoxes(2000, 100.0, 1.0, 51);
  addBox(boxes, 5000, -kInf, -kInf, -kInf, kInf, kInf, kInf);
  const PairList oracle = bruteForcePairs(boxes);
  std::size_t with_everything = 0;
  for (const IdPair& pair : oracle) with_everything += pair.b == 5000;
  EXPECT_EQ(with_everything, 2000u);
  expectStressMatch(boxes, oracle, "one box covering all space");
}

TEST(StressInfinity, RandomSlabsInfiniteOnSeveralAxes) {
  const BoxSet boxes = infiniteSlabScene(5000, 52);
  expectStressMatch(boxes, "infinite slabs, 5000 boxes");
}

TEST(StressInfinity, OnlyInfiniteBoxes) {
  // No finite coordinate at all: slab and partition set-up have no span to work with.
  SplitMix64 random(53);
  BoxSet boxes;
  for (uint32_t i = 0; i < 600; ++i) {
    double low[3];
    double high[3];
    for (int axis = 0; axis < 3; ++axis) {
      const int kind = static_cast<int>(random.below(4));
      low[axis] = kind == 3 ? kInf : -kInf;
      high[axis] = kind == 0 ? -kInf : kInf;
    }
    boxes.add(i, low, high);
  }
  expectStressMatch(boxes, "only infinite coordinates");
}

TEST(StressInfinity, SlabsWithInfiniteThirdAxis) {
  // The third (slab) axis holds both huge finite spans and infinities.
  BoxSet boxes = randomBoxes(4500, 100.0, 2.0, 54);
  SplitMix64 random(55);
  for (std::size_t i = 0; i < boxes.size(); i += 7) {
    for (int axis = 0; axis < 3; ++axis) {
      if (random.chance(0.3)) boxes.lo(axis, i) = -kInf;
      if (random.chance(0.3)) boxes.hi(axis, i) = random.chance(0.5) ? kInf : 1e308;
    }
  }
  expectStressMatch(boxes, "infinite and 1e308 on the slab axis");
}

}  // namespace
}  // namespace sap_broadphase::stress
