// rostest of sources.test: several publishers and topics merged into one world, tf2 into a
// fixed frame, the latched static world and pair events. Never asserts on wall-clock speed;
// waits are bounded only to fail instead of hanging.
#include <algorithm>
#include <condition_variable>
#include <functional>
#include <iterator>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include "ros_test_support.h"
#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/FrameStats.h"
#include "sap_broadphase/PairArray.h"
#include "sap_broadphase/PairEvents.h"
#include "sap_broadphase/core/brute_force.h"
#include "sources.h"
#include "test_frames.h"

namespace sap_broadphase {
namespace test {
namespace {

constexpr double kWait = 60.0;  // seconds; a bound on waiting, never an assertion on speed

/// The boxes of the robot nodes of sources.test (box_source.py).
BoxSet robotBoxes() {
  BoxSet boxes;
  const double a_lo[3] = {0, 0, 0}, a_hi[3] = {1, 1, 1};
  const double b_lo[3] = {0.5, 0.5, 0.5}, b_hi[3] = {1.5, 1.5, 1.5};
  boxes.add(1, a_lo, a_hi);
  boxes.add(2, b_lo, b_hi);
  return boxes;
}

/// inBoxes with every id moved up by inOffset (a source's own id range).
BoxSet withIdOffset(BoxSet inBoxes, uint32_t inOffset) {
  for (uint32_t& id : inBoxes.ids) id += inOffset;
  return inBoxes;
}

/// The union of box sets: the world of the node's sources.
BoxSet unionOf(const std::vector<const BoxSet*>& inParts) {
  BoxSet world;
  for (const BoxSet* part : inParts) {
    for (std::size_t i = 0; i < part->size(); ++i) {
      const double* box = part->bounds.data() + kBoundsPerBox * i;
      world.add(part->ids[i], box, box + 3, part->group(i), part->mask(i));
    }
  }
  return world;
}

/// Pairs of inFrom not in inWithout.
PairList difference(const PairList& inFrom, const PairList& inWithout) {
  PairList out;
  std::set_difference(inFrom.begin(), inFrom.end(), inWithout.begin(), inWithout.end(),
                      std::back_inserter(out));
  return out;
}

PairList flatToPairs(const std::vector<uint32_t>& inFlat) {
  PairList pairs;
  for (std::size_t i = 0; i + 1 < inFlat.size(); i += 2)
    pairs.push_back({inFlat[i], inFlat[i + 1]});
  return pairs;
}

/// One node's outputs as the test sees them, and publishers on its source topics.
class Probe {
 public:
  explicit Probe(const std::string& inNamespace) : node_(inNamespace) {
    pairs_sub_ = node_.subscribe<PairArray>("pairs", 1000, [this](const PairArray::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      pairs_.push_back(*m);
      changed_.notify_all();
    });
    stats_sub_ = node_.subscribe<FrameStats>("stats", 1000, [this](const FrameStats::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      stats_.push_back(*m);
      changed_.notify_all();
    });
    events_sub_ =
        node_.subscribe<PairEvents>("pair_events", 1000, [this](const PairEvents::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          events_[m->header.stamp] = *m;
          changed_.notify_all();
        });
  }

  /// A publisher on inTopic (relative to the namespace), latched or not.
  ros::Publisher& publisher(const std::string& inTopic, bool inLatched = false) {
    ros::Publisher& slot = publishers_[inTopic];
    if (!slot) slot = node_.advertise<BoxArray>(inTopic, 100, inLatched);
    return slot;
  }

  /// Waits until the node listens on every topic in inTopics and publishes to us.
  bool waitConnected(const std::vector<std::string>& inTopics) {
    return pollUntil(kWait, [&] {
      bool ready = pairs_sub_.getNumPublishers() > 0 && stats_sub_.getNumPublishers() > 0 &&
                   events_sub_.getNumPublishers() > 0;
      for (const std::string& topic : inTopics)
        ready = ready && publisher(topic).getNumSubscribers() > 0;
      return ready;
    });
  }

