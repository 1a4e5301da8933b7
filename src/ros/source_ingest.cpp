// SourceIngest: the inputs' parts, built in order.
#include "source_ingest.h"

#include <utility>

namespace sap_broadphase {

namespace {

/// tf2's buffer when there is a ~fixed_frame to move boxes into, else none.
std::unique_ptr<tf2_ros::Buffer> transformsFor(const NodeParams& inParams) {
  if (inParams.fixed_frame.empty()) return nullptr;
  return std::make_unique<tf2_ros::Buffer>();
}

}  // namespace

SourceIngest::SourceIngest(ros::NodeHandle& ioNode, const NodeParams& inParams,
                           NodeStatus& ioStatus, Wake inWake)
    : tf_buffer_(transformsFor(inParams)),
      tf_listener_(tf_buffer_ ? std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, ioNode)
                              : nullptr),
      report_(ioStatus),
      placement_(inParams.fixed_frame, tf_buffer_.get()),
      mailbox_(
          placement_, inParams.transform_timeout, [] { return ros::Time::now(); }, report_, inWake),
      tf_changed_(wakeOnTransforms(inWake)),
      subscriptions_(ioNode, inParams, ioStatus, mailbox_, placement_),
      upkeep_(ioNode, subscriptions_.adapters(), subscriptions_.statefulTopics(), mailbox_,
              ioStatus) {}

boost::signals2::connection SourceIngest::wakeOnTransforms(Wake inWake) {
  if (!tf_buffer_) return {};
  // Runs on the listener's thread; it only wakes the worker (no lock of ours), and only while
  // a frame waits.
  return tf_buffer_->_addTransformsChangedListener([this, wake = std::move(inWake)] {
    if (mailbox_.anyWaiting()) wake();
  });
}

SourceIngest::~SourceIngest() {
  stop();
}

void SourceIngest::stop() {
  subscriptions_.stop();
  // The listener's reset joins its thread, the only one that calls the tf2 change listener.
  if (tf_buffer_) tf_buffer_->_removeTransformsChangedListener(tf_changed_);
  tf_listener_.reset();
}

}  // namespace sap_broadphase
