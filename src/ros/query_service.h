// QueryService: `query_boxes`, what overlaps given boxes in the node's current world (the last
// frame of its sources and the scenery), answered on threads of its own from the worker's
// snapshot of its last frame (world_snapshot.h), so that a call never waits for the frame in
// progress and a long frame never holds up the node's other callbacks.
#pragma once

#include <optional>
#include <string>

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "frame_worker.h"
#include "sap_broadphase/QueryBoxes.h"
#include "sap_broadphase/core/box_set.h"
#include "source_ingest.h"

namespace sap_broadphase {

class QueryService {
 public:
  /// Advertises `query_boxes` on ioNode, served by its own spinner threads. inIngest (its
  /// placement in ~fixed_frame) and inWorker (the world) must outlive the service.
  QueryService(ros::NodeHandle& ioNode, const SourceIngest& inIngest, const FrameWorker& inWorker,
               int inLogPeriod);
  /// Stops the spinner; a call in progress is answered first.
  ~QueryService();
  QueryService(const QueryService&) = delete;
  QueryService& operator=(const QueryService&) = delete;

 private:
  /// Checks the query boxes as a source frame's, places them in ~fixed_frame and asks the
  /// worker's engine.
  bool onQuery(QueryBoxes::Request& inRequest, QueryBoxes::Response& outResponse);
  /// Logs (throttled, INFO: the caller has the reason) and answers a refusal.
  void refuse(const std::string& inReason, QueryBoxes::Response& outResponse);

  const SourcePlacement& placement_;
  const FrameWorker& worker_;
  int log_period_;
  ros::CallbackQueue queue_;
  ros::ServiceServer service_;
  std::optional<ros::AsyncSpinner> spinner_;
};

}  // namespace sap_broadphase
