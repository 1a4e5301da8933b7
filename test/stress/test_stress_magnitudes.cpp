// Extreme magnitudes, subnormals, signed zeros and large translations against the oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "sap_broadphase/core/brute_force.h"
#include "stress_scenes.h"
#include "stress_support.h"
#include "test_support.h"

namespace sap_broadphase::stress {
namespace {

using test_support::latticeBoxes;
using test_support::randomBoxes;

TEST(StressMagnitudes, DecadesFrom1em300To1e300InOneScene) {
  const BoxSet boxes = magnitudeScene(5000, 11);
  const PairList oracle = bruteForcePairs(boxes);
  ASSERT_GT(oracle.size(), 100u) << "the scene should pair within its decades";
  expectStressMatch(boxes, oracle, "magnitudes 1e-300..1e300");
}

TEST(StressMagnitudes, DecadesWithFilters) {
  BoxSet boxes = magnitudeScene(3000, 12);
  addRandomFilters(boxes, 13);
  expectStressMatch(boxes, "magnitudes with groups/masks");
}

TEST(StressMagnitudes, Subnormals) {
  const BoxSet boxes = subnormalScene(2500, 21);
  const PairList oracle = bruteForcePairs(boxes);
  ASSERT_GT(oracle.size(), 1000u);
  expectStressMatch(boxes, oracle, "subnormals");
}

TEST(StressMagnitudes, SubnormalOneUnitGapDoesNotPair) {
  const double unit = std::numeric_limits<double>::denorm_min();
  BoxSet boxes;
  addBox(boxes, 0, 0.0, 0.0, 0.0, unit, 1.0, 1.0);
  addBox(boxes, 1, 2 * unit, 0.0, 0.0, 3 * unit, 1.0, 1.0);  // one subnormal unit apart
  addBox(boxes, 2, unit, 0.0, 0.0, unit, 1.0, 1.0);          // touches box 0 and stops there
  addBox(boxes, 3, -unit, 0.0, 0.0, -unit, 1.0, 1.0);        // one unit left of box 0
  const PairList expected = {{0, 2}};
  EXPECT_TRUE(samePairList(expected, bruteForcePairs(boxes)));
  expectStressMatch(boxes, expected, "subnormal 1-unit gap");
}

TEST(StressMagnitudes, SignedZerosTouch) {
  // -0.0 == 0.0: boxes ending at -0.0 touch boxes starting at +0.0 on every axis.
  BoxSet boxes;
  addBox(boxes, 0, -1.0, -1.0, -1.0, -0.0, -0.0, -0.0);
  addBox(boxes, 1, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0);
  addBox(boxes, 2, -0.0, -0.0, -0.0, 0.0, 0.0, 0.0);         // a point at the origin, both zeros
  addBox(boxes, 3, 0.0, -0.0, 0.0, -0.0, 0.0, -0.0);         // the same point, zeros the other way
  addBox(boxes, 4, -1e-300, -1.0, -1.0, -1e-300, 1.0, 1.0);  // just left of zero: no touch
  const PairList expected = {{0, 1}, {0, 2}, {0, 3}, {0, 4}, {1, 2}, {1, 3}, {2, 3}};
  EXPECT_TRUE(samePairList(expected, bruteForcePairs(boxes)));
  expectStressMatch(boxes, expected, "signed zeros, hand-made");
}

TEST(StressMagnitudes, SignedZeroLattice) {
  expectStressMatch(signedZeroScene(4000, 31), "signed zero lattice");
}

// The same random scene moved by large offsets: rounding changes the pairs, so the oracle
// is computed on the translated values.
TEST(StressMagnitudes, TranslatedByLargeOffsets) {
  const BoxSet base = randomBoxes(4000, 100.0, 3.0, 41);
  const double offsets[][3] = {
      {1e6, -1e6, 1e6},     {0x1p24, 0x1p24, -0x1p24}, {0x1p40 + 0.5, -0x1p40, 3.0},
      {1e15, 1e15, 1e15},   {0x1p53, -0x1p53, 0x1p52}, {1e200, -1e200, 1e-200},
      {-1e300, 1e300, 0.0},
  };
  for (const auto& offset : offsets) {
    const BoxSet moved = translated(base, offset);
    expectStressMatch(moved, "translated by (" + std::to_string(offset[0]) + ", " +
                                 std::to_string(offset[1]) + ", " + std::to_string(offset[2]) +
                                 ")");
  }
}

// Near 1e300 two boxes of the translated scene can collapse onto the same doubles: then
// they touch and must pair, exactly as the oracle says.
TEST(StressMagnitudes, TranslatedLatticeCollapses) {
  const BoxSet base = latticeBoxes(1200, 40, 2, 42);
  const double offset[3] = {1e20, 1e20, 1e20};  // 1 is far below one ulp of 1e20
  const BoxSet moved = translated(base, offset);
  const PairList oracle = bruteForcePairs(moved);
  EXPECT_EQ(oracle.size(), 1200u * 1199u / 2) << "every box collapsed onto the same point";
  expectStressMatch(moved, oracle, "lattice translated by 1e20");
}

// Robots in UTM or Earth-centred coordinates: 5 cm boxes in a 10 m site, millions of metres
// from the origin. Exact for every configuration, and the keys, taken relative to the frame,
// do not collapse: the primary sort's dispersion D stays that of the same site at the origin.
TEST(StressMagnitudes, SmallBoxesAtEarthScaleCoordinates) {
  const BoxSet site = randomBoxes(5000, 10.0, 0.05, 43);  // 10^4 endpoints: 16 partitions
  const double offsets[][3] = {
      {4.2e6, 1.1e6, 4.7e6}, {-2.7e6, -4.3e6, 3.9e6}, {500000.5, 5.4e6, 120.0}, {1e9, -1e9, 1e9}};
  BroadphaseConfig config;
  config.method = Method::kParallel;
  config.threads = 2;
  Broadphase at_origin(config);
  at_origin.update(site);
  for (const auto& offset : offsets) {
    const BoxSet moved = translated(site, offset);
    const std::string label = "site at (" + std::to_string(offset[0]) + ", " +
                              std::to_string(offset[1]) + ", " + std::to_string(offset[2]) + ")";
    expectStressMatch(moved, label);
    Broadphase far_away(config);
    far_away.update(moved);
    EXPECT_LT(far_away.stats().dispersion_primary, at_origin.stats().dispersion_primary + 0.05)
        << label;
  }
}

}  // namespace
}  // namespace sap_broadphase::stress
