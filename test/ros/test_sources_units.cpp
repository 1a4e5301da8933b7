// Unit tests of the world's sources (SourceSet), the node's words for a refused world and the
// box transform.
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>
#include <boost/make_shared.hpp>

#include "sap_broadphase/core/broadphase.h"
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

SourceFramePtr recordsFrame(BoxSet inBoxes, const std_msgs::Header& inHeader) {
  auto frame = std::make_shared<SourceFrame>();
  frame->header = inHeader;
  frame->records = std::move(inBoxes);
  return frame;
}

SourceFramePtr messageFrame(BoxArrayConstPtr inMessage) {
  auto frame = std::make_shared<SourceFrame>();
  frame->header = inMessage->header;
  frame->message = std::move(inMessage);
  return frame;
}

BoxArrayConstPtr oneBoxMessage(uint32_t inId, double inLo, double inHi, uint32_t inSeconds) {
  auto message = boost::make_shared<BoxArray>();
  message->header = header("world", inSeconds);
  message->ids = {inId};
  message->bounds = {inLo, inLo, inLo, inHi, inHi, inHi};
  return message;
}

/// The spans of a world, as the worker hands them to the engine.
std::vector<BoxSpan> spansOf(const WorldAssembly& inWorld) {
  std::vector<BoxSpan> spans;
  for (const WorldMember& member : inWorld.members) spans.push_back(member.frame->span());
  return spans;
}

/// Why the engine refuses inWorld, in the node's words (empty when it accepts it).
std::string refusalOf(const WorldAssembly& inWorld, const BoxSet& inScenery = BoxSet()) {
  Broadphase engine;
  engine.setStaticBoxes(inScenery);
  try {
    engine.update(BoxFrame(spansOf(inWorld)));
  } catch (const InvalidBoxes& refusal) {
    return worldRefusal(refusal.error(), inWorld);
  }
  return "";
}

/// Two sources, 'boxes' from /a (first) and from /b, each with one frame.
void storeTwo(SourceSet& ioSources, const BoxSet& inA, const char* inFrameA, const BoxSet& inB,
              const char* inFrameB) {
  ioSources.store({"boxes", "/a", ""}, recordsFrame(inA, header(inFrameA, 1)), ros::Time(1, 0));
  ioSources.store({"boxes", "/b", ""}, recordsFrame(inB, header(inFrameB, 1)), ros::Time(1, 0));
}

/// The world of the two sources of storeTwo().
WorldAssembly worldOfTwo(const BoxSet& inA, const char* inFrameA, const BoxSet& inB,
                         const char* inFrameB) {
  SourceSet sources;
  storeTwo(sources, inA, inFrameA, inB, inFrameB);
  WorldAssembly world;
  sources.assemble("", world);
  return world;
}

TEST(SourceSet, WorldIsTheLatestFrameOfEachSourceInTheOrderTheyAppeared) {
  SourceSet sources;
  const SourceKey a{"boxes", "/a", ""}, b{"boxes", "/b", ""};
  sources.store(b, recordsFrame(oneBox(2, 0.5, 1.5), header("world", 12)), ros::Time(100, 0));
  sources.store(a, messageFrame(oneBoxMessage(1, 0.0, 1.0, 10)), ros::Time(100, 0));
  WorldAssembly world;
  sources.assemble("", world);
  ASSERT_EQ(world.members.size(), 2u);
  EXPECT_EQ(world.members[0].key.publisher, "/b") << "/b appeared first";
  EXPECT_TRUE(world.left_out.empty());
  EXPECT_EQ(world.header().stamp, ros::Time(12, 0));
  EXPECT_EQ(world.header().frame_id, "world");
  // A message is read where it lies, records where the node wrote them: no copy.
  EXPECT_EQ(world.members[1].frame->span().bounds, world.members[1].frame->message->bounds.data());
  EXPECT_EQ(world.members[0].frame->span().bounds, world.members[0].frame->records.bounds.data());
  EXPECT_EQ(bruteForcePairs(BoxFrame(spansOf(world))), PairList({{1, 2}}));
  // The latest frame of /b replaces its earlier one; /b still comes first.
  sources.store(b, recordsFrame(oneBox(2, 5.0, 6.0), header("world", 13)), ros::Time(101, 0));
  sources.assemble("", world);
  ASSERT_EQ(world.members.size(), 2u);
  EXPECT_EQ(world.members[0].key.publisher, "/b");
  EXPECT_TRUE(bruteForcePairs(BoxFrame(spansOf(world))).empty());
}

