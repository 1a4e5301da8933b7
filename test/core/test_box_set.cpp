// BoxSet and validate(): the edge where input is refused with the box's index, id and reason.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/brute_force.h"

namespace sap_broadphase {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Three valid unit boxes with ids 10, 20, 30.
BoxSet threeBoxes() {
  BoxSet boxes;
  for (uint32_t i = 0; i < 3; ++i) {
    const double lo[3] = {double(i), 0, 0};
    const double hi[3] = {double(i) + 1, 1, 1};
    boxes.add(10 * (i + 1), lo, hi);
  }
  return boxes;
}

TEST(Validate, AcceptsValidSets) {
  EXPECT_FALSE(validate(BoxSet{}).has_value());
  EXPECT_FALSE(validate(threeBoxes()).has_value());
}

TEST(Validate, AcceptsInfinitiesAndSignedZeros) {
  BoxSet boxes;
  const double slabLo[3] = {-kInf, -kInf, -kInf};
  const double slabHi[3] = {kInf, kInf, 0.0};
  boxes.add(1, slabLo, slabHi);
  const double zeroLo[3] = {0.0, -0.0, 0.0};
  const double zeroHi[3] = {-0.0, 0.0, -0.0};  // min 0.0 and max -0.0: equal, not min > max
  boxes.add(2, zeroLo, zeroHi);
  const double farLo[3] = {kInf, -kInf, 5};
  const double farHi[3] = {kInf, -kInf, 5};
  boxes.add(3, farLo, farHi);
  EXPECT_FALSE(validate(boxes).has_value()) << validate(boxes)->message();
}

TEST(Validate, RefusesNaNNamingIndexIdAndAxis) {
  const char* const kNames[2][3] = {{"min_x", "min_y", "min_z"}, {"max_x", "max_y", "max_z"}};
  for (int side = 0; side < 2; ++side) {
    for (int axis = 0; axis < 3; ++axis) {
      BoxSet boxes = threeBoxes();
      (side == 0 ? boxes.lo(axis, 1) : boxes.hi(axis, 1)) = kNaN;
      const auto error = validate(boxes);
      ASSERT_TRUE(error.has_value());
      EXPECT_EQ(error->index, 1u);
      EXPECT_EQ(error->id, 20u);
      EXPECT_NE(error->reason.find(kNames[side][axis]), std::string::npos) << error->reason;
      EXPECT_NE(error->reason.find("NaN"), std::string::npos) << error->reason;
      EXPECT_NE(error->message().find("id 20"), std::string::npos) << error->message();
    }
  }
}

TEST(Validate, RefusesMinAboveMaxNamingTheAxis) {
  const char* const kAxes[3] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    BoxSet boxes = threeBoxes();
    boxes.lo(axis, 2) = 3.0;
    boxes.hi(axis, 2) = 2.0;
    const auto error = validate(boxes);
    ASSERT_TRUE(error.has_value());
    EXPECT_EQ(error->index, 2u);
    EXPECT_EQ(error->id, 30u);
    EXPECT_NE(error->reason.find(std::string("min_") + kAxes[axis]), std::string::npos)
        << error->reason;
    EXPECT_NE(error->reason.find(std::string("max_") + kAxes[axis]), std::string::npos)
        << error->reason;
  }
  BoxSet inverted = threeBoxes();
  inverted.lo(0, 0) = kInf;
  inverted.hi(0, 0) = -kInf;
  EXPECT_TRUE(validate(inverted).has_value());
}

TEST(Validate, ReportsTheLowestBadIndex) {
  BoxSet boxes = threeBoxes();
  boxes.lo(2, 2) = kNaN;
  boxes.lo(1, 1) = 5.0;  // min_y > max_y on box 1
  const auto error = validate(boxes);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->index, 1u);
}

TEST(Validate, NamesTheProblemForCallersThatWordItTheirWay) {
  BoxSet boxes = threeBoxes();
  boxes.hi(2, 1) = kNaN;
  boxes.lo(1, 1) = 5.0;  // min_y > max_y too, but the NaN of max_z comes first
  auto error = validate(boxes);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->problem, BoxProblem::kNaN);
  EXPECT_EQ(error->coordinate, 5);
  EXPECT_EQ(error->reason, "max_z is NaN");
  boxes.hi(2, 1) = 1.0;
  error = validate(boxes);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->problem, BoxProblem::kMinAboveMax);
  EXPECT_EQ(error->coordinate, 1);
  // A repeated id on a lower index than a bad coordinate is the first problem.
  boxes = threeBoxes();
  boxes.ids[1] = boxes.ids[0];
  boxes.lo(0, 2) = kNaN;
  error = validate(boxes);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->problem, BoxProblem::kDuplicateId);
  EXPECT_EQ(error->index, 1u);
  EXPECT_EQ(error->earlier, 0u);
}