  /// Waits for a pairs message received from now on that satisfies inAccept, calling
  /// inRepublish every half second meanwhile (keeps the test's sources alive, retries frames
  /// that waited for a transform). Returns it, or nothing after kWait.
  std::optional<PairArray> waitPairs(const std::function<bool(const PairArray&)>& inAccept,
                                     const std::function<void()>& inRepublish = {},
                                     bool inFromStart = false) {
    std::size_t seen = 0;
    if (!inFromStart) {
      std::lock_guard<std::mutex> lock(mutex_);
      seen = pairs_.size();
    }
    if (inRepublish) inRepublish();
    return waitReceived(pairs_, seen, inAccept, inRepublish);
  }

  /// Waits for the pairs of the frame stamped inStamp, received at any time (see waitPairs).
  std::optional<PairArray> waitStamped(const ros::Time& inStamp,
                                       const std::function<void()>& inRepublish = {}) {
    return waitPairs([&](const PairArray& m) { return m.header.stamp == inStamp; }, inRepublish,
                     true);
  }

  /// Waits for the pairs of the frame stamped inStamp computed from its source alone: each
  /// frame id is a source of its own, so the source of the last test (in another frame) stays
  /// in the world until it times out. Republishing keeps this source alive meanwhile; once a
  /// frame of this stamp reports one source, every later one does, and the next pairs of this
  /// stamp are its own.
  std::optional<PairArray> waitStampedAlone(const ros::Time& inStamp,
                                            const std::function<void()>& inRepublish) {
    const auto alone = waitStats(
        [&](const FrameStats& s) {
          return s.header.stamp == inStamp && s.sources == 1 && s.path != "refused";
        },
        inRepublish);
    if (!alone) return std::nullopt;
    return waitPairs([&](const PairArray& m) { return m.header.stamp == inStamp; }, inRepublish);
  }

  /// Waits for the pairs equal to inExpected (see waitPairs).
  bool waitPairsEqual(const PairList& inExpected, const std::function<void()>& inRepublish = {}) {
    return waitPairs([&](const PairArray& m) { return toPairs(m) == inExpected; }, inRepublish)
        .has_value();
  }

  /// Pairs messages received after the one accepted last by waitPairs... all of them so far.
  std::vector<PairArray> pairsSince(std::size_t inFirst) {
    std::lock_guard<std::mutex> lock(mutex_);
    return {pairs_.begin() + std::min(inFirst, pairs_.size()), pairs_.end()};
  }
  std::size_t pairsCount() {
    std::lock_guard<std::mutex> lock(mutex_);
    return pairs_.size();
  }

  /// Waits for a stats message satisfying inAccept (see waitPairs for inRepublish).
  std::optional<FrameStats> waitStats(const std::function<bool(const FrameStats&)>& inAccept,
                                      const std::function<void()>& inRepublish = {}) {
    return waitReceived(stats_, 0, inAccept, inRepublish);
  }

  /// Waits for the pair events of the frame stamped inStamp.
  std::optional<PairEvents> waitEvents(const ros::Time& inStamp) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!changed_.wait_for(lock, std::chrono::duration<double>(kWait),
                           [&] { return events_.count(inStamp) > 0; }))
      return std::nullopt;
    return events_.at(inStamp);
  }

 private:
  /// Waits for a message of inReceived (filled by a callback under mutex_), from index inSeen
  /// on, that satisfies inAccept; calls inRepublish every half second meanwhile. Returns it, or
  /// nothing after kWait.
  template <typename Message>
  std::optional<Message> waitReceived(const std::vector<Message>& inReceived, std::size_t inSeen,
                                      const std::function<bool(const Message&)>& inAccept,
                                      const std::function<void()>& inRepublish) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(kWait);
    while (ros::WallTime::now() < end) {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait_for(lock, std::chrono::milliseconds(500),
                        [&] { return inReceived.size() > inSeen; });
      for (; inSeen < inReceived.size(); ++inSeen) {
        if (inAccept(inReceived[inSeen])) return inReceived[inSeen];
      }
      lock.unlock();
      if (inRepublish) inRepublish();
    }
    return std::nullopt;
  }

  ros::NodeHandle node_;
  std::map<std::string, ros::Publisher> publishers_;
  ros::Subscriber pairs_sub_, stats_sub_, events_sub_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<PairArray> pairs_;
  std::vector<FrameStats> stats_;
  std::map<ros::Time, PairEvents> events_;
};

