// The engine against the oracle on the inputs where exactness is hardest: touching faces,
// identical and zero-extent boxes, infinite slabs, signed zeros, values that float32 keys
// cannot tell apart, and group/mask filters.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/sweep/sort_keys.h"
#include "sap_broadphase/core/brute_force.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::expectAllConfigsMatch;
using test_support::TestRandom;

constexpr double kInf = std::numeric_limits<double>::infinity();

void addBox(BoxSet& ioBoxes, double inX0, double inY0, double inZ0, double inX1, double inY1,
            double inZ1) {
  const double lo[3] = {inX0, inY0, inZ0};
  const double hi[3] = {inX1, inY1, inZ1};
  ioBoxes.add(static_cast<uint32_t>(ioBoxes.size()), lo, hi);
}

TEST(EngineEdgeCases, TouchingUnitGrid) {
  // k^3 unit cubes sharing faces, edges and corners exactly: each touches up to 26 others.
  const int k = 11;
  BoxSet boxes;
  for (int x = 0; x < k; ++x)
    for (int y = 0; y < k; ++y)
      for (int z = 0; z < k; ++z) addBox(boxes, x, y, z, x + 1, y + 1, z + 1);
  const PairList oracle = bruteForcePairs(boxes);
  // Pairs of touching cells of a k^3 grid: 3 directions of faces, 6 of edges, 4 of corners.
  const std::size_t faces = 3u * (k - 1) * k * k;
  const std::size_t edges = 6u * (k - 1) * (k - 1) * k;
  const std::size_t corners = 4u * (k - 1) * (k - 1) * (k - 1);
  ASSERT_EQ(oracle.size(), faces + edges + corners);
  expectAllConfigsMatch(boxes, oracle, "unit grid");
}

TEST(EngineEdgeCases, TouchingGridWithInexactSpacing) {
  // Cells [i*0.1, (i+1)*0.1]: neighbours share bit-identical faces that float32 keys round
  // outward, while cells two apart are separated by less than a float32 step at large offsets.
  for (double offset : {0.0, 1e6, -3e7}) {
    BoxSet boxes;
    const int k = 9;
    for (int x = 0; x < k; ++x)
      for (int y = 0; y < k; ++y)
        for (int z = 0; z < k; ++z)
          addBox(boxes, offset + x * 0.1, y * 0.1, z * 0.1, offset + (x + 1) * 0.1, (y + 1) * 0.1,
                 (z + 1) * 0.1);
    expectAllConfigsMatch(boxes, "0.1 grid at offset " + std::to_string(offset));
  }
}

TEST(EngineEdgeCases, RandomLatticeBoxesWithManyExactTouches) {
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const BoxSet boxes = test_support::latticeBoxes(1500, 12, 2, seed);
    expectAllConfigsMatch(boxes, "lattice seed " + std::to_string(seed));
  }
}

TEST(EngineEdgeCases, IdenticalBoxes) {
  BoxSet boxes;
  for (int i = 0; i < 300; ++i) addBox(boxes, 1, 2, 3, 4, 5, 6);
  for (int i = 0; i < 100; ++i) addBox(boxes, 7, 7, 7, 7, 7, 7);  // identical points
  for (int i = 0; i < 50; ++i) addBox(boxes, 4, 5, 6, 9, 9, 9);   // touching the first group
  const PairList oracle = bruteForcePairs(boxes);
  ASSERT_EQ(oracle.size(), 300u * 299 / 2 + 100u * 99 / 2 + 50u * 49 / 2 + 50u * 300 + 50u * 100);
  expectAllConfigsMatch(boxes, oracle, "identical boxes");
}

