// Unit tests of the node's ingest without a roscore: SourcePlacement against a tf2 buffer filled
// by hand, SourceMailbox with a fake clock and a recorder of its reports, and the refusal and
// fall-back loop that loads a world into the engine (loadWorld).
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tf2/buffer_core.h>
#include <boost/make_shared.hpp>

#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/brute_force.h"
#include "source_mailbox.h"
#include "source_placement.h"
#include "sources.h"
#include "world_snapshot.h"

namespace sap_broadphase {
namespace test {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

BoxArrayConstPtr oneBoxMessage(const std::string& inFrame, uint32_t inId, double inLo, double inHi,
                               uint32_t inSeconds = 1) {
  auto message = boost::make_shared<BoxArray>();
  message->header.frame_id = inFrame;
  message->header.stamp = ros::Time(inSeconds, 0);
  message->ids = {inId};
  message->bounds = {inLo, inLo, inLo, inHi, inHi, inHi};
  return message;
}

std::shared_ptr<SourceFrame> frameOf(BoxArrayConstPtr inMessage) {
  auto frame = std::make_shared<SourceFrame>();
  frame->header = inMessage->header;
  frame->message = std::move(inMessage);
  return frame;
}

/// A static transform of inChild in inParent, moved by inX along x.
void addShift(tf2::BufferCore& ioTransforms, const std::string& inParent,
              const std::string& inChild, double inX) {
  geometry_msgs::TransformStamped transform;
  transform.header.frame_id = inParent;
  transform.child_frame_id = inChild;
  transform.transform.translation.x = inX;
  transform.transform.rotation.w = 1.0;
  ASSERT_TRUE(ioTransforms.setTransform(transform, "test", true));
}

// ---- SourcePlacement ----

TEST(SourcePlacement, WithoutFixedFrameBoxesAreReadWhereTheyLie) {
  const SourcePlacement placement("", nullptr);
  auto frame = frameOf(oneBoxMessage("robot", 1, 0.0, 1.0));
  const double* published = frame->message->bounds.data();
  EXPECT_TRUE(placement.canPlace("anything", ros::Time(5, 0)));
  EXPECT_FALSE(placement.unplaceableFrame(""));
  EXPECT_FALSE(placement.place(ros::Time(0), *frame));
  ASSERT_TRUE(frame->message) << "not copied";
  EXPECT_EQ(frame->span().bounds, published);
  EXPECT_EQ(frame->header.frame_id, "robot");
}

TEST(SourcePlacement, MovesIntoTheFixedFrameAsRecords) {
  tf2::BufferCore transforms;
  addShift(transforms, "map", "robot", 10.0);
  const SourcePlacement placement("map", &transforms);
  EXPECT_TRUE(placement.canPlace("robot", ros::Time(0)));
  auto frame = frameOf(oneBoxMessage("robot", 7, 0.0, 1.0));
  ASSERT_FALSE(placement.place(ros::Time(0), *frame));
  EXPECT_FALSE(frame->message) << "moved: the records are the frame now";
  EXPECT_EQ(frame->header.frame_id, "map");
  ASSERT_EQ(frame->records.size(), 1u);
  EXPECT_EQ(frame->records.ids[0], 7u);
  // Rounded outwards: contains [10, 11] in x, and [0, 1] in y.
  EXPECT_LE(frame->records.lo(0, 0), 10.0);
  EXPECT_GT(frame->records.lo(0, 0), 9.99);
  EXPECT_GE(frame->records.hi(0, 0), 11.0);
  EXPECT_LT(frame->records.hi(0, 0), 11.01);
  EXPECT_LE(frame->records.lo(1, 0), 0.0);
  EXPECT_GE(frame->records.hi(1, 0), 1.0);
  // Records (an adapter's) are moved where they are.
  frame->header.frame_id = "robot";
  ASSERT_FALSE(placement.place(ros::Time(0), *frame));
  EXPECT_GE(frame->records.hi(0, 0), 21.0);
}

TEST(SourcePlacement, NoTransformIsSaidSoAndLeavesTheBoxesAsPublished) {
  tf2::BufferCore transforms;
  const SourcePlacement placement("map", &transforms);
  EXPECT_FALSE(placement.canPlace("robot", ros::Time(0)));
  auto frame = frameOf(oneBoxMessage("robot", 1, 0.0, 1.0));
  const auto refusal = placement.place(ros::Time(0), *frame);
  ASSERT_TRUE(refusal);
  EXPECT_EQ(refusal->kind, PlacementRefusal::Kind::kNoTransform);
  EXPECT_EQ(refusal->reason.rfind("no transform into 'map': ", 0), 0u) << refusal->reason;
  EXPECT_EQ(frame->span().bounds[3], 1.0);
  EXPECT_EQ(frame->header.frame_id, "robot");
}

TEST(SourcePlacement, AnInfiniteTransformIsRefusedNamingIt) {
  tf2::BufferCore transforms;
  addShift(transforms, "map", "r_inf", kInfinity);  // tf2 refuses NaN, not infinity
  const SourcePlacement placement("map", &transforms);
  auto frame = frameOf(oneBoxMessage("r_inf", 1, 0.0, 1.0));
  const auto refusal = placement.place(ros::Time(0), *frame);
  ASSERT_TRUE(refusal);
  EXPECT_EQ(refusal->kind, PlacementRefusal::Kind::kBadTransform);
  EXPECT_NE(refusal->reason.find("the transform from 'r_inf' into 'map'"), std::string::npos)
      << refusal->reason;
  // tf2's lookup composes the infinite shift (inf - inf is NaN): either is named.
  EXPECT_NE(refusal->reason.find("is not finite (translation.x is "), std::string::npos)
      << refusal->reason;
  EXPECT_EQ(frame->span().bounds[0], 0.0) << "not moved";
  EXPECT_EQ(frame->span().bounds[3], 1.0) << "not moved";
}

TEST(SourcePlacement, AnEmptyFrameIdCanNeverBePlaced) {
  tf2::BufferCore transforms;
  const SourcePlacement placement("map", &transforms);
  const auto reason = placement.unplaceableFrame("");
  ASSERT_TRUE(reason);
  EXPECT_NE(reason->find("~fixed_frame 'map'"), std::string::npos) << *reason;
  auto frame = frameOf(oneBoxMessage("", 1, 0.0, 1.0));
  const auto refusal = placement.place(ros::Time(0), *frame);
  ASSERT_TRUE(refusal);
  EXPECT_EQ(refusal->kind, PlacementRefusal::Kind::kUnplaceable);
}

// ---- SourceMailbox ----

/// What a mailbox reported, and a clock and wake-ups the test drives.
struct MailboxFixture : public MailboxReport {
  void dropped() override { ++drops; }
  void skipped(const std::string& inWhy) override { skips.push_back(inWhy); }

