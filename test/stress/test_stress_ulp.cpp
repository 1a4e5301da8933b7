// Coordinates where float32 keys lose precision (2^24, 2^53, 1e300, DBL_MAX): 1-ulp gaps must
// not pair, exact touching and 1-ulp overlaps must, on every axis and with every key collision.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "sap_broadphase/core/brute_force.h"
#include "stress_scenes.h"
#include "stress_support.h"

namespace sap_broadphase::stress {
namespace {

// Where the float32 keys of neighbouring doubles collide, plus the easy cases.
const double kBases[] = {0x1p24,
                         0x1p24 + 1.0,
                         0x1p53,
                         -0x1p53,
                         1.0,
                         -1.0,
                         1e300,
                         -1e300,
                         std::numeric_limits<double>::max() / 2,
                         static_cast<double>(std::numeric_limits<float>::max()),
                         1e-300,
                         std::numeric_limits<double>::min(),
                         0.0};

std::string baseName(double inBase) {
  char text[64];
  std::snprintf(text, sizeof text, "%a", inBase);
  return text;
}

// Box 0 ends at inEdge on inAxis; box 1 starts inSteps ulps after it (negative: overlap).
BoxSet edgePair(double inEdge, int inSteps, int inAxis) {
  BoxSet boxes;
  double low0[3] = {0.0, 0.0, 0.0};
  double high0[3] = {1.0, 1.0, 1.0};
  double low1[3] = {0.0, 0.0, 0.0};
  double high1[3] = {1.0, 1.0, 1.0};
  low0[inAxis] = ulpStep(inEdge, -1000);
  high0[inAxis] = inEdge;
  low1[inAxis] = ulpStep(inEdge, inSteps);
  high1[inAxis] = ulpStep(inEdge, 1000);
  boxes.add(0, low0, high0);
  boxes.add(1, low1, high1);
  return boxes;
}

TEST(StressUlp, OneUlpGapTouchAndOverlapPerAxis) {
  for (double base : kBases) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int steps : {2, 1, 0, -1, -2}) {
        const BoxSet boxes = edgePair(base, steps, axis);
        const PairList expected = steps > 0 ? PairList{} : PairList{{0, 1}};
        const std::string label = "edge " + baseName(base) + " axis " + std::to_string(axis) +
                                  " gap " + std::to_string(steps) + " ulp";
        ASSERT_TRUE(samePairList(expected, bruteForcePairs(boxes))) << label;
        expectStressMatch(boxes, expected, label);
      }
    }
  }
}

// Many boxes at once: every base gets a lattice in its own ulps, 2500 boxes, touching and
// 1-ulp gaps everywhere; float32 keys of all corners are nearly or exactly equal.
TEST(StressUlp, UlpLatticeNear2Pow24) {
  expectStressMatch(ulpLatticeScene(0x1p24, 2500, 12, 2, 61), "ulp lattice at 2^24");
}

TEST(StressUlp, UlpLatticeNear2Pow53) {
  expectStressMatch(ulpLatticeScene(0x1p53, 2500, 12, 2, 62), "ulp lattice at 2^53");
  expectStressMatch(ulpLatticeScene(-0x1p53, 2500, 12, 2, 63), "ulp lattice at -2^53");
}

TEST(StressUlp, UlpLatticeNear1e300AndOne) {
  expectStressMatch(ulpLatticeScene(1e300, 2500, 12, 2, 64), "ulp lattice at 1e300");
  expectStressMatch(ulpLatticeScene(1.0, 2500, 12, 2, 65), "ulp lattice at 1");
  expectStressMatch(ulpLatticeScene(0.0, 2500, 12, 2, 66), "ulp lattice at 0 (subnormals)");
}

TEST(StressUlp, UlpLatticeAtDoubleMax) {
  // The lattice reaches past DBL_MAX: its top cells are +infinity.
  expectStressMatch(ulpLatticeScene(std::numeric_limits<double>::max(), 2000, 10, 2, 67),
                    "ulp lattice at DBL_MAX");
}

// Integer coordinates just above 2^24: doubles hold them exactly, float32 keys round pairs of
// them together. A one-unit gap must not pair; the keys must not lose the touching pairs.
TEST(StressUlp, IntegersAbove2Pow24) {
  SplitMix64 random(68);
  BoxSet boxes;
  for (uint32_t i = 0; i < 4000; ++i) {
    double low[3];
    double high[3];
    for (int axis = 0; axis < 3; ++axis) {
      low[axis] = 0x1p24 + static_cast<double>(random.below(60));
      high[axis] = low[axis] + static_cast<double>(random.below(3));
    }
    boxes.add(i, low, high);
  }
  expectStressMatch(boxes, "integers above 2^24");
}

// Rows of boxes each one ulp apart (no pair) or touching (pair) along x at 2^53.
TEST(StressUlp, RowsAt2Pow53) {
  BoxSet boxes;
  uint32_t id = 0;
  for (int row = 0; row < 40; ++row) {
    const bool touching = row % 2 == 0;
    double x = 0x1p53;
    for (int k = 0; k < 60; ++k) {
      const double next = ulpStep(x, 1);
      const double low[3] = {x, static_cast<double>(row) * 2.0, 0.0};
      const double high[3] = {next, static_cast<double>(row) * 2.0 + 1.0, 1.0};
      boxes.add(id++, low, high);
      x = touching ? next : ulpStep(next, 1);
    }
  }
  const PairList oracle = bruteForcePairs(boxes);
  EXPECT_EQ(oracle.size(), 20u * 59u) << "touching rows pair neighbours, gapped rows nothing";
  expectStressMatch(boxes, oracle, "rows of 1-ulp boxes at 2^53");
}

}  // namespace
}  // namespace sap_broadphase::stress