TEST(EngineEdgeCases, ZeroExtentBoxes) {
  TestRandom random(8);
  BoxSet boxes;
  for (int i = 0; i < 1000; ++i) {
    const double x = static_cast<double>(random.below(6));
    const double y = static_cast<double>(random.below(6));
    const double z = static_cast<double>(random.below(6));
    switch (i % 4) {
      case 0:
        addBox(boxes, x, y, z, x, y, z);
        break;  // point
      case 1:
        addBox(boxes, x, y, z, x + 1, y, z);
        break;  // segment
      case 2:
        addBox(boxes, x, y, z, x + 2, y + 1, z);
        break;  // flat
      default:
        addBox(boxes, x, y, z, x + 1, y + 1, z + 1);
        break;
    }
  }
  expectAllConfigsMatch(boxes, "zero-extent boxes");
}

TEST(EngineEdgeCases, InfiniteSlabsAndBoxesAtInfinity) {
  TestRandom random(9);
  BoxSet boxes;
  addBox(boxes, -kInf, -kInf, -kInf, kInf, kInf, 0.0);   // ground half-space
  addBox(boxes, -kInf, -kInf, -kInf, kInf, kInf, kInf);  // everything
  addBox(boxes, 5, -kInf, -kInf, 5, kInf, kInf);         // a plane x = 5
  addBox(boxes, kInf, 0, 0, kInf, 1, 1);                 // at +inf on x
  addBox(boxes, kInf, 0, 0, kInf, 1, 1);                 // the same: touches the previous
  addBox(boxes, -kInf, 0, 0, -kInf, 1, 1);               // at -inf on x
  addBox(boxes, 0, -kInf, 0, 1, -1e308, 1);              // reaching down to -inf on y
  addBox(boxes, -1e300, -1e300, -1e300, 1e300, 1e300, 1e300);
  for (int i = 0; i < 600; ++i) {
    const double x = random.between(-10, 10);
    const double y = random.between(-10, 10);
    const double z = random.between(-10, 10);
    addBox(boxes, x, y, z, x + 1, y + 1, z + 1);
  }
  expectAllConfigsMatch(boxes, "infinite slabs");
}

TEST(EngineEdgeCases, SignedZerosTouch) {
  BoxSet boxes;
  addBox(boxes, -1, -1, -1, -0.0, -0.0, -0.0);     // ends at -0
  addBox(boxes, 0.0, 0.0, 0.0, 1, 1, 1);           // starts at +0: touches the first
  addBox(boxes, -1, -1, -1, 0.0, 0.0, 0.0);        // ends at +0
  addBox(boxes, -0.0, -0.0, -0.0, 1, 1, 1);        // starts at -0
  addBox(boxes, -0.0, 0.0, -0.0, 0.0, -0.0, 0.0);  // a point at the origin, mixed signs
  addBox(boxes, 1e-320, 1e-320, 1e-320, 1, 1, 1);  // just above zero: touches no negative box
  addBox(boxes, -1, -1, -1, -1e-320, 0, 0);        // just below zero on x
  const PairList oracle = bruteForcePairs(boxes);
  EXPECT_EQ(oracle.size(), 14u);
  expectAllConfigsMatch(boxes, oracle, "signed zeros");
}

TEST(EngineEdgeCases, GapsSmallerThanAFloat32Step) {
  // Neighbours one double-ulp apart (no overlap) or exactly touching: float32 keys cannot tell
  // these apart, so only the exact final test decides.
  TestRandom random(10);
  BoxSet boxes;
  for (int i = 0; i < 800; ++i) {
    const double base = random.between(-100.0, 100.0) * (i % 2 ? 1.0 : 1e-30);
    const double touch = random.below(2) ? base : std::nextafter(base, kInf);
    const double y = static_cast<double>(random.below(3));
    addBox(boxes, base - 0.5, y, 0, base, y + 1, 1);
    addBox(boxes, touch, y, 0, touch + 0.5, y + 1, 1);
  }
  for (int i = 0; i < 200; ++i) {  // subnormal coordinates that all round to float32 zero
    const double x = std::numeric_limits<double>::denorm_min() * static_cast<double>(i);
    addBox(boxes, x, 5, 5, x, 6, 6);
  }
  expectAllConfigsMatch(boxes, "sub-float32 gaps");
}