TEST(Validate, RefusesDuplicateIds) {
  BoxSet boxes = threeBoxes();
  boxes.ids[2] = 10;
  const auto error = validate(boxes);
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->id, 10u);
  EXPECT_EQ(error->index, 2u);
  EXPECT_NE(error->reason.find("duplicate"), std::string::npos) << error->reason;
}

// Dense ids (a bit per possible id) and sparse ids (sorted) name the same first repeat: the
// smallest index whose id an earlier box has, and that earlier box.
TEST(Validate, FindsTheFirstRepeatWithDenseAndSparseIds) {
  for (uint32_t spacing : {1u, 1000003u}) {
    BoxSet boxes;
    const double low[3] = {0, 0, 0}, high[3] = {1, 1, 1};
    for (uint32_t i = 0; i < 1000; ++i) boxes.add(i * spacing, low, high);
    EXPECT_FALSE(validate(boxes).has_value()) << spacing;
    boxes.ids[700] = boxes.ids[200];
    boxes.ids[900] = boxes.ids[100];
    const auto error = validate(boxes);
    ASSERT_TRUE(error.has_value()) << spacing;
    EXPECT_EQ(error->index, 700u) << spacing;
    EXPECT_EQ(error->id, 200u * spacing);
    EXPECT_NE(error->reason.find("also box 200"), std::string::npos) << error->reason;
  }
}

TEST(Validate, RefusesMismatchedLengths) {
  BoxSet short_bounds = threeBoxes();
  short_bounds.bounds.pop_back();
  EXPECT_TRUE(validate(short_bounds).has_value());
  EXPECT_THROW(short_bounds.span(), InvalidBoxes);  // a span cannot hold the mismatch
  BoxSet long_bounds = threeBoxes();
  long_bounds.bounds.push_back(1.0);
  EXPECT_TRUE(validate(long_bounds).has_value());
  BoxSet groups = threeBoxes();
  groups.groups = {1, 2};
  EXPECT_TRUE(validate(groups).has_value());
  BoxSet masks = threeBoxes();
  masks.masks = {1, 2, 3, 4};
  EXPECT_TRUE(validate(masks).has_value());
  BoxSet both = threeBoxes();
  both.groups = {1, 2, 3};
  both.masks = {1, 2, 3};
  EXPECT_FALSE(validate(both).has_value());
}

TEST(BoxSet, AddFillsDefaultFiltersWhenNeeded) {
  BoxSet boxes = threeBoxes();
  EXPECT_FALSE(boxes.hasFilters());
  const double lo[3] = {0, 0, 0};
  const double hi[3] = {1, 1, 1};
  boxes.add(40, lo, hi, 0x4u, 0x2u);
  ASSERT_EQ(boxes.groups.size(), 4u);
  ASSERT_EQ(boxes.masks.size(), 4u);
  EXPECT_EQ(boxes.group(0), kDefaultGroup);
  EXPECT_EQ(boxes.mask(0), kDefaultMask);
  EXPECT_EQ(boxes.group(3), 0x4u);
  boxes.add(50, lo, hi);
  EXPECT_EQ(boxes.groups.size(), 5u);
  EXPECT_EQ(boxes.group(4), kDefaultGroup);
  EXPECT_FALSE(validate(boxes).has_value());
  boxes.clear();
  EXPECT_EQ(boxes.size(), 0u);
}

TEST(Oracle, ClosedIntervalsAndFilters) {
  BoxSet boxes;
  const double a[2][3] = {{0, 0, 0}, {1, 1, 1}};
  const double touching[2][3] = {{1, 0, 0}, {2, 1, 1}};               // shares a face with a
  const double apart[2][3] = {{1.5, 0, 0}, {3, 1, 1}};                // overlaps touching only
  const double minusZero[2][3] = {{-1, -1, -1}, {-0.0, -0.0, -0.0}};  // touches a at a corner
  boxes.add(4, a[0], a[1]);
  boxes.add(3, touching[0], touching[1]);
  boxes.add(2, apart[0], apart[1]);
  boxes.add(1, minusZero[0], minusZero[1]);
  EXPECT_EQ(bruteForcePairs(boxes), (PairList{{1, 4}, {2, 3}, {3, 4}}));
  boxes.groups = {0x1, 0x2, 0x1, 0x1};
  boxes.masks = {0x1, 0x1, 0x2, 0xFFFFFFFF};
  // (4,3): group(4)=1 & mask(3)=1, group(3)=2 & mask(4)=1 -> 0: filtered out.
  // (3,2): group(3)=2 & mask(2)=2, group(2)=1 & mask(3)=1: allowed.
  // (4,1): group(4)=1 & mask(1)=all, group(1)=1 & mask(4)=1: allowed.
  EXPECT_EQ(bruteForcePairs(boxes), (PairList{{1, 4}, {2, 3}}));
}

}  // namespace
}  // namespace sap_broadphase
