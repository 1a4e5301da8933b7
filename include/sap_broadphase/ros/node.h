// BroadphaseNode: boxes in on a topic, pairs/markers/stats out from a worker thread, and the
// compute_pairs service on its own spinner thread with its own engine.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/ComputePairs.h"
#include "sap_broadphase/FrameStats.h"
#include "sap_broadphase/PairArray.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/ros/node_params.h"

namespace sap_broadphase {

/// The ROS face of the engine. All topic and service names are relative to the node handle
/// given, so they can be remapped or pushed into a namespace.
class BroadphaseNode {
 public:
  /// Subscribes, advertises and starts the worker and the service thread. The topic callback
  /// runs on ioNode's callback queue (spin it, e.g. ros::spin()).
  BroadphaseNode(ros::NodeHandle& ioNode, const NodeParams& inParams);
  /// Stops the service thread and the worker (a frame in progress is finished first).
  ~BroadphaseNode();
  BroadphaseNode(const BroadphaseNode&) = delete;
  BroadphaseNode& operator=(const BroadphaseNode&) = delete;

 private:
  /// Frame counters of the topic path; guarded by mutex_.
  struct Counters {
    uint64_t received = 0;
    uint64_t processed = 0;
    uint64_t dropped = 0;
    uint64_t refused = 0;
    std::string last_refusal;
  };

  /// Topic callback: cheap shape check, then hands the frame to the worker (latest wins).
  void onBoxes(const BoxArrayConstPtr& inMsg);
  /// Service callback: converts, validates and computes on the service's own engine.
  bool onComputePairs(ComputePairs::Request& inRequest, ComputePairs::Response& outResponse);
  /// The worker thread: waits for a pending frame, computes it, publishes.
  void workerLoop();
  /// Computes and publishes one frame (worker thread only).
  void processFrame(const BoxArray& inMsg);
  /// Counts and logs a refused topic frame and publishes stats for it (any thread).
  void refuseFrame(const BoxArray& inMsg, const std::string& inReason);
  /// Stats of the counters as they are now, header and box count from inMsg.
  FrameStats makeStats(const BoxArray& inMsg);

  NodeParams params_;
  ros::Subscriber boxes_sub_;
  ros::Publisher pairs_pub_;
  ros::Publisher markers_pub_;
  ros::Publisher stats_pub_;

  // Service: own queue and thread so a long topic frame never delays it.
  ros::CallbackQueue service_queue_;
  ros::ServiceServer service_;
  std::optional<ros::AsyncSpinner> service_spinner_;
  Broadphase service_engine_;  // used only by the service thread
  BoxSet service_boxes_;       // its conversion buffer

  // Worker hand-off: guarded by mutex_.
  std::mutex mutex_;
  std::condition_variable wake_;
  BoxArrayConstPtr pending_;
  bool stopping_ = false;
  Counters counters_;

  // Worker-owned state.
  Broadphase engine_;
  BoxSet boxes_;
  std::thread worker_;
};

}  // namespace sap_broadphase
