// PairsService: `compute_pairs`, answered on a thread and an engine of its own so that a long
// topic frame never delays a call (and a call never disturbs the topic engine's temporal state).
#pragma once

#include <mutex>
#include <optional>

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "sap_broadphase/ComputePairs.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/broadphase.h"

namespace sap_broadphase {

class PairsService {
 public:
  /// Advertises `compute_pairs` on ioNode, served by its own spinner thread.
  PairsService(ros::NodeHandle& ioNode, const BroadphaseConfig& inEngine, int inLogPeriod);
  /// Stops the spinner; a call in progress is answered first.
  ~PairsService();
  PairsService(const PairsService&) = delete;
  PairsService& operator=(const PairsService&) = delete;

  /// The next call runs on a new engine with inEngine (any thread).
  void reconfigure(const BroadphaseConfig& inEngine);

 private:
  /// Checks the request's shape and computes on the service's own engine, which reads and
  /// checks the boxes where they lie.
  bool onComputePairs(ComputePairs::Request& inRequest, ComputePairs::Response& outResponse);
  /// Logs (throttled) and answers a refusal: success false, the reason in the message.
  void refuse(const std::string& inReason, ComputePairs::Response& outResponse);

  int log_period_;
  ros::CallbackQueue queue_;
  ros::ServiceServer service_;
  std::optional<ros::AsyncSpinner> spinner_;
  Broadphase engine_;                               // used only by the service thread
  std::mutex mutex_;                                // guards pending_config_
  std::optional<BroadphaseConfig> pending_config_;  // for the service thread
};

}  // namespace sap_broadphase
