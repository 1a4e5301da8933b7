// Unit tests of the world's merge (SourceSet), the box transform and the capacity watch.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>
#include <boost/make_shared.hpp>

#include "sap_broadphase/core/brute_force.h"
#include "sources.h"
#include "test_frames.h"

namespace sap_broadphase {
namespace test {
namespace {

std_msgs::Header header(const char* inFrame, uint32_t inSeconds) {
  std_msgs::Header result;
  result.frame_id = inFrame;
  result.stamp = ros::Time(inSeconds, 0);
  return result;
}

BoxSet oneBox(uint32_t inId, double inLo, double inHi) {
  BoxSet boxes;
  const double lo[3] = {inLo, inLo, inLo}, hi[3] = {inHi, inHi, inHi};
  boxes.add(inId, lo, hi);
  return boxes;
}

TEST(SourceSet, UnionOfLatestFramesNewestStampAndCrossSourcePairs) {
  SourceSet sources;
  BoxSet a = oneBox(1, 0.0, 1.0), b = oneBox(2, 0.5, 1.5), a_again = oneBox(1, 5.0, 6.0);
  sources.store({"boxes", "/a", ""}, a, header("world", 10), ros::Time(100, 0));
  sources.store({"boxes", "/b", ""}, b, header("world", 12), ros::Time(100, 0));
  BoxSet world;
  WorldAssembly assembly;
  EXPECT_EQ(bruteForcePairs(*sources.assemble({}, "", world, assembly).boxes), PairList({{1, 2}}));
  EXPECT_EQ(assembly.sources_merged, 2u);
  EXPECT_TRUE(assembly.refusals.empty());
  EXPECT_EQ(assembly.header.stamp, ros::Time(12, 0));
  EXPECT_EQ(assembly.header.frame_id, "world");
  // The latest frame of /a replaces its earlier one.
  sources.store({"boxes", "/a", ""}, a_again, header("world", 11), ros::Time(101, 0));
  EXPECT_TRUE(bruteForcePairs(*sources.assemble({}, "", world, assembly).boxes).empty());
  EXPECT_EQ(world.size(), 2u);
}

TEST(SourceSet, SharedIdLeavesTheNewerSourceOutNamingBoth) {
  SourceSet sources;
  BoxSet a = oneBox(7, 0.0, 1.0), b = oneBox(7, 0.0, 1.0), c = oneBox(8, 0.0, 1.0);
  sources.store({"boxes", "/a", ""}, a, header("world", 1), ros::Time(1, 0));
  sources.store({"boxes", "/b", ""}, b, header("world", 1), ros::Time(1, 0));
  sources.store({"extra", "/c", ""}, c, header("world", 1), ros::Time(1, 0));
  BoxSet fresh_a = oneBox(7, 0.0, 1.0);  // /a publishes again: it still joined first
  sources.store({"boxes", "/a", ""}, fresh_a, header("world", 2), ros::Time(2, 0));
  BoxSet world;
  WorldAssembly assembly;
  const BoxSet& merged = *sources.assemble({}, "", world, assembly).boxes;
  ASSERT_EQ(assembly.refusals.size(), 1u);
  EXPECT_EQ(
      assembly.refusals[0].reason.rfind("id 7 of 'boxes' from /b is also in 'boxes' from /a", 0),
      0u)
      << assembly.refusals[0].reason;
  // The refusal carries the left-out frame's own header and size, for the log and stats.
  EXPECT_EQ(assembly.refusals[0].header.frame_id, "world");
  EXPECT_EQ(assembly.refusals[0].header.stamp, header("world", 1).stamp);
  EXPECT_EQ(assembly.refusals[0].boxes, 1u);
  EXPECT_EQ(assembly.sources_merged, 2u);
  EXPECT_EQ(bruteForcePairs(merged), PairList({{7, 8}}));
  // The scenery's ids are refused likewise.
  sources.assemble({3, 8, 9}, "", world, assembly);
  ASSERT_EQ(assembly.refusals.size(), 2u);
  EXPECT_NE(assembly.refusals[1].reason.find("id 8 of 'extra' from /c is also in 'static_boxes'"),
            std::string::npos)
      << assembly.refusals[1].reason;
}

TEST(SourceSet, OtherFrameRefusedNamingBothFrames) {
  SourceSet sources;
  BoxSet a = oneBox(1, 0.0, 1.0), b = oneBox(2, 0.0, 1.0);
  sources.store({"boxes", "/a", ""}, a, header("robot_a", 1), ros::Time(1, 0));
  sources.store({"boxes", "/b", ""}, b, header("robot_b", 1), ros::Time(1, 0));
  BoxSet world;
  WorldAssembly assembly;
  const BoxSet& merged = *sources.assemble({}, "", world, assembly).boxes;
  ASSERT_EQ(assembly.refusals.size(), 1u);
  EXPECT_NE(assembly.refusals[0].reason.find("'robot_b'"), std::string::npos);
  EXPECT_NE(assembly.refusals[0].reason.find("'robot_a'"), std::string::npos);
  EXPECT_EQ(merged.size(), 1u);
  // With scenery in another frame, that frame is the world's.
  sources.assemble({}, "map", world, assembly);
  EXPECT_EQ(assembly.refusals.size(), 2u);
  EXPECT_EQ(assembly.sources_merged, 0u);
}

TEST(SourceSet, FiltersOfOneSourceCompletedWithDefaults) {
  SourceSet sources;
  BoxSet plain = oneBox(1, 0.0, 1.0), filtered;
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  filtered.add(2, lo, hi, 0x2u, 0x2u);  // collides only with group 0x2: not with box 1
  filtered.add(3, lo, hi, 0x1u, 0xFFFFFFFFu);
  sources.store({"boxes", "/plain", ""}, plain, header("w", 1), ros::Time(1, 0));
  sources.store({"boxes", "/filtered", ""}, filtered, header("w", 1), ros::Time(1, 0));
  BoxSet world;
  WorldAssembly assembly;
  const BoxSet& merged = *sources.assemble({}, "", world, assembly).boxes;
  ASSERT_EQ(merged.groups.size(), 3u);
  ASSERT_EQ(merged.masks.size(), 3u);
  EXPECT_FALSE(validate(merged));
  EXPECT_EQ(bruteForcePairs(merged), PairList({{1, 3}}));
}

BoxArrayConstPtr oneBoxMessage(uint32_t inId, double inLo, double inHi, uint32_t inSeconds) {
  auto message = boost::make_shared<BoxArray>();
  message->header = header("world", inSeconds);
  message->ids = {inId};
  message->bounds = {inLo, inLo, inLo, inHi, inHi, inHi};
  return message;
}

// A frame kept as published is the world itself when it is alone, and is converted and
// checked where a union (or markers) needs its boxes.
TEST(SourceSet, KeptMessageAloneIsTheWorldAndJoinsAUnionConverted) {
  SourceSet sources;
  const SourceKey a{"boxes", "/a", "world"};
  const BoxArrayConstPtr a_frame = oneBoxMessage(1, 0.0, 1.0, 5);
  sources.storeMessage(a, a_frame, ros::Time(5, 0));
  BoxSet world;
  WorldAssembly assembly;
  World alone = sources.assemble({}, "", world, assembly, false);
  EXPECT_EQ(alone.message, a_frame.get());
  EXPECT_EQ(alone.boxes, nullptr);
  EXPECT_EQ(alone.source.publisher, "/a");
  EXPECT_EQ(alone.size(), 1u);
  EXPECT_EQ(assembly.frames_accepted, 0u);  // the engine checks it: accept() says it passed
  EXPECT_TRUE(sources.accept(a));
  EXPECT_FALSE(sources.accept(a));  // counted once
  // Markers need boxes: converted, and the same frame is not counted again.
  World drawn = sources.assemble({}, "", world, assembly, true);
  ASSERT_NE(drawn.boxes, nullptr);
  EXPECT_EQ(drawn.boxes->size(), 1u);
  EXPECT_EQ(assembly.frames_accepted, 0u);
  // A second source: both as boxes, with their cross pair.
  sources.storeMessage({"boxes", "/b", "world"}, oneBoxMessage(2, 0.5, 1.5, 6), ros::Time(6, 0));
  World both = sources.assemble({}, "", world, assembly, false);
  ASSERT_NE(both.boxes, nullptr);
  EXPECT_EQ(bruteForcePairs(*both.boxes), PairList({{1, 2}}));
  EXPECT_EQ(assembly.frames_accepted, 1u);  // /b's frame
}

TEST(SourceSet, RefusedKeptMessageFallsBackOnTheLastGoodFrame) {
  SourceSet sources;
  const SourceKey a{"boxes", "/a", "world"}, b{"boxes", "/b", "world"};
  sources.storeMessage(a, oneBoxMessage(1, 0.0, 1.0, 1), ros::Time(1, 0));
  sources.storeMessage(b, oneBoxMessage(2, 0.5, 1.5, 1), ros::Time(1, 0));
  BoxSet world;
  WorldAssembly assembly;
  EXPECT_EQ(bruteForcePairs(*sources.assemble({}, "", world, assembly).boxes), PairList({{1, 2}}));
  EXPECT_EQ(assembly.frames_accepted, 2u);
  // /a's next frame has min > max: refused, named, and /a's last good frame stays.
  sources.storeMessage(a, oneBoxMessage(1, 3.0, 2.0, 2), ros::Time(2, 0));
  EXPECT_EQ(bruteForcePairs(*sources.assemble({}, "", world, assembly).boxes), PairList({{1, 2}}));
  ASSERT_EQ(assembly.refused_frames.size(), 1u);
  EXPECT_EQ(assembly.refused_frames[0].reason,
            "'boxes' from /a in 'world': box 0 (id 1): min_x (3) > max_x (2)");
  EXPECT_EQ(assembly.refused_frames[0].header.stamp, ros::Time(2, 0));
  EXPECT_EQ(assembly.sources_merged, 2u);
  // Refused by the engine when alone: back to its last good frame, or out without one.
  SourceSet alone;
  alone.storeMessage(a, oneBoxMessage(1, 0.0, 1.0, 1), ros::Time(1, 0));
  EXPECT_TRUE(alone.accept(a));
  alone.storeMessage(a, oneBoxMessage(1, 3.0, 2.0, 2), ros::Time(2, 0));
  alone.refuse(a);
  World kept = alone.assemble({}, "", world, assembly, false);
  ASSERT_NE(kept.message, nullptr);
  EXPECT_EQ(kept.message->bounds[0], 0.0);
  EXPECT_EQ(assembly.header.stamp, ros::Time(1, 0));
  alone.storeMessage(b, oneBoxMessage(2, 3.0, 2.0, 3), ros::Time(3, 0));
  alone.refuse(b);  // never accepted: leaves
  EXPECT_EQ(alone.size(), 1u);
}

TEST(SourceSet, KeptMessageIdsMeetTheSceneryIds) {
  SourceSet sources;
  auto numbered = boost::make_shared<BoxArray>();  // no ids: boxes 0 and 1
  numbered->header = header("world", 1);
  numbered->bounds = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3};
  sources.storeMessage({"boxes", "/a", "world"}, numbered, ros::Time(1, 0));
  BoxSet world;
  WorldAssembly assembly;
  sources.assemble({1, 5}, "", world, assembly, false);
  ASSERT_EQ(assembly.refusals.size(), 1u);
  EXPECT_EQ(assembly.refusals[0].reason.rfind(
                "id 1 of 'boxes' from /a in 'world' is also in 'static_boxes'", 0),
            0u)
      << assembly.refusals[0].reason;
}

TEST(SourceSet, SilentSourcesExpire) {
  SourceSet sources;
  BoxSet a = oneBox(1, 0.0, 1.0), b = oneBox(2, 0.0, 1.0);
  sources.store({"boxes", "/a", ""}, a, header("w", 1), ros::Time(10, 0));
  sources.store({"boxes", "/b", ""}, b, header("w", 1), ros::Time(11, 0));
  BoxSet a_again = oneBox(1, 0.0, 1.0);
  sources.store({"boxes", "/a", ""}, a_again, header("w", 1), ros::Time(10, 1));
  const auto never = [](const SourceKey&) { return 0.0; };
  const auto one_second = [](const SourceKey&) { return 1.0; };
  EXPECT_TRUE(sources.expire(ros::Time(11, 500000000), never).empty()) << "0 = never";
  const std::vector<SourceSet::Expired> expired =
      sources.expire(ros::Time(11, 500000000), one_second);
  ASSERT_EQ(expired.size(), 1u);
  EXPECT_EQ(sourceName(expired[0].key), "'boxes' from /a");
  EXPECT_EQ(expired[0].frames, 2u);  // a stream, not a single frame
  EXPECT_EQ(sources.size(), 1u);
  const std::vector<SourceSet::Expired> single =
      sources.expire(ros::Time(12, 500000000), one_second);
  ASSERT_EQ(single.size(), 1u);
  EXPECT_EQ(single[0].frames, 1u);
}

TEST(SourceSet, ClockJumpingBackRestartsTheTimeOuts) {
  // A bag played again: the clock goes from 100 s back to 5 s. Received at 100 s, a source
  // would lie in the new clock's future and never time out.
  SourceSet sources;
  BoxSet a = oneBox(1, 0.0, 1.0);
  sources.store({"boxes", "/a", ""}, a, header("w", 1), ros::Time(100, 0));
  const auto one_second = [](const SourceKey&) { return 1.0; };
  sources.restartClock(ros::Time(5, 0));
  EXPECT_TRUE(sources.expire(ros::Time(5, 500000000), one_second).empty());
  EXPECT_EQ(sources.expire(ros::Time(6, 100000000), one_second).size(), 1u);
}

TEST(TransformBoxes, ContainsEveryMovedCornerAndIsTight) {
  const BoxSet boxes = randomBoxes(200, 2.0, false, 7);
  geometry_msgs::Transform transform;
  tf2::Quaternion rotation;
  rotation.setRPY(0.3, -0.7, 1.9);
  transform.rotation.x = rotation.x();
  transform.rotation.y = rotation.y();
  transform.rotation.z = rotation.z();
  transform.rotation.w = rotation.w();
  transform.translation.x = 100.0;
  transform.translation.y = -3.0;
  transform.translation.z = 0.25;
  BoxSet moved = boxes;
  transformBoxes(transform, moved);
  const tf2::Matrix3x3 matrix(rotation);
  const tf2::Vector3 shift(100.0, -3.0, 0.25);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (int corner = 0; corner < 8; ++corner) {
      const tf2::Vector3 point(corner & 1 ? boxes.hi(0, i) : boxes.lo(0, i),
                               corner & 2 ? boxes.hi(1, i) : boxes.lo(1, i),
                               corner & 4 ? boxes.hi(2, i) : boxes.lo(2, i));
      const tf2::Vector3 out = matrix * point + shift;
      for (int axis = 0; axis < 3; ++axis) {
        EXPECT_LE(moved.lo(axis, i), out[axis]) << "box " << i << " axis " << axis;
        EXPECT_GE(moved.hi(axis, i), out[axis]) << "box " << i << " axis " << axis;
        lo[axis] = std::min(lo[axis], out[axis]);
        hi[axis] = std::max(hi[axis], out[axis]);
      }
    }
    for (int axis = 0; axis < 3; ++axis) {  // outward rounding only: a few ulps at 100
      EXPECT_NEAR(moved.lo(axis, i), lo[axis], 1e-12);
      EXPECT_NEAR(moved.hi(axis, i), hi[axis], 1e-12);
    }
  }
}

TEST(TransformBoxes, TouchingBoxesStillTouchAndInfinityStaysInfinite) {
  BoxSet boxes = touchingGrid(3, 0);
  const double inf = std::numeric_limits<double>::infinity();
  const double lo[3] = {-inf, 0.0, 0.0}, hi[3] = {inf, 0.5, 0.5};
  boxes.add(1000, lo, hi);
  geometry_msgs::Transform transform;
  tf2::Quaternion rotation;
  rotation.setRPY(0.0, 0.0, 0.4);
  transform.rotation.x = rotation.x();
  transform.rotation.y = rotation.y();
  transform.rotation.z = rotation.z();
  transform.rotation.w = rotation.w();
  transform.translation.x = 0.1;
  BoxSet moved = boxes;
  transformBoxes(transform, moved);
  EXPECT_FALSE(validate(moved));
  const PairList before = bruteForcePairs(boxes), after = bruteForcePairs(moved);
  EXPECT_TRUE(std::includes(after.begin(), after.end(), before.begin(), before.end()));
  EXPECT_EQ(moved.lo(0, moved.size() - 1), -inf);
  EXPECT_EQ(moved.hi(1, moved.size() - 1), inf) << "x mixes into y under a yaw";
}

}  // namespace
}  // namespace test
}  // namespace sap_broadphase