/// Publishes inBoxes on inTopic of inProbe, stamped inStamp (now when zero), in inFrame.
ros::Time publishBoxes(Probe& ioProbe, const std::string& inTopic, const BoxSet& inBoxes,
                       const char* inFrame, ros::Time inStamp = ros::Time()) {
  BoxArray msg = toMessage(inBoxes, inFrame);
  msg.header.stamp = inStamp.isZero() ? ros::Time::now() : inStamp;
  ioProbe.publisher(inTopic).publish(msg);
  return msg.header.stamp;
}

// ---- Sources: two robot nodes and the test on `boxes`, the test on `extra` ----

Probe& multi() {
  static Probe probe("multi");
  return probe;
}

TEST(Sources, TwoRobotNodesOnOneTopicGiveTheCrossSourcePair) {
  ASSERT_TRUE(multi().waitConnected({"boxes", "extra"}));
  // Robot A: id 1, [0,1]^3; robot B: id 2, [0.5,1.5]^3, each from its own node.
  const PairList expected = bruteForcePairs(robotBoxes());
  ASSERT_EQ(expected, PairList({{1, 2}}));
  const auto pairs = multi().waitPairs([&](const PairArray& m) { return toPairs(m) == expected; });
  ASSERT_TRUE(pairs) << "the pair (1, 2) of two publishers never came";
  EXPECT_EQ(pairs->header.frame_id, "world");
}

TEST(Sources, ThreePublishersAndSecondTopicExactAgainstTheUnion) {
  const BoxSet robots = robotBoxes();
  BoxSet mine = withIdOffset(randomBoxes(300, 0.6, false, 101), 1000);  // ids 1000..1299
  const double lo[3] = {1.2, 1.2, 1.2}, hi[3] = {2, 2, 2};
  mine.add(3, lo, hi);  // touches robot B only
  BoxSet extra = withIdOffset(randomBoxes(400, 0.6, false, 102), 2000);
  const PairList expected = bruteForcePairs(unionOf({&robots, &mine, &extra}));
  ASSERT_TRUE(std::count(expected.begin(), expected.end(), IdPair{2, 3}) == 1);
  auto republish = [&] {
    publishBoxes(multi(), "boxes", mine, "world");
    publishBoxes(multi(), "extra", extra, "world");
  };
  EXPECT_TRUE(multi().waitPairsEqual(expected, republish));
  const auto stats = multi().waitStats([](const FrameStats& s) { return s.sources == 4; });
  ASSERT_TRUE(stats) << "robot A, robot B, the test on boxes and on extra";

  // The latest frame of a source replaces its previous one: a new `extra` frame.
  const BoxSet newer_extra = withIdOffset(randomBoxes(400, 0.6, false, 103), 2000);
  const PairList newer_expected = bruteForcePairs(unionOf({&robots, &mine, &newer_extra}));
  ASSERT_NE(newer_expected, expected);
  auto republish_newer = [&] {
    publishBoxes(multi(), "boxes", mine, "world");
    publishBoxes(multi(), "extra", newer_extra, "world");
  };
  EXPECT_TRUE(multi().waitPairsEqual(newer_expected, republish_newer));
  const std::size_t first_after = multi().pairsCount();
  republish_newer();  // robots keep publishing: several frames are computed meanwhile
  EXPECT_TRUE(multi().waitPairsEqual(newer_expected, republish_newer));
  for (const PairArray& later : multi().pairsSince(first_after))
    EXPECT_EQ(toPairs(later), newer_expected) << "an older frame of `extra` came back";
}

