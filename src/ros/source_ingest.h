// SourceIngest: the node's inputs, in parts by the thread they run on, built and stopped here
// in the order they depend on each other:
// - SourcePlacement (source_placement.h): tf2 and ~fixed_frame; moves boxes into it for the
//   worker and the query threads;
// - SourceMailbox (source_mailbox.h): the latest frame of each source, written by the
//   subscriber callbacks, taken by the worker;
// - SourceSubscriptions (source_subscriptions.h): the callbacks, which post into the mailbox;
// - SourceUpkeep (source_upkeep.h): the worker's chores between frames (~id_names, queue
//   losses, publishers gone).
// It owns tf2's buffer and listener (with a ~fixed_frame), whose thread wakes the worker while
// a frame waits for its transform.
#pragma once

#include <memory>
#include <optional>

#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "node_params.h"
#include "node_status.h"
#include "source_mailbox.h"
#include "source_placement.h"
#include "source_subscriptions.h"
#include "source_upkeep.h"

namespace sap_broadphase {

/// The mailbox's reports as the node's status counts them.
class StatusMailboxReport : public MailboxReport {
 public:
  explicit StatusMailboxReport(NodeStatus& ioStatus) : status_(ioStatus) {}
  void dropped() override { status_.countDropped(); }
  void skipped(const std::string& inWhy) override { status_.skip(inWhy); }

 private:
  NodeStatus& status_;
};

class SourceIngest {
 public:
  /// Called after a frame or a scenery arrived (any thread), to wake the worker.
  using Wake = SourceMailbox::Wake;

  /// Subscribes on ioNode (callbacks on its queue) and, with a ~fixed_frame, listens to tf.
  SourceIngest(ros::NodeHandle& ioNode, const NodeParams& inParams, NodeStatus& ioStatus,
               Wake inWake);
  /// Calls stop().
  ~SourceIngest();
  /// Unsubscribes and stops listening to tf: no callback, and so no wake, after it returns.
  void stop();
  SourceIngest(const SourceIngest&) = delete;
  SourceIngest& operator=(const SourceIngest&) = delete;

  const SourcePlacement& placement() const { return placement_; }
  SourceMailbox& mailbox() { return mailbox_; }
  SourceUpkeep& upkeep() { return upkeep_; }

 private:
  /// With a ~fixed_frame, has tf2's listener thread wake the worker (inWake) after every
  /// transform tf2 takes in while a frame waits.
  boost::signals2::connection wakeOnTransforms(Wake inWake);

  // In the order of construction: tf2 listens before the first source frame arrives.
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;  // with a ~fixed_frame
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  StatusMailboxReport report_;
  SourcePlacement placement_;
  SourceMailbox mailbox_;
  boost::signals2::connection tf_changed_;
  SourceSubscriptions subscriptions_;
  SourceUpkeep upkeep_;
};

}  // namespace sap_broadphase
