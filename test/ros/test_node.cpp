// rostest of the node: topic round trips and the service against the oracle, refusals, a
// burst of frames, markers. Never asserts on wall-clock speed; timeouts only bound waiting.
#include <cmath>
#include <limits>
#include <memory>
#include <set>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "node_client.h"
#include "ros_test_support.h"
#include "sap_broadphase/core/brute_force.h"
#include "test_frames.h"

namespace sap_broadphase {
namespace test {
namespace {

constexpr double kWait = 30.0;  // seconds; only a bound on waiting, never an assertion on speed

/// One client per node of node.test, connected once.
NodeClient& client(const std::string& inNamespace) {
  static std::map<std::string, std::unique_ptr<NodeClient>> clients;
  auto& slot = clients[inNamespace];
  if (!slot) {
    slot = std::make_unique<NodeClient>(inNamespace, inNamespace != "burst");
    EXPECT_TRUE(slot->waitConnected(kWait)) << "node in '" << inNamespace << "' not connected";
  }
  return *slot;
}

/// Sends inBoxes on the topic and checks the answer against the oracle and the header.
void expectTopicExact(NodeClient& ioClient, const BoxSet& inBoxes, bool inOmitIds = false) {
  BoxArray msg = toMessage(inBoxes, "test_frame", inOmitIds);
  const auto pairs = ioClient.roundTrip(msg, kWait);
  ASSERT_TRUE(pairs) << "no pairs for a frame of " << inBoxes.size() << " boxes";
  EXPECT_EQ(pairs->header.stamp, msg.header.stamp);
  EXPECT_EQ(pairs->header.frame_id, "test_frame");
  const PairList expected = bruteForcePairs(inBoxes);
  EXPECT_EQ(toPairs(*pairs), expected) << inBoxes.size() << " boxes";
}

TEST(TopicRoundTrip, RandomFramesWithSparseIds) {
  NodeClient& node = client("exact");
  uint32_t seed = 1;
  for (std::size_t count : {0, 1, 2, 60, 700, 3000, 6000, 6000}) {
    expectTopicExact(node, randomBoxes(count, 0.6, true, seed++));
  }
}

TEST(TopicRoundTrip, DefaultIdsWhenIdsAreEmpty) {
  expectTopicExact(client("exact"), randomBoxes(5000, 0.5, false, 11), true);
}

TEST(TopicRoundTrip, TouchingBoxes) {
  expectTopicExact(client("exact"), touchingGrid(6, 1000));  // 216 boxes, sequential path
  expectTopicExact(client("exact"), touchingGrid(17, 5));    // 4913 boxes, parallel path
}

TEST(TopicRoundTrip, IdenticalBoxes) {
  expectTopicExact(client("exact"), identicalBoxes(300, 4000000000u));  // 44850 pairs
}

TEST(TopicRoundTrip, GroupsAndMasksHonoured) {
  BoxSet boxes = randomBoxes(4000, 0.8, true, 21);
  randomFilters(boxes, 3, 22);
  expectTopicExact(client("exact"), boxes);
  // Only groups given: the node fills the default masks.
  BoxSet grouped = randomBoxes(500, 1.0, false, 23);
  randomFilters(grouped, 2, 24);
  BoxArray msg = toMessage(grouped, "test_frame");
  msg.masks.clear();
  grouped.masks.assign(grouped.size(), kDefaultMask);
  const auto pairs = client("exact").roundTrip(msg, kWait);
  ASSERT_TRUE(pairs);
  EXPECT_EQ(toPairs(*pairs), bruteForcePairs(grouped));
}

/// The refusal cases: a message, and a piece of text the reason must contain.
std::vector<std::pair<BoxArray, std::string>> badFrames() {
  const BoxSet boxes = randomBoxes(40, 1.0, true, 31);
  std::vector<std::pair<BoxArray, std::string>> frames;
  BoxArray msg = toMessage(boxes, "bad");
  msg.bounds.push_back(1.0);
  frames.emplace_back(msg, "bounds");
  msg = toMessage(boxes, "bad");
  msg.ids.pop_back();
  frames.emplace_back(msg, "ids");
  msg = toMessage(boxes, "bad");
  msg.groups.assign(39, 1u);
  frames.emplace_back(msg, "groups");
  msg = toMessage(boxes, "bad");
  msg.masks.assign(41, 1u);
  frames.emplace_back(msg, "masks");
  msg = toMessage(boxes, "bad");
  msg.bounds[6 * 17 + 4] = std::numeric_limits<double>::quiet_NaN();
  frames.emplace_back(msg, "id " + std::to_string(msg.ids[17]));
  msg = toMessage(boxes, "bad");
  msg.bounds[6 * 23 + 2] = msg.bounds[6 * 23 + 5] + 1.0;  // min_z > max_z
  frames.emplace_back(msg, "id " + std::to_string(msg.ids[23]));
  msg = toMessage(boxes, "bad");
  msg.ids[30] = msg.ids[3];
  frames.emplace_back(msg, std::to_string(msg.ids[3]));
  return frames;
}

TEST(Service, ValidFramesExact) {
  NodeClient& node = client("exact");
  uint32_t seed = 41;
  for (std::size_t count : {0, 3, 900, 5000}) {
    const BoxSet boxes = randomBoxes(count, 0.7, true, seed++);
    BoxArray msg = toMessage(boxes, "service_frame");
    msg.header.stamp = ros::Time(77, 7);
    const auto response = node.call(msg);
    ASSERT_TRUE(response);
    EXPECT_TRUE(response->success) << response->message;
    EXPECT_EQ(response->pairs.header.stamp, msg.header.stamp);
    EXPECT_EQ(response->pairs.header.frame_id, "service_frame");
    // The frame answered on: the request's own.
    EXPECT_EQ(response->header.stamp, msg.header.stamp);
    EXPECT_EQ(response->header.frame_id, "service_frame");
    EXPECT_EQ(toPairs(response->pairs), bruteForcePairs(boxes));
  }
}

TEST(Service, EveryRefusalAnsweredThenStillExact) {
  NodeClient& node = client("exact");
  for (const auto& [msg, needle] : badFrames()) {
    const auto response = node.call(msg);
    ASSERT_TRUE(response);
    EXPECT_FALSE(response->success) << "expected a refusal mentioning " << needle;
    EXPECT_NE(response->message.find(needle), std::string::npos)
        << "'" << response->message << "' should mention '" << needle << "'";
    EXPECT_TRUE(response->pairs.pairs.empty());
  }
  const BoxSet boxes = randomBoxes(2000, 0.7, false, 51);
  const auto response = node.call(toMessage(boxes, "after"));
  ASSERT_TRUE(response);
  EXPECT_TRUE(response->success);
  EXPECT_EQ(toPairs(response->pairs), bruteForcePairs(boxes));
}

TEST(TopicRefusal, BadFramesCountedAndNextGoodFrameServed) {
  NodeClient& node = client("exact");
  std::vector<ros::Time> bad_stamps;
  for (auto& [msg, needle] : badFrames()) {
    bad_stamps.push_back(node.publish(msg));
    // One at a time, so latest-wins never drops a bad frame unseen.
    const ros::Time stamp = bad_stamps.back();
    const auto stats = node.waitStats(
        [&](const FrameStats& s) { return s.header.stamp == stamp && s.path == "refused"; }, kWait);
    ASSERT_TRUE(stats) << "no refusal stats for the frame about " << needle;
    EXPECT_NE(stats->last_refusal.find(needle), std::string::npos) << stats->last_refusal;
  }
  const BoxSet boxes = randomBoxes(1500, 0.7, true, 61);
  expectTopicExact(node, boxes);
  for (const ros::Time& stamp : bad_stamps) EXPECT_FALSE(node.sawPairs(stamp));
  const auto stats = node.waitStats(
      [&](const FrameStats& s) { return s.frames_refused >= bad_stamps.size() && s.pairs > 0; },
      kWait);
  ASSERT_TRUE(stats);
  EXPECT_EQ(stats->last_refusal.empty(), false);
}

TEST(Burst, TwoHundredFramesLastOneArrivesEveryFrameAccountedFor) {
  NodeClient& node = client("burst");  // method brute: each frame is slow on purpose
  std::vector<BoxSet> frames;
  for (uint32_t i = 0; i < 4; ++i) frames.push_back(randomBoxes(2500, 0.5, true, 71 + i));
  ros::Time last_stamp;
  for (int i = 0; i < 200; ++i) {
    BoxArray msg = toMessage(frames[i % frames.size()], "burst");
    last_stamp = node.publish(msg);
  }
  // The service keeps answering while the topic frames are being worked off.
  const BoxSet service_boxes = randomBoxes(1000, 0.7, false, 79);
  const auto response = node.call(toMessage(service_boxes, "during_burst"));
  ASSERT_TRUE(response);
  EXPECT_TRUE(response->success);
  EXPECT_EQ(toPairs(response->pairs), bruteForcePairs(service_boxes));

  const auto pairs = node.waitPairs(last_stamp, 120.0);
  ASSERT_TRUE(pairs) << "the last frame of the burst never came back";
  EXPECT_EQ(toPairs(*pairs), bruteForcePairs(frames[199 % frames.size()]));
  const auto stats =
      node.waitStats([&](const FrameStats& s) { return s.header.stamp == last_stamp; }, kWait);
  ASSERT_TRUE(stats);
  EXPECT_EQ(stats->frames_received, 200u);
  EXPECT_EQ(stats->frames_refused, 0u);
  // Each frame was either taken or replaced by a newer one of its source; how many were
  // replaced depends on the machine's speed, so the split is not asserted.
  EXPECT_EQ(stats->frames_processed + stats->frames_dropped, 200u);
}

/// Checks that a LINE_LIST holds exactly the wireframes of the boxes with the given ids.
void expectWireframes(const visualization_msgs::Marker& inMarker, const BoxSet& inBoxes,
                      std::size_t inExpectedBoxes) {
  EXPECT_EQ(inMarker.type, visualization_msgs::Marker::LINE_LIST);
  EXPECT_EQ(inMarker.action, visualization_msgs::Marker::ADD);
  ASSERT_EQ(inMarker.points.size(), 24 * inExpectedBoxes);
  for (std::size_t box = 0; box < inExpectedBoxes; ++box) {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (std::size_t k = 0; k < 24; ++k) {
      const auto& point = inMarker.points[24 * box + k];
      const double xyz[3] = {point.x, point.y, point.z};
      for (int axis = 0; axis < 3; ++axis) {
        lo[axis] = std::min(lo[axis], xyz[axis]);
        hi[axis] = std::max(hi[axis], xyz[axis]);
      }
    }
    bool found = false;  // the 24 points span exactly one of the boxes
    for (std::size_t i = 0; i < inBoxes.size() && !found; ++i) {
      found = true;
      for (int axis = 0; axis < 3; ++axis)
        found = found && lo[axis] == inBoxes.lo(axis, i) && hi[axis] == inBoxes.hi(axis, i);
    }
    EXPECT_TRUE(found) << "wireframe " << box << " matches no box";
  }
}

/// Publishes frames until one comes back with markers (rviz-like subscribers attach lazily).
std::optional<visualization_msgs::MarkerArray> markersFor(NodeClient& ioClient, BoxArray& ioMsg) {
  for (int attempt = 0; attempt < 20; ++attempt) {
    const ros::Time stamp = ioClient.publish(ioMsg);
    if (auto markers = ioClient.waitMarkers(stamp, 2.0)) return markers;
  }
  return std::nullopt;
}

std::size_t collidingBoxCount(const PairList& inPairs) {
  std::set<uint32_t> ids;
  for (const IdPair& pair : inPairs) ids.insert({pair.a, pair.b});
  return ids.size();
}

TEST(Markers, DeleteAllThenOneLineListOf24PointsPerCollidingBox) {
  NodeClient& node = client("exact");
  const BoxSet boxes = randomBoxes(800, 0.8, true, 81);
  BoxArray msg = toMessage(boxes, "marker_frame");
  const auto markers = markersFor(node, msg);
  ASSERT_TRUE(markers);
  ASSERT_GE(markers->markers.size(), 2u);
  EXPECT_EQ(markers->markers[0].action, visualization_msgs::Marker::DELETEALL);
  const auto& colliding = markers->markers[1];
  EXPECT_EQ(colliding.ns, "colliding");
  EXPECT_EQ(colliding.header.frame_id, "marker_frame");
  EXPECT_EQ(colliding.header.stamp, msg.header.stamp);
  const std::size_t expected = collidingBoxCount(bruteForcePairs(boxes));
  ASSERT_GT(expected, 0u);
  expectWireframes(colliding, boxes, expected);
  const auto stats = node.waitStats(
      [&](const FrameStats& s) { return s.header.stamp == msg.header.stamp; }, kWait);
  ASSERT_TRUE(stats);
  EXPECT_EQ(stats->marker_boxes, expected);
  EXPECT_EQ(stats->marker_boxes_omitted, 0u);
}

TEST(Markers, CapHonouredAndReported) {
  NodeClient& node = client("capped");  // ~max_marker_boxes: 5, non-colliding and links shown
  const BoxSet boxes = randomBoxes(800, 0.8, false, 91);
  BoxArray msg = toMessage(boxes, "marker_frame", true);
  const auto markers = markersFor(node, msg);
  ASSERT_TRUE(markers);
  ASSERT_GE(markers->markers.size(), 2u);
  EXPECT_EQ(markers->markers[0].action, visualization_msgs::Marker::DELETEALL);
  expectWireframes(markers->markers[1], boxes, 5);
  for (std::size_t i = 2; i < markers->markers.size(); ++i)
    EXPECT_NE(markers->markers[i].ns, "non_colliding") << "the cap is used up by colliding boxes";
  const std::size_t colliding = collidingBoxCount(bruteForcePairs(boxes));
  const auto stats = node.waitStats(
      [&](const FrameStats& s) { return s.header.stamp == msg.header.stamp; }, kWait);
  ASSERT_TRUE(stats);
  EXPECT_EQ(stats->marker_boxes, 5u);
  EXPECT_EQ(stats->marker_boxes_omitted, colliding - 5);
}

}  // namespace
}  // namespace test
}  // namespace sap_broadphase

int main(int argc, char** argv) {
  return sap_broadphase::test::runRosTests(argc, argv, "test_node", 2);
}