  int drops = 0;
  std::vector<std::string> skips;
  int wakes = 0;
  ros::Time now{100, 0};
};

TEST(SourceMailbox, TheLatestFrameOfASourceWinsAndWakesTheWorker) {
  const SourcePlacement placement("", nullptr);
  MailboxFixture fixture;
  SourceMailbox mailbox(
      placement, 2.0, [&] { return fixture.now; }, fixture, [&] { ++fixture.wakes; });
  const SourceKey a{"boxes", "/a", "world"}, b{"boxes", "/b", "world"};
  mailbox.post(a, frameOf(oneBoxMessage("world", 1, 0.0, 1.0, 1)));
  mailbox.post(a, frameOf(oneBoxMessage("world", 1, 0.0, 1.0, 2)));
  fixture.now = ros::Time(101, 0);
  mailbox.post(b, frameOf(oneBoxMessage("world", 2, 0.0, 1.0, 3)));
  EXPECT_EQ(fixture.wakes, 3);
  EXPECT_EQ(fixture.drops, 1) << "the first frame of /a never started";
  std::map<SourceKey, Delivery> deliveries;
  BoxArrayConstPtr scenery;
  mailbox.take(deliveries, scenery);
  ASSERT_EQ(deliveries.size(), 2u);
  EXPECT_EQ(deliveries[a].frame->header.stamp, ros::Time(2, 0));
  EXPECT_EQ(deliveries[a].received, ros::Time(100, 0));
  EXPECT_EQ(deliveries[b].received, ros::Time(101, 0));
  EXPECT_FALSE(scenery);
  mailbox.take(deliveries, scenery);
  EXPECT_TRUE(deliveries.empty()) << "taken once";
}

TEST(SourceMailbox, AFrameWaitsForItsTransformThenGoesOrIsSkipped) {
  tf2::BufferCore transforms;
  const SourcePlacement placement("map", &transforms);
  MailboxFixture fixture;
  SourceMailbox mailbox(
      placement, 2.0, [&] { return fixture.now; }, fixture, [&] { ++fixture.wakes; });
  const SourceKey a{"boxes", "/a", "robot"}, late{"boxes", "/late", "nowhere"};
  mailbox.post(a, frameOf(oneBoxMessage("robot", 1, 0.0, 1.0)));
  mailbox.post(late, frameOf(oneBoxMessage("nowhere", 2, 0.0, 1.0)));
  EXPECT_EQ(fixture.wakes, 0) << "nothing is ready";
  EXPECT_TRUE(mailbox.anyWaiting());
  std::map<SourceKey, Delivery> deliveries;
  BoxArrayConstPtr scenery;
  mailbox.take(deliveries, scenery);
  EXPECT_TRUE(deliveries.empty());
  // Its transform arrives: the frame of /a goes to the worker; /late still waits.
  addShift(transforms, "map", "robot", 1.0);
  fixture.now = ros::Time(101, 0);
  mailbox.take(deliveries, scenery);
  ASSERT_EQ(deliveries.size(), 1u);
  EXPECT_EQ(deliveries.begin()->first.publisher, "/a");
  EXPECT_TRUE(fixture.skips.empty());
  EXPECT_TRUE(mailbox.anyWaiting());
  // Past ~transform_timeout (2 s after its receipt at 100 s): skipped, named.
  fixture.now = ros::Time(102, 500000000);
  mailbox.take(deliveries, scenery);
  EXPECT_TRUE(deliveries.empty());
  ASSERT_EQ(fixture.skips.size(), 1u);
  EXPECT_NE(fixture.skips[0].find("'boxes' from /late"), std::string::npos) << fixture.skips[0];
  EXPECT_NE(fixture.skips[0].find("~transform_timeout"), std::string::npos) << fixture.skips[0];
  EXPECT_FALSE(mailbox.anyWaiting());
}

TEST(SourceMailbox, AClockGoneBackRestartsTheWait) {
  tf2::BufferCore transforms;
  const SourcePlacement placement("map", &transforms);
  MailboxFixture fixture;
  SourceMailbox mailbox(
      placement, 2.0, [&] { return fixture.now; }, fixture, [&] { ++fixture.wakes; });
  mailbox.post({"boxes", "/a", "robot"}, frameOf(oneBoxMessage("robot", 1, 0.0, 1.0)));
  // The clock goes back to 10 s (a bag loops): 10 s is not 2 s past the receipt at 100 s in
  // the new clock's eyes, since the receipt counts as 10 s now.
  fixture.now = ros::Time(10, 0);
  mailbox.restartClock(fixture.now);
  fixture.now = ros::Time(11, 0);
  std::map<SourceKey, Delivery> deliveries;
  BoxArrayConstPtr scenery;
  mailbox.take(deliveries, scenery);
  EXPECT_TRUE(fixture.skips.empty());
  fixture.now = ros::Time(12, 500000000);
  mailbox.take(deliveries, scenery);
  EXPECT_EQ(fixture.skips.size(), 1u);
}

TEST(SourceMailbox, TheSceneryWaitsForItsTransformAsLongAsItTakes) {
  tf2::BufferCore transforms;
  const SourcePlacement placement("map", &transforms);
  MailboxFixture fixture;
  SourceMailbox mailbox(
      placement, 2.0, [&] { return fixture.now; }, fixture, [&] { ++fixture.wakes; });
  mailbox.postScenery(oneBoxMessage("building", 1, 0.0, 1.0));
  EXPECT_EQ(fixture.wakes, 1);
  std::map<SourceKey, Delivery> deliveries;
  BoxArrayConstPtr scenery;
  fixture.now = ros::Time(1000, 0);
  mailbox.take(deliveries, scenery);
  EXPECT_FALSE(scenery);
  EXPECT_TRUE(fixture.skips.empty());
  addShift(transforms, "map", "building", 3.0);
  mailbox.take(deliveries, scenery);
  ASSERT_TRUE(scenery);
  EXPECT_EQ(scenery->header.frame_id, "building");
  // An empty scenery (clearing it) needs no transform.
  auto clear = boost::make_shared<BoxArray>();
  clear->header.frame_id = "elsewhere";
  mailbox.postScenery(clear);
  scenery.reset();
  mailbox.take(deliveries, scenery);
  EXPECT_EQ(scenery, clear);
}

TEST(SourceMailbox, RemembersTheLastConvertedHeader) {
  const SourcePlacement placement("", nullptr);
  MailboxFixture fixture;
  SourceMailbox mailbox(
      placement, 2.0, [&] { return fixture.now; }, fixture, [] {});
  std_msgs::Header header;
  header.frame_id = "robot_a";
  header.stamp = ros::Time(4, 0);
  mailbox.noteConverted(header);
  EXPECT_EQ(mailbox.lastConverted().frame_id, "robot_a");
  EXPECT_EQ(mailbox.lastConverted().stamp, ros::Time(4, 0));
}

// ---- loadWorld: the refusal and fall-back loop ----

/// Sources, an engine and the world the worker assembles from them; the refusals told by the
/// last load, in order.
class LoadWorld : public testing::Test {
 protected:
  /// Assembles the world from the sources and loads it into the engine as the worker does.
  const PairList* assembleAndLoad() {
    sources.assemble("", world);
    updates = 0;
    return loadWorld(
        world, sources, spans,
        [&](const BoxFrame& inFrame) -> const PairList& {
          ++updates;
          return engine.update(inFrame);
        },
        [&](const SourceFrame& inFrame, const std::string& inReason) {
          refused.push_back(inFrame.header.frame_id + " | " + inReason);
        });
  }

