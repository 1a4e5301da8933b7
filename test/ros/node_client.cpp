// A test-side client of one BroadphaseNode.
#include "node_client.h"

#include "ros_test_support.h"

namespace sap_broadphase {
namespace test {

NodeClient::NodeClient(const std::string& inNamespace, bool inWantMarkers) : node_(inNamespace) {
  boxes_pub_ = node_.advertise<BoxArray>("boxes", 1000);
  pairs_sub_ = node_.subscribe<PairArray>("pairs", 1000, [this](const PairArray::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    pairs_[msg->header.stamp] = *msg;
    changed_.notify_all();
  });
  stats_sub_ = node_.subscribe<FrameStats>("stats", 1000, [this](const FrameStats::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    stats_.push_back(*msg);
    changed_.notify_all();
  });
  if (inWantMarkers) {
    markers_sub_ = node_.subscribe<visualization_msgs::MarkerArray>(
        "markers", 100, [this](const visualization_msgs::MarkerArray::ConstPtr& msg) {
          if (msg->markers.empty()) return;
          std::lock_guard<std::mutex> lock(mutex_);
          markers_[msg->markers.front().header.stamp] = *msg;
          changed_.notify_all();
        });
  }
  service_ = node_.serviceClient<ComputePairs>("compute_pairs");
}

template <typename Predicate>
bool NodeClient::waitFor(double inSeconds, Predicate inReady,
                         std::unique_lock<std::mutex>& ioLock) {
  return changed_.wait_for(ioLock, std::chrono::duration<double>(inSeconds), inReady);
}

bool NodeClient::waitConnected(double inSeconds) {
  return pollUntil(inSeconds, [this] {
    const bool markers_ok = !markers_sub_ || markers_sub_.getNumPublishers() > 0;
    return boxes_pub_.getNumSubscribers() > 0 && pairs_sub_.getNumPublishers() > 0 &&
           stats_sub_.getNumPublishers() > 0 && markers_ok &&
           service_.waitForExistence(ros::Duration(0.1));
  });
}

ros::Time NodeClient::publish(BoxArray& ioBoxes) {
  ioBoxes.header.stamp = ros::Time(next_stamp_++, 500);
  boxes_pub_.publish(ioBoxes);
  return ioBoxes.header.stamp;
}

std::optional<PairArray> NodeClient::roundTrip(BoxArray& ioBoxes, double inSeconds) {
  return waitPairs(publish(ioBoxes), inSeconds);
}

std::optional<PairArray> NodeClient::waitPairs(const ros::Time& inStamp, double inSeconds) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!waitFor(
          inSeconds, [&] { return pairs_.count(inStamp) > 0; }, lock))
    return std::nullopt;
  return pairs_.at(inStamp);
}

bool NodeClient::sawPairs(const ros::Time& inStamp) {
  std::lock_guard<std::mutex> lock(mutex_);
  return pairs_.count(inStamp) > 0;
}

std::optional<FrameStats> NodeClient::waitStats(
    const std::function<bool(const FrameStats&)>& inAccept, double inSeconds) {
  std::unique_lock<std::mutex> lock(mutex_);
  std::optional<FrameStats> found;
  waitFor(
      inSeconds,
      [&] {
        for (const FrameStats& stats : stats_) {
          if (inAccept(stats)) {
            found = stats;
            return true;
          }
        }
        return false;
      },
      lock);
  return found;
}

std::optional<visualization_msgs::MarkerArray> NodeClient::waitMarkers(const ros::Time& inStamp,
                                                                       double inSeconds) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!waitFor(
          inSeconds, [&] { return markers_.count(inStamp) > 0; }, lock))
    return std::nullopt;
  return markers_.at(inStamp);
}

std::optional<ComputePairs::Response> NodeClient::call(const BoxArray& inBoxes) {
  ComputePairs srv;
  srv.request.boxes = inBoxes;
  if (!service_.call(srv)) return std::nullopt;
  return srv.response;
}

}  // namespace test
}  // namespace sap_broadphase
