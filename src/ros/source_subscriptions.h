// SourceSubscriptions: the subscriber callbacks of the node's inputs, every topic of ~sources
// and the latched static_boxes. Built and stopped on the node's thread; its callbacks run on
// roscpp's callback threads (the node handle's queue), check or convert each message and post
// it into the SourceMailbox, counting and naming what they refuse in the status. They write
// nothing else.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "node_params.h"
#include "node_status.h"
#include "publisher_probe.h"
#include "sap_broadphase/BoxArray.h"
#include "source_mailbox.h"
#include "source_placement.h"
#include "sources.h"

namespace topic_tools {
class ShapeShifter;  // the message of a source read through an adapter (any type)
}  // namespace topic_tools

namespace sap_broadphase {

class SourceAdapter;  // adapters.h: a ~sources entry of another type

class SourceSubscriptions {
 public:
  /// Subscribes on ioNode (callbacks on its queue). ioStatus, ioMailbox and inPlacement must
  /// outlive the subscriptions.
  SourceSubscriptions(ros::NodeHandle& ioNode, const NodeParams& inParams, NodeStatus& ioStatus,
                      SourceMailbox& ioMailbox, const SourcePlacement& inPlacement);
  /// Calls stop().
  ~SourceSubscriptions();
  /// Unsubscribes: no callback after it returns (a callback in progress is waited for).
  void stop();
  SourceSubscriptions(const SourceSubscriptions&) = delete;
  SourceSubscriptions& operator=(const SourceSubscriptions&) = delete;

  /// The sources read through an adapter: each is thread-safe (a mutex of its own), for the
  /// worker's upkeep (names, publishers gone).
  std::vector<SourceAdapter*> adapters() const;
  /// Resolved names of the MarkerArray sources, whose queue losses are counted.
  const std::vector<std::string>& statefulTopics() const { return stateful_topics_; }

 private:
  /// Subscribes to a ~sources entry: a BoxArray topic as published (shared in process by a
  /// nodelet, never copied), any other entry through its adapter.
  void subscribe(ros::NodeHandle& ioNode, const SourceSpec& inSpec, int inQueueSize);
  /// Subscribes to the latched scenery, static_boxes.
  void subscribeScenery(ros::NodeHandle& ioNode);
  /// Callback of a BoxArray source read as published: the shape is checked, then posted.
  void deliver(const std::string& inTopic, const ros::MessageEvent<BoxArray const>& inEvent);
  /// Callback of a source read through an adapter (another type, or a BoxArray with an
  /// id_offset, group or mask): converts the message (naming new ids), then posts it.
  void onAdaptedMessage(SourceAdapter& ioAdapter,
                        const ros::MessageEvent<topic_tools::ShapeShifter const>& inEvent);
  /// Callback of static_boxes: checks and posts the scenery.
  void keepScenery(const BoxArrayConstPtr& inMsg);
  /// Counts a frame of inTopic from inPublisher received; refuses it when it can never be
  /// placed in ~fixed_frame, else posts it.
  void deliverFrame(const std::string& inTopic, const std::string& inPublisher,
                    std::shared_ptr<SourceFrame> inFrame);
  /// Counts and logs a message of inTopic whose handling threw (inWhat): refused, not fatal.
  void refuseUnhandled(const std::string& inTopic, const std::string& inWhat);

  NodeStatus& status_;
  SourceMailbox& mailbox_;
  const SourcePlacement& placement_;
  std::vector<ros::Subscriber> subscribers_;
  std::vector<std::unique_ptr<SourceAdapter>> adapters_;  // sources read through an adapter
  std::vector<std::pair<std::string, PublisherProbe::Check>> probed_topics_;  // resolved
  std::unique_ptr<PublisherProbe> publisher_probe_;  // after the subscriptions, stopped first
  std::vector<std::string> stateful_topics_;         // resolved names of the MarkerArray sources
};

}  // namespace sap_broadphase