  SourceSet sources;
  Broadphase engine;
  WorldAssembly world;
  std::vector<BoxSpan> spans;
  std::vector<std::string> refused;
  int updates = 0;
};

TEST_F(LoadWorld, ARefusedFrameFallsBackOnTheLastAcceptedOne) {
  const SourceKey a{"boxes", "/a", "world"}, b{"boxes", "/b", "world"};
  sources.store(a, frameOf(oneBoxMessage("world", 1, 0.0, 1.0)), ros::Time(1, 0));
  sources.store(b, frameOf(oneBoxMessage("world", 2, 0.5, 1.5)), ros::Time(1, 0));
  const PairList* pairs = assembleAndLoad();
  ASSERT_NE(pairs, nullptr);
  EXPECT_EQ(*pairs, PairList({{1, 2}}));
  EXPECT_TRUE(refused.empty());
  for (const WorldMember& member : world.members) sources.accept(member.key);
  // /b's next frame has min > max: refused naming /b's own box, /b falls back on [0.5, 1.5].
  sources.store(b, frameOf(oneBoxMessage("world", 2, 3.0, 2.0)), ros::Time(2, 0));
  pairs = assembleAndLoad();
  ASSERT_NE(pairs, nullptr);
  EXPECT_EQ(*pairs, PairList({{1, 2}})) << "answered on /b's last accepted frame";
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_NE(refused[0].find("'boxes' from /b"), std::string::npos) << refused[0];
  EXPECT_NE(refused[0].find("box 0"), std::string::npos) << refused[0];
  EXPECT_EQ(updates, 2);
  EXPECT_EQ(world.members.size(), 2u);
}

TEST_F(LoadWorld, ASourceWithoutAnAcceptedFrameLeavesTheWorld) {
  const SourceKey a{"boxes", "/a", "world"}, b{"boxes", "/b", "world"};
  sources.store(a, frameOf(oneBoxMessage("world", 1, 0.0, 1.0)), ros::Time(1, 0));
  // /b shares /a's id 1 on its first frame: the newer source is refused and leaves.
  sources.store(b, frameOf(oneBoxMessage("world", 1, 0.5, 1.5)), ros::Time(1, 0));
  const PairList* pairs = assembleAndLoad();
  ASSERT_NE(pairs, nullptr);
  EXPECT_TRUE(pairs->empty());
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_NE(refused[0].find("id 1 of 'boxes' from /b in 'world' is also in 'boxes' from /a"),
            std::string::npos)
      << refused[0];
  ASSERT_EQ(world.members.size(), 1u);
  EXPECT_EQ(world.members[0].key.publisher, "/a");
  EXPECT_EQ(sources.size(), 1u);
}

TEST_F(LoadWorld, NoSourceLeftGivesNoPairs) {
  const SourceKey a{"boxes", "/a", "world"};
  sources.store(a, frameOf(oneBoxMessage("world", 1, 2.0, 1.0)), ros::Time(1, 0));
  EXPECT_EQ(assembleAndLoad(), nullptr);
  EXPECT_EQ(refused.size(), 1u);
  EXPECT_TRUE(world.members.empty());
  EXPECT_EQ(sources.size(), 0u);
}

// ---- WorldSnapshot: what queries read ----

TEST(WorldSnapshot, AnswersAsTheEngineWouldOnItsFrameAndTheScenery) {
  const auto a = frameOf(oneBoxMessage("world", 1, 0.0, 1.0));
  const auto b = frameOf(oneBoxMessage("world", 2, 0.5, 1.5));
  const auto scenery = frameOf(oneBoxMessage("world", 9, 1.2, 3.0));
  const BroadphaseConfig config;
  std_msgs::Header header;
  header.frame_id = "world";
  header.stamp = ros::Time(7, 0);
  const WorldSnapshot world(header, {a, b}, std::make_shared<SceneryIndex>(scenery, config),
                            config);
  BoxSet queries;
  const double lo0[3] = {0.9, 0.9, 0.9}, hi0[3] = {1.3, 1.3, 1.3};
  const double lo1[3] = {5.0, 5.0, 5.0}, hi1[3] = {6.0, 6.0, 6.0};
  queries.add(0, lo0, hi0);
  queries.add(1, lo1, hi1);
  const std::vector<BoxSpan> spans = {a->span(), b->span(), scenery->span()};
  EXPECT_EQ(world.query(queries), bruteForceQuery(queries, BoxFrame(spans)));
  EXPECT_EQ(world.query(queries), QueryHitList({{0, 1}, {0, 2}, {0, 9}}));
  EXPECT_EQ(world.header().stamp, ros::Time(7, 0));
  // The scenery alone, and a bad query box refused naming it.
  const WorldSnapshot empty(header, {}, std::make_shared<SceneryIndex>(nullptr, config), config);
  EXPECT_TRUE(empty.query(queries).empty());
  BoxSet bad;
  const double lo_bad[3] = {2.0, 0.0, 0.0}, hi_bad[3] = {1.0, 1.0, 1.0};
  bad.add(4, lo_bad, hi_bad);
  EXPECT_THROW(empty.query(bad), InvalidBoxes);
  EXPECT_THROW(world.query(bad), InvalidBoxes);
}

}  // namespace
}  // namespace test
}  // namespace sap_broadphase
