// Degenerate scenes: zero extents, identical boxes, one plane, 0/1/2 boxes, ids at the top of
// uint32, filters, and a mixture of every special value, against the oracle.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

#include "sap_broadphase/core/brute_force.h"
#include "stress_scenes.h"
#include "stress_support.h"
#include "test_support.h"

namespace sap_broadphase::stress {
namespace {

using test_support::latticeBoxes;
using test_support::randomBoxes;

constexpr uint32_t kTopId = std::numeric_limits<uint32_t>::max();

TEST(StressDegenerate, EmptyAndSingleBox) {
  BoxSet boxes;
  expectStressMatch(boxes, PairList{}, "no boxes");
  addBox(boxes, kTopId, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
  expectStressMatch(boxes, PairList{}, "one box, id 2^32-1");
  addBox(boxes, 0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
  expectStressMatch(boxes, PairList{{0, kTopId}}, "ids 0 and 2^32-1 at one point");
}

TEST(StressDegenerate, ZeroExtentPoints) {
  // Points on a small integer lattice: many coincide exactly and must pair.
  expectStressMatch(latticeBoxes(5000, 12, 0, 71), "5000 points on a 12^3 lattice");
}

TEST(StressDegenerate, ZeroExtentOnSomeAxes) {
  BoxSet boxes = latticeBoxes(4000, 20, 3, 72);
  SplitMix64 random(73);
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (int axis = 0; axis < 3; ++axis)
      if (random.chance(0.4)) boxes.hi(axis, i) = boxes.lo(axis, i);
  expectStressMatch(boxes, "lattice, faces and edges of zero extent");
}

TEST(StressDegenerate, AllBoxesIdentical) {
  BoxSet boxes;
  for (uint32_t i = 0; i < 1500; ++i) addBox(boxes, i, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0);
  const PairList oracle = bruteForcePairs(boxes);
  ASSERT_EQ(oracle.size(), 1500u * 1499u / 2);
  expectStressMatch(boxes, oracle, "1500 identical boxes");
}

TEST(StressDegenerate, AllIdenticalPoints) {
  BoxSet boxes;
  for (uint32_t i = 0; i < 1000; ++i) addBox(boxes, kTopId - i, 7.0, 7.0, 7.0, 7.0, 7.0, 7.0);
  expectStressMatch(boxes, "1000 identical points, ids near 2^32-1");
}

TEST(StressDegenerate, AllOnOnePlane) {
  for (int axis = 0; axis < 3; ++axis) {
    BoxSet boxes = randomBoxes(5000, 100.0, 2.5, 74 + axis);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      boxes.lo(axis, i) = 0.0;
      boxes.hi(axis, i) = 0.0;
    }
    expectStressMatch(boxes, "5000 boxes flat on plane " + std::to_string(axis) + " = 0");
  }
}

TEST(StressDegenerate, AllOnOneLine) {
  BoxSet boxes = randomBoxes(4000, 1000.0, 1.0, 77);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    boxes.lo(1, i) = boxes.hi(1, i) = 3.0;
    boxes.lo(2, i) = boxes.hi(2, i) = -0.0;
  }
  expectStressMatch(boxes, "4000 segments on one line");
}

TEST(StressDegenerate, IdsNearTopOfUint32) {
  BoxSet boxes = latticeBoxes(5000, 25, 2, 78);
  for (std::size_t i = 0; i < boxes.size(); ++i)
    boxes.ids[i] = kTopId - static_cast<uint32_t>((i * 7919) % boxes.size());
  expectStressMatch(boxes, "ids 2^32-5000..2^32-1, shuffled");
  // Ids at both ends of the range at once.
  for (std::size_t i = 0; i < boxes.size(); i += 2) boxes.ids[i] = static_cast<uint32_t>(i);
  expectStressMatch(boxes, "ids at both ends of uint32");
}

TEST(StressDegenerate, GroupsAndMasks) {
  BoxSet boxes = latticeBoxes(5000, 20, 2, 79);
  addRandomFilters(boxes, 80);
  expectStressMatch(boxes, "lattice with random groups/masks (some zero)");
  // Group 0 or mask 0 everywhere: nothing can pair.
  BoxSet silent = latticeBoxes(2000, 5, 2, 81);
  silent.groups.assign(silent.size(), 0u);
  silent.masks.assign(silent.size(), 0xFFFFFFFFu);
  expectStressMatch(silent, PairList{}, "all groups zero");
  silent.groups.assign(silent.size(), 0xFFFFFFFFu);
  silent.masks.assign(silent.size(), 0u);
  expectStressMatch(silent, PairList{}, "all masks zero");
}

TEST(StressDegenerate, OneSidedMasksDoNotPair) {
  // A sees B's group but B does not see A's: the filter needs both directions.
  BoxSet boxes;
  const double low[3] = {0.0, 0.0, 0.0};
  const double high[3] = {1.0, 1.0, 1.0};
  boxes.add(1, low, high, 0x1u, 0x2u);
  boxes.add(2, low, high, 0x2u, 0x4u);
  boxes.add(3, low, high, 0x4u, 0x2u);
  expectStressMatch(boxes, PairList{{2, 3}}, "one-sided masks");
}

TEST(StressDegenerate, SpecialValueMixture) {
  const BoxSet boxes = specialValueScene(5000, 82);
  const PairList oracle = bruteForcePairs(boxes);
  ASSERT_GT(oracle.size(), 0u);
  expectStressMatch(boxes, oracle, "every special value at once");
}

TEST(StressDegenerate, SpecialValueMixtureWithFilters) {
  BoxSet boxes = specialValueScene(3000, 83);
  addRandomFilters(boxes, 84);
  expectStressMatch(boxes, "special values with groups/masks");
}

}  // namespace
}  // namespace sap_broadphase::stress