TEST(SourceSet, OtherFrameLeftOutNamingBothFrames) {
  SourceSet sources;
  storeTwo(sources, oneBox(1, 0.0, 1.0), "robot_a", oneBox(2, 0.0, 1.0), "robot_b");
  WorldAssembly world;
  sources.assemble("", world);
  ASSERT_EQ(world.left_out.size(), 1u);
  EXPECT_NE(world.left_out[0].reason.find("'robot_b'"), std::string::npos);
  EXPECT_NE(world.left_out[0].reason.find("'robot_a'"), std::string::npos);
  EXPECT_EQ(world.left_out[0].source.key.publisher, "/b");
  EXPECT_EQ(world.members.size(), 1u);
  // With scenery in another frame, that frame is the world's.
  sources.assemble("map", world);
  EXPECT_EQ(world.left_out.size(), 2u);
  EXPECT_TRUE(world.members.empty());
  EXPECT_EQ(sources.size(), 2u) << "left out of a frame, not forgotten";
}

TEST(SourceSet, RefusedFrameFallsBackOnTheLastAcceptedOne) {
  SourceSet sources;
  const SourceKey a{"boxes", "/a", "world"};
  const SourceFramePtr good = messageFrame(oneBoxMessage(1, 0.0, 1.0, 1));
  sources.store(a, good, ros::Time(1, 0));
  EXPECT_TRUE(sources.accept(a));
  EXPECT_FALSE(sources.accept(a)) << "a frame is accepted (and counted) once";
  sources.store(a, messageFrame(oneBoxMessage(1, 3.0, 2.0, 2)), ros::Time(2, 0));
  EXPECT_EQ(sources.refuse(a), good);
  WorldAssembly world;
  sources.assemble("", world);
  ASSERT_EQ(world.members.size(), 1u);
  EXPECT_EQ(world.members[0].frame, good);
  EXPECT_EQ(world.header().stamp, ros::Time(1, 0));
  // The accepted frame refused in turn (an id the scenery now has): the source leaves.
  EXPECT_EQ(sources.refuse(a), nullptr);
  EXPECT_EQ(sources.size(), 0u);
  // A source whose first frame is refused has nothing to fall back on.
  sources.store(a, messageFrame(oneBoxMessage(1, 3.0, 2.0, 3)), ros::Time(3, 0));
  EXPECT_EQ(sources.refuse(a), nullptr);
  EXPECT_EQ(sources.size(), 0u);
}

TEST(WorldRefusal, NamesTheSourceAndItsOwnBox) {
  SourceSet sources;
  BoxSet a = oneBox(1, 0.0, 1.0);
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  a.add(2, lo, hi);
  auto bad = boost::make_shared<BoxArray>();  // no ids: boxes 0 and 1
  bad->header = header("world", 2);
  bad->bounds = {0, 0, 0, 1, 1, 1, 3, 0, 0, 2, 1, 1};
  sources.store({"boxes", "/a", "world"}, recordsFrame(a, header("world", 1)), ros::Time(1, 0));
  sources.store({"boxes", "/b", "world"}, messageFrame(bad), ros::Time(1, 0));
  WorldAssembly world;
  sources.assemble("", world);
  // Box 3 of the world is box 1 of /b's frame.
  EXPECT_EQ(refusalOf(world), "'boxes' from /b in 'world': box 1 (id 1): min_x (3) > max_x (2)");
}

