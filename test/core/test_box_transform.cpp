// Moving boxes between frames (core/box_transform.h): the 8 corners rounded outwards, a box that
// is no box left as published, and transforms that are not finite refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/tools/box_transform.h"
#include "sap_broadphase/core/box_set.h"

namespace sap_broadphase {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

BoxSet unitBoxAt(double inX) {
  BoxSet boxes;
  const double lo[3] = {inX, 0.0, 0.0}, hi[3] = {inX + 1.0, 1.0, 1.0};
  boxes.add(1, lo, hi);
  return boxes;
}

/// A rotation of inRadians about z.
RigidTransform yaw(double inRadians) {
  RigidTransform transform;
  transform.rotation[2] = std::sin(inRadians / 2);
  transform.rotation[3] = std::cos(inRadians / 2);
  return transform;
}

TEST(BoxTransform, AQuarterTurnAboutZMapsXOntoY) {
  BoxSet boxes = unitBoxAt(2.0);  // x in [2, 3], y in [0, 1]
  RigidTransform transform = yaw(M_PI / 2);
  transform.translation[2] = 5.0;
  transformBoxes(transform, boxes);
  // (x, y) -> (-y, x): x in [-1, 0], y in [2, 3]; z moved by 5. Outwards only, by a few ulps.
  const double expected_lo[3] = {-1.0, 2.0, 5.0}, expected_hi[3] = {0.0, 3.0, 6.0};
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_LE(boxes.lo(axis, 0), expected_lo[axis]) << "axis " << axis;
    EXPECT_GE(boxes.hi(axis, 0), expected_hi[axis]) << "axis " << axis;
    EXPECT_NEAR(boxes.lo(axis, 0), expected_lo[axis], 1e-12) << "axis " << axis;
    EXPECT_NEAR(boxes.hi(axis, 0), expected_hi[axis], 1e-12) << "axis " << axis;
  }
}

TEST(BoxTransform, TheQuaternionsLengthIsDividedOut) {
  RigidTransform unit = yaw(0.7), scaled = unit;
  for (double& component : scaled.rotation) component *= 3.0;
  BoxSet a = unitBoxAt(4.0), b = unitBoxAt(4.0);
  transformBoxes(unit, a);
  transformBoxes(scaled, b);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(a.lo(axis, 0), b.lo(axis, 0), 1e-12);
    EXPECT_NEAR(a.hi(axis, 0), b.hi(axis, 0), 1e-12);
  }
}

TEST(BoxTransform, TheIdentityOnlyRoundsOutwards) {
  BoxSet boxes = unitBoxAt(1e6);
  transformBoxes(RigidTransform(), boxes);
  EXPECT_LT(boxes.lo(0, 0), 1e6);
  EXPECT_GT(boxes.hi(0, 0), 1e6 + 1.0);
  EXPECT_NEAR(boxes.lo(0, 0), 1e6, 1e-6);
  EXPECT_NEAR(boxes.hi(0, 0), 1e6 + 1.0, 1e-6);
}

TEST(BoxTransform, ABoxThatIsNoBoxStaysAsPublished) {
  BoxSet boxes;
  const double lo_nan[3] = {0.0, kNaN, 0.0}, hi_nan[3] = {1.0, 1.0, 1.0};
  const double lo_reversed[3] = {0.0, 0.0, 3.0}, hi_reversed[3] = {1.0, 1.0, 2.0};
  boxes.add(1, lo_nan, hi_nan);
  boxes.add(2, lo_reversed, hi_reversed);
  RigidTransform transform;
  transform.translation[2] = 10.0;
  transformBoxes(transform, boxes);
  EXPECT_TRUE(std::isnan(boxes.lo(1, 0)));
  EXPECT_EQ(boxes.lo(2, 1), 3.0);
  EXPECT_EQ(boxes.hi(2, 1), 2.0);
  ASSERT_TRUE(validate(boxes));
  EXPECT_EQ(validate(boxes)->message(), "box 0 (id 1): min_y is NaN");
}

TEST(BoxTransform, ATransformThatIsNotFiniteIsRefusedNamingItsComponent) {
  const char* names[7] = {"translation.x", "translation.y", "translation.z", "rotation.x",
                          "rotation.y",    "rotation.z",    "rotation.w"};
  for (int component = 0; component < 7; ++component) {
    for (const double bad : {kInf, -kInf, kNaN}) {
      RigidTransform transform;
      double* value =
          component < 3 ? &transform.translation[component] : &transform.rotation[component - 3];
      *value = bad;
      const auto problem = nonFiniteTransform(transform);
      ASSERT_TRUE(problem) << names[component];
      EXPECT_EQ(problem->rfind(std::string(names[component]) + " is ", 0), 0u) << *problem;
      BoxSet boxes = unitBoxAt(0.0);
      const BoxSet published = boxes;
      EXPECT_EQ(moveBoxes(transform, boxes), problem);
      EXPECT_EQ(boxes.bounds, published.bounds) << "refused: the boxes are not moved";
    }
  }
  EXPECT_FALSE(nonFiniteTransform(RigidTransform()));
  BoxSet boxes = unitBoxAt(0.0);
  RigidTransform shift;
  shift.translation[0] = 2.0;
  EXPECT_FALSE(moveBoxes(shift, boxes));
  EXPECT_GE(boxes.hi(0, 0), 3.0);
}

TEST(BoxTransform, AnInfiniteBoundStaysInfiniteAndNeverBecomesNaN) {
  BoxSet boxes;
  const double lo[3] = {-kInf, 0.0, 0.0}, hi[3] = {kInf, 0.5, 0.5};
  boxes.add(1, lo, hi);
  transformBoxes(yaw(0.4), boxes);
  EXPECT_FALSE(validate(boxes));
  EXPECT_EQ(boxes.lo(0, 0), -kInf);
  EXPECT_EQ(boxes.hi(1, 0), kInf) << "x mixes into y under a yaw";
  EXPECT_LT(boxes.lo(2, 0), 0.0) << "z untouched but rounded outwards";
  EXPECT_GT(boxes.lo(2, 0), -1e-15);
}

}  // namespace
}  // namespace sap_broadphase
