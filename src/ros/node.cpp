// BroadphaseNode: builds its parts in the order they depend on each other.
#include "node.h"

namespace sap_broadphase {

BroadphaseNode::BroadphaseNode(ros::NodeHandle& ioNode, const ros::NodeHandle& inPrivate,
                               const NodeParams& inParams)
    : status_(ioNode, inPrivate, inParams.engine, inParams.refusal_log_period),
      outputs_(ioNode, inParams.pairs_queue_size, inParams.publish_markers, inParams.markers),
      ingest_(ioNode, inParams, status_, [this] { wakeWorker(); }),
      worker_(inParams, ingest_, outputs_, status_),
      service_(ioNode, inParams.engine, inParams.refusal_log_period),
      query_service_(ioNode, ingest_, worker_, inParams.refusal_log_period) {
  ROS_INFO("sap_broadphase: %s", describeNodeParams(inParams).c_str());
  worker_ready_ = &worker_;
  wakeWorker();  // for what arrived before the worker was there
  reconfigure_ = std::make_unique<NodeReconfigure>(
      inPrivate, inParams, [this](const NodeParams& inSettings, bool inNewEngine) {
        worker_.reconfigure(inSettings);
        if (inNewEngine) service_.reconfigure(inSettings.engine);
      });
}

BroadphaseNode::~BroadphaseNode() {
  reconfigure_.reset();
  ingest_.stop();
}

void BroadphaseNode::wakeWorker() {
  if (FrameWorker* worker = worker_ready_.load()) worker->wake();
}

}  // namespace sap_broadphase