TEST(Sources, DuplicateIdAcrossSourcesRefusedNamingBoth) {
  const BoxSet robots = robotBoxes();
  BoxSet clash = withIdOffset(randomBoxes(50, 0.6, false, 104), 3000);
  const double lo[3] = {0, 0, 0}, hi[3] = {2, 2, 2};
  clash.add(1, lo, hi);  // robot A's id
  auto republish = [&] { publishBoxes(multi(), "extra", clash, "world"); };
  const auto stats = multi().waitStats(
      [](const FrameStats& s) {
        return s.last_refusal.find("id 1 of 'extra' from /") != std::string::npos;
      },
      republish);
  ASSERT_TRUE(stats) << "no refusal naming the id and the test's source";
  EXPECT_NE(stats->last_refusal.find("'boxes' from /multi/robot_a"), std::string::npos)
      << stats->last_refusal;
  // The other sources are still computed; the clashing frame is left out. The test's frame on
  // `boxes` may still be live: the expected world is the robots plus, maybe, that frame.
  EXPECT_TRUE(multi()
                  .waitPairs([&](const PairArray& m) {
                    const PairList pairs = toPairs(m);
                    return std::count(pairs.begin(), pairs.end(), IdPair{1, 2}) == 1 &&
                           std::none_of(pairs.begin(), pairs.end(),
                                        [](const IdPair& p) { return p.b >= 3000 && p.b < 4000; });
                  })
                  .has_value());
}

TEST(Sources, RefusedFrameLeavesTheSourcesLastAcceptedOne) {
  BoxSet good;
  const double lo[3] = {0.2, 0.2, 0.2}, hi[3] = {0.8, 0.8, 0.8};
  good.add(3500, lo, hi);  // overlaps robot A's box
  const auto holds = [](const PairArray& inPairs, IdPair inPair) {
    const PairList pairs = toPairs(inPairs);
    return std::count(pairs.begin(), pairs.end(), inPair) == 1;
  };
  auto republish = [&] { publishBoxes(multi(), "extra", good, "world"); };
  ASSERT_TRUE(multi()
                  .waitPairs(
                      [&](const PairArray& m) {
                        return holds(m, IdPair{1, 3500});
                      },
                      republish)
                  .has_value());
  // The next frame of `extra` has min_x > max_x: refused, named, and `extra` stays in the world
  // with its last accepted frame while the robots' frames keep coming.
  BoxSet bad = good;
  bad.lo(0, 0) = 3.0;
  bad.hi(0, 0) = 2.0;
  const ros::Time bad_stamp = publishBoxes(multi(), "extra", bad, "world");
  const auto stats = multi().waitStats(
      [&](const FrameStats& s) { return s.header.stamp == bad_stamp && s.path == "refused"; });
  ASSERT_TRUE(stats) << "no refusal of the bad frame";
  EXPECT_NE(stats->last_refusal.find("'extra' from /"), std::string::npos) << stats->last_refusal;
  EXPECT_NE(stats->last_refusal.find("box 0 (id 3500): min_x (3) > max_x (2)"), std::string::npos)
      << stats->last_refusal;
  EXPECT_TRUE(multi()
                  .waitPairs([&](const PairArray& m) {
                    return m.header.stamp > bad_stamp && holds(m, IdPair{1, 2}) &&
                           holds(m, IdPair{1, 3500});
                  })
                  .has_value())
      << "the robots' frames after the refusal lost the last accepted frame of `extra`";
}

TEST(Sources, SilentSourcesTimeOut) {
  // The test stops publishing: its two sources time out (~source_timeout 3 s), the robots stay.
  const auto stats =
      multi().waitStats([](const FrameStats& s) { return s.sources_timed_out >= 2; });
  ASSERT_TRUE(stats) << "the test's sources never timed out";
  EXPECT_TRUE(multi().waitPairsEqual(bruteForcePairs(robotBoxes())));
  const auto later = multi().waitStats([](const FrameStats& s) { return s.sources == 2; });
  EXPECT_TRUE(later);
}

// ---- tf2: sources transformed into `map` ----

Probe& tfProbe() {
  static Probe probe("tf");
  return probe;
}

tf2_ros::Buffer& tfBuffer() {
  static tf2_ros::Buffer buffer;
  static tf2_ros::TransformListener listener(buffer);
  return buffer;
}

/// The boxes moved into `map` as the node must: the test's own tf2 lookup of the same data.
BoxSet inMap(const BoxSet& inBoxes, const std::string& inFrame, const ros::Time& inStamp) {
  const auto transform = tfBuffer().lookupTransform("map", inFrame, inStamp, ros::Duration(kWait));
  BoxSet moved = inBoxes;
  transformBoxes(transform.transform, moved);
  return moved;
}

