// BroadphaseNode: the broad phase as a ROS node, the thin owner of its parts: the sources'
// ingest (subscriptions, latest frames, tf2), the worker with its engine, the outputs (pairs,
// events, markers), the status (stats, /diagnostics), the compute_pairs and query_boxes services
// and dynamic_reconfigure. The executable (node_main.cpp) and the nodelet (nodelets.cpp) both build
// this class; only where the parameters come from differs.
#pragma once

#include <atomic>
#include <memory>

#include <ros/ros.h>

#include "frame_outputs.h"
#include "frame_worker.h"
#include "node_params.h"
#include "node_reconfigure.h"
#include "node_status.h"
#include "pairs_service.h"
#include "query_service.h"
#include "source_ingest.h"

namespace sap_broadphase {

/// All topic and service names are relative to the node handle given, so they can be remapped
/// or pushed into a namespace. Every thread it needs is its own (worker, service spinner, tf
/// listener); the caller only spins ioNode's queue.
class BroadphaseNode {
 public:
  /// Subscribes, advertises and starts the worker and the service thread. The source callbacks
  /// run on ioNode's callback queue (spin it, e.g. ros::spin()); inPrivate names the node for
  /// /diagnostics and serves dynamic_reconfigure on its callback queue.
  BroadphaseNode(ros::NodeHandle& ioNode, const ros::NodeHandle& inPrivate,
                 const NodeParams& inParams);
  /// Stops the inputs, then the worker (a frame in progress is finished first) and the service.
  ~BroadphaseNode();
  BroadphaseNode(const BroadphaseNode&) = delete;
  BroadphaseNode& operator=(const BroadphaseNode&) = delete;

 private:
  /// Wakes the worker once it exists: a nodelet manager may run a source callback while the
  /// constructor is still building the worker.
  void wakeWorker();

  NodeStatus status_;
  FrameOutputs outputs_;
  std::atomic<FrameWorker*> worker_ready_{nullptr};
  SourceIngest ingest_;
  FrameWorker worker_;
  PairsService service_;
  QueryService query_service_;  // after worker_: stopped before it
  std::unique_ptr<NodeReconfigure> reconfigure_;
};

}  // namespace sap_broadphase
