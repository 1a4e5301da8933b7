// rostest of the nodelets: ScenePublisherNodelet and BroadphaseNodelet in one manager
// (nodelet.test). The boxes pass from one to the other inside the manager; this test, in its
// own process, listens to both topics and checks every answered frame against the oracle.
// Never asserts on wall-clock speed; timeouts only bound waiting.
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <string>

#include <gtest/gtest.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include "message_read_back.h"
#include "ros_test_support.h"
#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/PairArray.h"
#include "sap_broadphase/core/brute_force.h"
#include "test_frames.h"

namespace sap_broadphase {
namespace test {
namespace {

constexpr double kWait = 60.0;  // seconds; only a bound on waiting, never an assertion on speed
constexpr std::size_t kFrames = 5;
const char* const kManager = "/sap_broadphase_manager";

/// Boxes and pairs as the manager publishes them, by stamp.
class TopicListener {
 public:
  TopicListener() {
    boxes_sub_ = node_.subscribe<BoxArray>("boxes", 10, [this](const BoxArrayConstPtr& inMsg) {
      std::lock_guard<std::mutex> lock(mutex_);
      boxes_[inMsg->header.stamp] = inMsg;
      changed_.notify_all();
    });
    pairs_sub_ = node_.subscribe<PairArray>("pairs", 10, [this](const PairArrayConstPtr& inMsg) {
      std::lock_guard<std::mutex> lock(mutex_);
      pairs_[inMsg->header.stamp] = inMsg;
      changed_.notify_all();
    });
  }

  /// Waits for inCount frames whose boxes and pairs both arrived; they go to outFrames.
  bool waitAnswered(
      std::size_t inCount,
      std::map<ros::Time, std::pair<BoxArrayConstPtr, PairArrayConstPtr>>& outFrames) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, std::chrono::duration<double>(kWait), [&] {
      outFrames.clear();
      for (const auto& [stamp, pairs] : pairs_) {
        auto boxes = boxes_.find(stamp);
        if (boxes != boxes_.end()) outFrames[stamp] = {boxes->second, pairs};
      }
      return outFrames.size() >= inCount;
    });
  }

 private:
  ros::NodeHandle node_;
  ros::Subscriber boxes_sub_, pairs_sub_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::map<ros::Time, BoxArrayConstPtr> boxes_;
  std::map<ros::Time, PairArrayConstPtr> pairs_;
};

/// The connections of inNode as its getBusInfo reports them: [id, peer, direction, transport,
/// topic, connected, info] each. Empty when the node cannot be asked.
XmlRpc::XmlRpcValue busInfo(const std::string& inNode) {
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  request[1] = inNode;
  if (!ros::master::execute("lookupNode", request, response, payload, false))
    return XmlRpc::XmlRpcValue();
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(payload), host, port))
    return XmlRpc::XmlRpcValue();
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue caller;
  caller[0] = ros::this_node::getName();
  if (!client.execute("getBusInfo", caller, response) || response.size() < 3)
    return XmlRpc::XmlRpcValue();
  return response[2];
}

/// True when inNode sends inTopic to itself without a socket.
bool sendsToItselfInProcess(const std::string& inNode, const std::string& inTopic) {
  XmlRpc::XmlRpcValue connections = busInfo(inNode);
  if (connections.getType() != XmlRpc::XmlRpcValue::TypeArray) return false;
  for (int i = 0; i < connections.size(); ++i) {
    XmlRpc::XmlRpcValue& connection = connections[i];
    if (connection.size() >= 5 && static_cast<std::string>(connection[2]) == "o" &&
        static_cast<std::string>(connection[3]) == "INTRAPROCESS" &&
        static_cast<std::string>(connection[4]) == inTopic)
      return true;
  }
  return false;
}

TEST(NodeletRoundTrip, SceneFramesAnsweredExactly) {
  TopicListener listener;
  std::map<ros::Time, std::pair<BoxArrayConstPtr, PairArrayConstPtr>> frames;
  ASSERT_TRUE(listener.waitAnswered(kFrames, frames))
      << "fewer than " << kFrames << " frames of scene_publisher came back as pairs";
  std::size_t total_pairs = 0;
  for (const auto& [stamp, frame] : frames) {
    const auto& [boxes_msg, pairs_msg] = frame;
    BoxSet boxes;
    ASSERT_FALSE(boxArrayToBoxSet(*boxes_msg, boxes)) << "scene_publisher sent a bad frame";
    EXPECT_EQ(pairs_msg->header.frame_id, boxes_msg->header.frame_id);
    EXPECT_EQ(toPairs(*pairs_msg), bruteForcePairs(boxes)) << "frame stamped " << stamp;
    total_pairs += pairs_msg->pairs.size() / 2;
  }
  // The scene is dense enough to collide: an engine that answered nothing would fail here.
  EXPECT_GT(total_pairs, 0u);
}

TEST(NodeletRoundTrip, BoxesStayInsideTheManager) {
  // Pairs came back, so the broad phase nodelet is subscribed to the publisher nodelet.
  TopicListener listener;
  std::map<ros::Time, std::pair<BoxArrayConstPtr, PairArrayConstPtr>> frames;
  ASSERT_TRUE(listener.waitAnswered(1, frames));
  EXPECT_TRUE(sendsToItselfInProcess(kManager, ros::names::resolve("boxes")))
      << kManager << " does not pass boxes to itself in process";
}

}  // namespace
}  // namespace test
}  // namespace sap_broadphase

int main(int argc, char** argv) {
  return sap_broadphase::test::runRosTests(argc, argv, "test_nodelet", 1);
}