TEST(WorldRefusal, SharedIdNamesBothSourcesOrTheScenery) {
  WorldAssembly world = worldOfTwo(oneBox(7, 0.0, 1.0), "world", oneBox(7, 0.0, 1.0), "world");
  const std::string shared = refusalOf(world);
  EXPECT_EQ(shared.rfind("id 7 of 'boxes' from /b is also in 'boxes' from /a: give each source", 0),
            0u)
      << shared;
  // The scenery's ids likewise; numbered boxes (no ids) have ids too.
  SourceSet alone;
  auto numbered = boost::make_shared<BoxArray>();
  numbered->header = header("world", 1);
  numbered->bounds = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3};
  alone.store({"boxes", "/c", "world"}, messageFrame(numbered), ros::Time(1, 0));
  alone.assemble("", world);
  BoxSet scenery = oneBox(1, 10.0, 11.0);
  const std::string with_scenery = refusalOf(world, scenery);
  EXPECT_EQ(with_scenery.rfind("id 1 of 'boxes' from /c in 'world' is also in 'static_boxes'", 0),
            0u)
      << with_scenery;
  // An id repeated within one frame is that frame's problem, its boxes numbered as it numbers
  // them.
  BoxSet twice = oneBox(4, 0.0, 1.0);
  const double lo[3] = {5, 5, 5}, hi[3] = {6, 6, 6};
  twice.add(4, lo, hi);
  world = worldOfTwo(oneBox(1, 0.0, 1.0), "world", twice, "world");
  EXPECT_EQ(refusalOf(world), "'boxes' from /b: box 1 (id 4): duplicate id (also box 0)");
}

TEST(SourceFrame, IdOffsetReachesTheEngine) {
  SourceFrame frame;
  frame.records = oneBox(6, 0.0, 1.0);
  frame.id_offset = 4294967290u;
  EXPECT_EQ(frame.span().idOf(0), 4294967296u);
  const auto error = validate(BoxFrame(frame.span()));
  ASSERT_TRUE(error);
  EXPECT_EQ(error->problem, BoxProblem::kIdOverflow) << error->message();
}

TEST(SourceSet, SilentSourcesExpire) {
  SourceSet sources;
  sources.store({"boxes", "/a", ""}, recordsFrame(oneBox(1, 0.0, 1.0), header("w", 1)),
                ros::Time(10, 0));
  sources.store({"boxes", "/b", ""}, recordsFrame(oneBox(2, 0.0, 1.0), header("w", 1)),
                ros::Time(11, 0));
  sources.store({"boxes", "/a", ""}, recordsFrame(oneBox(1, 0.0, 1.0), header("w", 1)),
                ros::Time(10, 1));
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
  sources.store({"boxes", "/a", ""}, recordsFrame(oneBox(1, 0.0, 1.0), header("w", 1)),
                ros::Time(100, 0));
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

TEST(TransformBoxes, ABoxThatIsNoBoxStaysAsPublished) {
  // Moved, a NaN bound would become infinite and min > max would become a box: either would
  // pass the engine's check, which must name the box in the sender's own numbers.
  BoxSet boxes = oneBox(1, 0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double lo_nan[3] = {0.0, nan, 0.0}, hi_nan[3] = {1.0, 1.0, 1.0};
  const double lo_reversed[3] = {0.0, 0.0, 3.0}, hi_reversed[3] = {1.0, 1.0, 2.0};
  boxes.add(2, lo_nan, hi_nan);
  boxes.add(3, lo_reversed, hi_reversed);
  geometry_msgs::Transform transform;
  transform.rotation.w = 1.0;
  transform.translation.z = 10.0;
  BoxSet moved = boxes;
  transformBoxes(transform, moved);
  EXPECT_GT(moved.lo(2, 0), 9.0) << "a box is moved";
  EXPECT_TRUE(std::isnan(moved.lo(1, 1)));
  EXPECT_EQ(moved.lo(2, 2), 3.0);
  EXPECT_EQ(moved.hi(2, 2), 2.0);
  const auto error = validate(moved);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->message(), "box 1 (id 2): min_y is NaN");
}

}  // namespace
}  // namespace test
}  // namespace sap_broadphase