TEST(Frames, StaticTranslationIntoTheFixedFrame) {
  ASSERT_TRUE(tfProbe().waitConnected({"boxes"}));
  const BoxSet boxes = randomBoxes(500, 0.8, true, 201);
  const ros::Time stamp = ros::Time::now();
  const BoxSet moved = inMap(boxes, "robot_a", stamp);
  EXPECT_NEAR(moved.lo(0, 0), boxes.lo(0, 0) + 10.0, 1e-12);
  const auto pairs = tfProbe().waitStampedAlone(
      stamp, [&] { publishBoxes(tfProbe(), "boxes", boxes, "robot_a", stamp); });
  ASSERT_TRUE(pairs);
  EXPECT_EQ(pairs->header.frame_id, "map");
  EXPECT_EQ(toPairs(*pairs), bruteForcePairs(moved));
  EXPECT_TRUE(difference(bruteForcePairs(boxes), toPairs(*pairs)).empty())
      << "a translation keeps every pair";
}

TEST(Frames, RotatedBoxesSupersetOfExactAndEqualToTheirAabbs) {
  const BoxSet boxes = randomBoxes(800, 0.8, false, 202);
  const ros::Time stamp = ros::Time::now();
  const BoxSet moved = inMap(boxes, "rotated", stamp);
  const auto pairs = tfProbe().waitStampedAlone(
      stamp, [&] { publishBoxes(tfProbe(), "boxes", boxes, "rotated", stamp); });
  ASSERT_TRUE(pairs);
  const PairList found = toPairs(*pairs);
  EXPECT_EQ(found, bruteForcePairs(moved)) << "the oracle on the transformed AABBs";
  // A rotation is rigid: boxes of one frame overlap after it exactly when they did before, so
  // the exact rotated-box pairs are those of the untransformed boxes.
  const PairList exact = bruteForcePairs(boxes);
  EXPECT_TRUE(difference(exact, found).empty()) << "a pair lost to the rotation";
  EXPECT_GT(found.size(), exact.size()) << "the rotated AABBs are larger: more pairs expected";
}

TEST(Frames, MovingTransformInterpolatedAtTheStamp) {
  static tf2_ros::TransformBroadcaster broadcaster;
  const ros::Time start = ros::Time::now();
  auto send = [&](const ros::Time& inStamp, double inX) {
    geometry_msgs::TransformStamped transform;
    transform.header.stamp = inStamp;
    transform.header.frame_id = "map";
    transform.child_frame_id = "robot_b";
    transform.transform.translation.x = inX;
    transform.transform.rotation.w = 1.0;
    broadcaster.sendTransform(transform);
  };
  const ros::Time middle = start + ros::Duration(0.5);
  const BoxSet boxes = randomBoxes(300, 0.8, true, 203);
  auto republish = [&] {
    send(start, 0.0);
    send(start + ros::Duration(1.0), 4.0);
    publishBoxes(tfProbe(), "boxes", boxes, "robot_b", middle);
  };
  republish();
  const BoxSet moved = inMap(boxes, "robot_b", middle);
  EXPECT_NEAR(moved.lo(0, 0), boxes.lo(0, 0) + 2.0, 1e-12) << "halfway between x = 0 and x = 4";
  const auto pairs = tfProbe().waitStampedAlone(middle, republish);
  ASSERT_TRUE(pairs);
  EXPECT_EQ(toPairs(*pairs), bruteForcePairs(moved));
}

TEST(Frames, MissingTransformSkippedCountedAndNodeStaysUp) {
  const BoxSet boxes = randomBoxes(100, 0.8, false, 204);
  const auto stats =
      tfProbe().waitStats([](const FrameStats& s) { return s.frames_skipped >= 1; },
                          [&] { publishBoxes(tfProbe(), "boxes", boxes, "nowhere"); });
  ASSERT_TRUE(stats) << "a frame without a transform was not counted as skipped";
  const ros::Time stamp = ros::Time::now();
  const auto pairs = tfProbe().waitStampedAlone(
      stamp, [&] { publishBoxes(tfProbe(), "boxes", boxes, "robot_a", stamp); });
  ASSERT_TRUE(pairs) << "the node stopped answering after a skipped frame";
  EXPECT_EQ(toPairs(*pairs), bruteForcePairs(inMap(boxes, "robot_a", stamp)));
}

