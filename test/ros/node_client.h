// A test-side client of one BroadphaseNode: publishes boxes, collects pairs, stats and
// markers by stamp, calls the service. Callbacks run on the test's AsyncSpinner.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/ComputePairs.h"
#include "sap_broadphase/FrameStats.h"
#include "sap_broadphase/PairArray.h"

namespace sap_broadphase {
namespace test {

class NodeClient {
 public:
  /// Connects to the node whose topics live in namespace inNamespace ("" = the root).
  explicit NodeClient(const std::string& inNamespace, bool inWantMarkers = false);

  /// Waits until the node subscribes to our boxes and publishes to our subscribers.
  bool waitConnected(double inSeconds);
  /// Publishes inBoxes with a fresh stamp (returned), not waiting for anything.
  ros::Time publish(BoxArray& ioBoxes);
  /// Publishes inBoxes with a fresh stamp and waits for the pairs of that stamp.
  std::optional<PairArray> roundTrip(BoxArray& ioBoxes, double inSeconds);
  /// Waits for the pairs of the frame stamped inStamp.
  std::optional<PairArray> waitPairs(const ros::Time& inStamp, double inSeconds);
  /// Waits for the first stats message that satisfies inAccept.
  std::optional<FrameStats> waitStats(const std::function<bool(const FrameStats&)>& inAccept,
                                      double inSeconds);
  /// Waits for the marker array of the frame stamped inStamp.
  std::optional<visualization_msgs::MarkerArray> waitMarkers(const ros::Time& inStamp,
                                                             double inSeconds);
  /// True when pairs stamped inStamp were ever received.
  bool sawPairs(const ros::Time& inStamp);
  /// Calls compute_pairs; nothing when the call itself failed.
  std::optional<ComputePairs::Response> call(const BoxArray& inBoxes);
  /// Number of publishers connected to our markers subscriber.
  uint32_t markerPublishers() const { return markers_sub_.getNumPublishers(); }

 private:
  template <typename Predicate>
  bool waitFor(double inSeconds, Predicate inReady, std::unique_lock<std::mutex>& ioLock);

  ros::NodeHandle node_;
  ros::Publisher boxes_pub_;
  ros::Subscriber pairs_sub_, stats_sub_, markers_sub_;
  ros::ServiceClient service_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::map<ros::Time, PairArray> pairs_;
  std::vector<FrameStats> stats_;
  std::map<ros::Time, visualization_msgs::MarkerArray> markers_;
  uint32_t next_stamp_ = 1;
};

}  // namespace test
}  // namespace sap_broadphase
