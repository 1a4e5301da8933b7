// Unit tests of the message conversions (no ROS master needed).
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "message_read_back.h"
#include "sap_broadphase/ros/conversions.h"
#include "test_frames.h"

namespace sap_broadphase {
namespace {

using test::boxArrayToBoxSet;
using test::pairArrayToPairList;

BoxArray twoBoxes() {
  BoxArray msg;
  msg.header.frame_id = "f";
  msg.bounds = {0, 0, 0, 1, 1, 1, 1, 1, 1, 2, 2, 2};
  return msg;
}

TEST(Conversions, EmptyIdsNumberTheBoxes) {
  BoxSet boxes;
  ASSERT_FALSE(boxArrayToBoxSet(twoBoxes(), boxes));
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes.ids[0], 0u);
  EXPECT_EQ(boxes.ids[1], 1u);
  EXPECT_EQ(boxes.lo(2, 1), 1.0);
  EXPECT_EQ(boxes.hi(0, 0), 1.0);
  EXPECT_FALSE(boxes.hasFilters());
}

TEST(Conversions, RoundTripKeepsEverything) {
  BoxSet original = test::randomBoxes(200, 1.0, true, 3);
  test::randomFilters(original, 4, 4);
  const BoxArray msg = test::toMessage(original, "f");
  BoxSet back;
  ASSERT_FALSE(boxArrayToBoxSet(msg, back));
  EXPECT_EQ(back.ids, original.ids);
  EXPECT_EQ(back.groups, original.groups);
  EXPECT_EQ(back.masks, original.masks);
  EXPECT_EQ(back.bounds, original.bounds);
}

TEST(Conversions, MissingMasksOrGroupsAreTheDefaults) {
  BoxArray msg = twoBoxes();
  msg.groups = {2u, 4u};
  BoxSet boxes;
  ASSERT_FALSE(boxArrayToBoxSet(msg, boxes));
  EXPECT_EQ(boxes.groups, (std::vector<uint32_t>{2u, 4u}));
  EXPECT_EQ(boxes.mask(0), kDefaultMask);
  EXPECT_EQ(boxes.mask(1), kDefaultMask);
  msg = twoBoxes();
  msg.masks = {2u, 4u};
  ASSERT_FALSE(boxArrayToBoxSet(msg, boxes));
  EXPECT_EQ(boxes.group(0), kDefaultGroup);
  EXPECT_EQ(boxes.group(1), kDefaultGroup);
}

TEST(Conversions, ShapeErrorsNameTheArray) {
  BoxArray msg = twoBoxes();
  msg.bounds.pop_back();
  ASSERT_TRUE(checkBoxArrayShape(msg));
  EXPECT_NE(checkBoxArrayShape(msg)->find("bounds has 11 values"), std::string::npos);
  const char* names[] = {"ids", "groups", "masks"};
  for (int field = 0; field < 3; ++field) {
    msg = twoBoxes();
    std::vector<uint32_t>& array = field == 0 ? msg.ids : field == 1 ? msg.groups : msg.masks;
    array = {1u, 2u, 3u};
    const auto error = checkBoxArrayShape(msg);
    ASSERT_TRUE(error) << names[field];
    EXPECT_EQ(*error, std::string(names[field]) +
                          " has 3 entries but bounds holds 2 boxes (12 values): give one " +
                          names[field] + " entry per box, or none");
    BoxSet boxes;
    EXPECT_EQ(boxArrayToBoxSet(msg, boxes), error);
  }
}

TEST(Conversions, ValueErrorsNameTheBox) {
  BoxArray msg = twoBoxes();
  msg.ids = {10u, 20u};
  msg.bounds[4] = std::numeric_limits<double>::quiet_NaN();
  BoxSet boxes;
  auto error = boxArrayToBoxSet(msg, boxes);
  ASSERT_TRUE(error);
  EXPECT_NE(error->find("id 10"), std::string::npos) << *error;
  msg = twoBoxes();
  msg.ids = {10u, 20u};
  msg.bounds[6] = 5.0;  // min_x of id 20 above its max_x
  error = boxArrayToBoxSet(msg, boxes);
  ASSERT_TRUE(error);
  EXPECT_NE(error->find("id 20"), std::string::npos) << *error;
  msg.bounds[6] = -std::numeric_limits<double>::infinity();  // infinities are fine
  EXPECT_FALSE(boxArrayToBoxSet(msg, boxes));
}

TEST(Conversions, PairsFlattenInOrderWithTheHeader) {
  std_msgs::Header header;
  header.frame_id = "f";
  header.stamp = ros::Time(3, 4);
  PairArray msg;
  pairListToPairArray({{1, 5}, {1, 9}, {2, 3}}, header, msg);
  EXPECT_EQ(msg.header.frame_id, "f");
  EXPECT_EQ(msg.header.stamp, ros::Time(3, 4));
  EXPECT_EQ(msg.pairs, (std::vector<uint32_t>{1, 5, 1, 9, 2, 3}));
  PairList back;
  ASSERT_TRUE(pairArrayToPairList(msg, back));
  EXPECT_EQ(back, (PairList{{1, 5}, {1, 9}, {2, 3}}));
  msg.pairs.pop_back();
  EXPECT_FALSE(pairArrayToPairList(msg, back));
}

}  // namespace
}  // namespace sap_broadphase