// ---- The static world and pair events ----

Probe& staticProbe() {
  static Probe probe("static");
  return probe;
}

constexpr uint32_t kMovingIds = 1000000;  // moving boxes use ids from here, scenery below

/// What the node must report: pairs of the union, except scenery x scenery.
PairList movingPairs(const BoxSet& inScenery, const BoxSet& inMoving) {
  PairList expected;
  for (const IdPair& pair : bruteForcePairs(unionOf({&inScenery, &inMoving})))
    if (pair.b >= kMovingIds) expected.push_back(pair);  // a < b: b moving when either is
  return expected;
}

/// Publishes the scenery latched, then moving frames until the node answers them with it.
void expectWithScenery(const BoxSet& inScenery, const BoxSet& inMoving) {
  Probe& probe = staticProbe();
  BoxArray scenery = toMessage(inScenery, "world");
  probe.publisher("static_boxes", true).publish(scenery);
  const PairList expected = movingPairs(inScenery, inMoving);
  ASSERT_FALSE(expected.empty());
  ASSERT_NE(expected, bruteForcePairs(inMoving)) << "the scenery must make a difference";
  const auto stats = probe.waitStats(
      [&](const FrameStats& s) {
        return s.static_world_boxes == inScenery.size() && s.path != "refused";
      },
      [&] { publishBoxes(probe, "boxes", inMoving, "world"); });
  ASSERT_TRUE(stats) << "the scenery of " << inScenery.size() << " boxes never took effect";
  const ros::Time stamp = publishBoxes(probe, "boxes", inMoving, "world");
  const auto pairs = probe.waitStamped(stamp);
  ASSERT_TRUE(pairs);
  EXPECT_EQ(toPairs(*pairs), expected);
}

TEST(StaticWorld, LatchedSceneryThenMovingFrames) {
  Probe& probe = staticProbe();
  probe.publisher("static_boxes", true);
  ASSERT_TRUE(probe.waitConnected({"boxes", "static_boxes"}));
  const BoxSet scenery = randomBoxes(3000, 0.8, false, 301);
  expectWithScenery(scenery, withIdOffset(randomBoxes(400, 0.8, false, 302), kMovingIds));
  for (uint32_t seed = 303; seed < 306; ++seed) {
    const BoxSet moving = withIdOffset(randomBoxes(400, 0.8, false, seed), kMovingIds);
    const ros::Time stamp = publishBoxes(probe, "boxes", moving, "world");
    const auto pairs = probe.waitStamped(stamp);
    ASSERT_TRUE(pairs);
    EXPECT_EQ(toPairs(*pairs), movingPairs(scenery, moving));
  }
}

TEST(StaticWorld, ReplacingTheScenery) {
  const BoxSet scenery = randomBoxes(1500, 1.0, false, 311);
  expectWithScenery(scenery, withIdOffset(randomBoxes(400, 0.8, false, 312), kMovingIds));
}

TEST(StaticWorld, MovingIdOfTheSceneryRefused) {
  Probe& probe = staticProbe();
  BoxSet moving = withIdOffset(randomBoxes(20, 0.8, false, 321), kMovingIds);
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  moving.add(7, lo, hi);  // id 7 belongs to the scenery
  publishBoxes(probe, "boxes", moving, "world");
  const auto stats = probe.waitStats([](const FrameStats& s) {
    return s.path == "refused" && s.last_refusal.find("id 7 of 'boxes'") != std::string::npos &&
           s.last_refusal.find("'static_boxes'") != std::string::npos;
  });
  EXPECT_TRUE(stats) << "no refusal naming the id and static_boxes";
}