TEST(EngineEdgeCases, KeysOnlyModeReportsASupersetThatOverlapsInFloat32) {
  // exact_final_test = false may report extra pairs (float32 keys overlap) but never misses one.
  TestRandom random(13);
  BoxSet boxes;
  for (int i = 0; i < 1500; ++i) {
    const double base = random.between(-100.0, 100.0);
    const double next = random.below(2) ? base : std::nextafter(base, kInf);
    const double y = static_cast<double>(random.below(4));
    addBox(boxes, base - 0.5, y, 0, base, y + 1, 1);
    addBox(boxes, next, y, 0, next + 0.5, y + 1, 1);
  }
  const PairList oracle = bruteForcePairs(boxes);
  std::vector<std::size_t> indexOfId(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) indexOfId[boxes.ids[i]] = i;
  for (Method method : {Method::kParallel, Method::kSequential}) {
    for (int threads : {1, 3}) {
      BroadphaseConfig config = test_support::engineConfig(method, threads, 0, 1);
      config.exact_final_test = false;
      Broadphase broadphase(config);
      const PairList pairs = broadphase.update(boxes);
      ASSERT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
      ASSERT_TRUE(std::adjacent_find(pairs.begin(), pairs.end()) == pairs.end());
      ASSERT_TRUE(std::includes(pairs.begin(), pairs.end(), oracle.begin(), oracle.end()))
          << test_support::describe(config);
      EXPECT_GT(pairs.size(), oracle.size()) << "no float32-only pair in this input?";
      for (const IdPair& pair : pairs) {
        const std::size_t a = indexOfId[pair.a];
        const std::size_t b = indexOfId[pair.b];
        for (int axis = 0; axis < 3; ++axis) {
          ASSERT_LE(lowKey(boxes.lo(axis, a)), highKey(boxes.hi(axis, b)));
          ASSERT_LE(lowKey(boxes.lo(axis, b)), highKey(boxes.hi(axis, a)));
        }
      }
    }
  }
}

TEST(EngineEdgeCases, GroupAndMaskFilters) {
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    BoxSet boxes = test_support::randomBoxes(1500, 8.0, 1.0, seed);
    test_support::addRandomFilters(boxes, seed + 100);
    expectAllConfigsMatch(boxes, "filters seed " + std::to_string(seed));
  }
  BoxSet fullyFiltered = test_support::randomBoxes(500, 3.0, 1.0, 4);
  fullyFiltered.groups.assign(500, 0x1u);
  fullyFiltered.masks.assign(500, 0x2u);
  EXPECT_TRUE(bruteForcePairs(fullyFiltered).empty());
  expectAllConfigsMatch(fullyFiltered, "every pair filtered");
}

TEST(EngineEdgeCases, SparseAndExtremeIds) {
  BoxSet boxes =
      test_support::shuffledSubset(test_support::randomBoxes(2000, 6.0, 1.0, 5), 1.0, true, 6);
  boxes.ids[0] = 0;
  boxes.ids[1] = 0xFFFFFFFFu;
  for (std::size_t i = 2; i < boxes.size(); ++i)
    if (boxes.ids[i] == 0 || boxes.ids[i] == 0xFFFFFFFFu) boxes.ids[i] = 12345;
  ASSERT_FALSE(validate(boxes).has_value());
  expectAllConfigsMatch(boxes, "sparse ids");
}

TEST(EngineEdgeCases, EveryPairOverlaps) {
  TestRandom random(12);
  BoxSet boxes;
  for (int i = 0; i < 400; ++i)
    addBox(boxes, -random.between(1, 2), -random.between(1, 2), -random.between(1, 2),
           random.between(1, 2), random.between(1, 2), random.between(1, 2));
  const PairList oracle = bruteForcePairs(boxes);
  ASSERT_EQ(oracle.size(), 400u * 399 / 2);
  expectAllConfigsMatch(boxes, oracle, "all overlapping");
}

}  // namespace
}  // namespace sap_broadphase