TEST(PairEventsTopic, SetDifferenceOfConsecutiveFrames) {
  Probe& probe = staticProbe();
  const BoxSet scenery = randomBoxes(1500, 1.0, false, 311);  // as left by ReplacingTheScenery
  BoxSet moving = withIdOffset(randomBoxes(500, 0.8, false, 331), kMovingIds);
  PairList previous;
  for (int frame = 0; frame < 6; ++frame) {
    const ros::Time stamp = publishBoxes(probe, "boxes", moving, "world");
    const auto pairs = probe.waitStamped(stamp);
    ASSERT_TRUE(pairs);
    const PairList current = toPairs(*pairs);
    EXPECT_EQ(current, movingPairs(scenery, moving));
    const auto events = probe.waitEvents(stamp);
    ASSERT_TRUE(events) << "no pair_events for frame " << frame;
    if (frame > 0) {  // frame 0 follows the last frame of an earlier test: checked from 1 on
      EXPECT_EQ(flatToPairs(events->began), difference(current, previous)) << "frame " << frame;
      EXPECT_EQ(flatToPairs(events->ended), difference(previous, current)) << "frame " << frame;
      EXPECT_FALSE(events->began.empty() && events->ended.empty()) << "the boxes moved";
    }
    previous = current;
    for (std::size_t i = 0; i < moving.size(); ++i) {  // everything drifts along +x
      moving.lo(0, i) += 0.05 * (i % 7);
      moving.hi(0, i) += 0.05 * (i % 7);
    }
  }
}

// ---- ~rate: frames at a fixed rate from what the sources hold ----

// Every source of the `tf` node drops out (~source_timeout 1 s): the node empties its world
// without publishing a frame, yet the next frame's events are still what changed since the
// last frame published, not every pair begun again.
TEST(PairEventsTopic, AfterEverySourceDroppedOutTheLastPublishedFrameIsTheReference) {
  Probe& probe = tfProbe();
  ros::NodeHandle node;
  std::mutex mutex;
  std::condition_variable changed;
  std::string timed_out;  // the tf node's "sources timed out", as /diagnostics last said
  ros::Subscriber diagnostics = node.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& inMsg) {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& status : inMsg->status) {
          if (status.name != "tf/sap_broadphase: broadphase") continue;
          for (const auto& pair : status.values)
            if (pair.key == "sources timed out") timed_out = pair.value;
        }
        changed.notify_all();
      });
  BoxSet boxes = randomBoxes(500, 0.8, false, 341);
  const ros::Time first_stamp = ros::Time::now();
  const auto republish = [&] { publishBoxes(probe, "boxes", boxes, "map", first_stamp); };
  const auto first_stats = probe.waitStats(
      [&](const FrameStats& s) {
        return s.header.stamp == first_stamp && s.sources == 1 && s.path != "refused";
      },
      republish);
  ASSERT_TRUE(first_stats) << "the first frame was never computed alone";
  const auto first = probe.waitStamped(first_stamp);
  ASSERT_TRUE(first);
  const PairList before = toPairs(*first);
  const uint64_t dropped_out = first_stats->sources_timed_out + 1;
  {
    std::unique_lock<std::mutex> lock(mutex);
    ASSERT_TRUE(changed.wait_for(
        lock, std::chrono::duration<double>(kWait),
        [&] { return !timed_out.empty() && std::stoull(timed_out) >= dropped_out; }))
        << "the source never timed out: " << timed_out;
  }
  for (std::size_t i = 0; i < boxes.size(); i += 3) {  // a third of the boxes drift along +x
    boxes.lo(0, i) += 0.3;
    boxes.hi(0, i) += 0.3;
  }
  const ros::Time stamp = publishBoxes(probe, "boxes", boxes, "map");
  const auto pairs = probe.waitStamped(stamp);
  ASSERT_TRUE(pairs);
  const PairList after = toPairs(*pairs);
  ASSERT_FALSE(difference(after, difference(after, before)).empty()) << "no pair lasted";
  const auto events = probe.waitEvents(stamp);
  ASSERT_TRUE(events);
  EXPECT_EQ(flatToPairs(events->began), difference(after, before));
  EXPECT_EQ(flatToPairs(events->ended), difference(before, after));
}

TEST(MarkersWithScenery, SubscribedWhileMovingBoxesOverlapTheScenery) {
  // rviz (any subscriber to `markers`) while the engine pairs moving boxes with scenery boxes,
  // whose ids the world of moving boxes does not hold.
  Probe& probe = staticProbe();
  std::mutex mutex;
  std::condition_variable arrived;
  std::vector<visualization_msgs::MarkerArray> markers;
  ros::NodeHandle node("static");
  ros::Subscriber markers_sub = node.subscribe<visualization_msgs::MarkerArray>(
      "markers", 100, [&](const visualization_msgs::MarkerArray::ConstPtr& inMsg) {
        std::lock_guard<std::mutex> lock(mutex);
        markers.push_back(*inMsg);
        arrived.notify_all();
      });
  ASSERT_TRUE(pollUntil(kWait, [&] { return markers_sub.getNumPublishers() > 0; }))
      << "the static node publishes no markers to the test";
  const BoxSet scenery = randomBoxes(1500, 1.0, false, 311);  // as the tests above left it
  const BoxSet moving = withIdOffset(randomBoxes(100, 1.0, false, 332), kMovingIds);
  expectWithScenery(scenery, moving);
  // The node lives on: the next frame is answered, and its markers drew colliding boxes.
  const ros::Time stamp = publishBoxes(probe, "boxes", moving, "world");
  ASSERT_TRUE(probe.waitStamped(stamp));
  std::unique_lock<std::mutex> lock(mutex);
  const bool drawn = arrived.wait_for(lock, std::chrono::duration<double>(kWait), [&] {
    for (const auto& array : markers)
      for (const auto& marker : array.markers)
        if (marker.ns == "colliding" && !marker.points.empty()) return true;
    return false;
  });
  EXPECT_TRUE(drawn) << "no markers with colliding boxes";
}

TEST(FixedRate, OneDeliveryComputedAgainAtEachTick) {
  static Probe probe("rated");
  ASSERT_TRUE(probe.waitConnected({"boxes"}));
  const BoxSet boxes = randomBoxes(200, 1.0, false, 401);
  const ros::Time stamp = publishBoxes(probe, "boxes", boxes, "world");
  int answers = 0;  // the one frame, recomputed at 20 Hz while nothing new arrives
  const auto third = probe.waitPairs(
      [&](const PairArray& m) {
        if (m.header.stamp != stamp) return false;
        EXPECT_EQ(toPairs(m), bruteForcePairs(boxes));
        return ++answers == 3;
      },
      {}, true);
  ASSERT_TRUE(third) << answers << " frames at ~rate from one delivery";
  const auto stats = probe.waitStats([&](const FrameStats& s) {
    return s.header.stamp == stamp && s.frames_computed >= 3 && s.frames_processed == 1;
  });
  EXPECT_TRUE(stats);
}

// ---- /diagnostics ----

TEST(Diagnostics, EachNodeReportsItsCounters) {
  ros::NodeHandle node;
  std::mutex mutex;
  std::condition_variable changed;
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> latest;  // by status name
  ros::Subscriber subscriber = node.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& inMsg) {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& status : inMsg->status) latest[status.name] = status;
        changed.notify_all();
      });
  auto value = [](const diagnostic_msgs::DiagnosticStatus& inStatus, const std::string& inKey) {
    for (const auto& pair : inStatus.values)
      if (pair.key == inKey) return pair.value;
    return std::string();
  };
  std::unique_lock<std::mutex> lock(mutex);
  const bool reported = changed.wait_for(lock, std::chrono::duration<double>(kWait), [&] {
    const auto statics = latest.find("static/sap_broadphase: broadphase");
    const auto multis = latest.find("multi/sap_broadphase: broadphase");
    return statics != latest.end() && multis != latest.end() &&
           value(statics->second, "frames computed") != "0" &&
           value(multis->second, "sources timed out") != "0";
  });
  ASSERT_TRUE(reported) << latest.size() << " statuses seen";
  EXPECT_EQ(value(latest["static/sap_broadphase: broadphase"], "static boxes"), "1500");
  EXPECT_NE(value(latest["multi/sap_broadphase: broadphase"], "last error"), "");
}

}  // namespace
}  // namespace test
}  // namespace sap_broadphase

int main(int argc, char** argv) {
  return sap_broadphase::test::runRosTests(argc, argv, "test_sources", 2);
}
