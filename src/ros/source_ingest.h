// SourceIngest: the node's inputs. Subscribes to every topic of ~sources and to static_boxes,
// keeps the latest frame of each source until the worker takes it, and places frames in
// ~fixed_frame with tf2. A frame whose transform has not arrived yet waits aside (the latest
// of its source, as a tf2_ros::MessageFilter with a queue of one per source would keep it)
// until tf2 can place it or ~transform_timeout passes, so a late source never holds up the
// others.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "markers.h"
#include "node_params.h"
#include "node_status.h"
#include "publisher_probe.h"
#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/core/box_set.h"
#include "sources.h"

namespace topic_tools {
class ShapeShifter;  // the message of a source read through an adapter (any type)
}  // namespace topic_tools

namespace sap_broadphase {

class SourceAdapter;  // adapters.h: a ~sources entry of another type

/// A source frame waiting for the worker: the latest of its source wins. Its own until the
/// worker stores it (moving it into ~fixed_frame first, where there is one).
struct Delivery {
  std::shared_ptr<SourceFrame> frame;
  ros::Time received;  ///< ROS time of arrival: source time-outs follow /clock under sim time
};

class SourceIngest {
 public:
  /// Called after a frame or a scenery arrived (any thread), to wake the worker.
  using Wake = std::function<void()>;

  /// Subscribes on ioNode (callbacks on its queue) and, with a ~fixed_frame, listens to tf.
  SourceIngest(ros::NodeHandle& ioNode, const NodeParams& inParams, NodeStatus& ioStatus,
               Wake inWake);
  /// Calls stop().
  ~SourceIngest();
  /// Unsubscribes and stops listening to tf: no callback, and so no wake, after it returns.
  void stop();
  SourceIngest(const SourceIngest&) = delete;
  SourceIngest& operator=(const SourceIngest&) = delete;

  /// Hands a BoxArray of source topic inTopic to the worker as published: the shape is
  /// checked, the frame waits for its transform (with a ~fixed_frame), then replaces any frame
  /// of its source the worker has not taken yet.
  void deliver(const std::string& inTopic, const ros::MessageEvent<BoxArray const>& inEvent);

  /// Moves the frames ready for the worker (latest per source, transformable) into
  /// outDeliveries (replaced) and the newest scenery, once tf2 can place it, into ioScenery.
  /// Frames still waiting for their transform stay, or are skipped after ~transform_timeout;
  /// a scenery waits as long as it takes (it is latched: nothing replaces it).
  void take(std::map<SourceKey, Delivery>& outDeliveries, BoxArrayConstPtr& ioScenery);

  /// Moves ioFrame (of the source or scenery named inName) into ~fixed_frame with the transform
  /// at inStamp (time 0: the latest, for the scenery: it stays put, and a latched message may
  /// be older than tf2's cache); nothing to do without a ~fixed_frame. False, with the skip
  /// counted, when tf2 has no such transform; false, with the frame refused (counted, logged),
  /// when the transform is not finite.
  bool placeFrame(const std::string& inName, const ros::Time& inStamp, SourceFrame& ioFrame);

  /// Publishes the names of every adapter's ids on ~id_names when some are new since the last
  /// time (worker thread, once per round: a burst of new names costs one message, not one per
  /// name).
  void publishIdNames();
  /// The names of the last ~id_names by id, to label the markers (worker thread; updated by
  /// publishIdNames only when names are added, never copied per frame).
  const BoxNames& idNames() const { return id_names_; }
  /// Counts the MarkerArray messages roscpp dropped from a full subscriber queue since the last
  /// call (roscpp's own count, read from the node's getBusStats) into the status. Looks at
  /// most every kLossCheckSeconds (worker thread).
  void countLostMessages();
  /// The source inKey timed out: its adapter forgets the publisher's state (worker thread).
  void forget(const SourceKey& inKey);

  /// The ROS clock went back to inNow: frames waiting for the worker or for their transform
  /// count as received now (their ~transform_timeout starts again).
  void restartClock(const ros::Time& inNow);

  /// Moves boxes (a query's) from inHeader's frame into ~fixed_frame with the transform
  /// at its stamp (0: the latest), as a source frame's; nothing to do without a ~fixed_frame.
  /// The reason when they cannot be placed (an empty frame_id, no transform). Any thread.
  std::optional<std::string> placeInFixedFrame(const std_msgs::Header& inHeader, BoxSet& ioBoxes);

  /// The frame every source is moved into, or empty without a ~fixed_frame.
  const std::string& fixedFrame() const { return fixed_frame_; }

 private:
  /// Subscribes to a ~sources entry: a BoxArray topic as published (shared in process by a
  /// nodelet, never copied), any other entry through its adapter.
  void subscribe(ros::NodeHandle& ioNode, const SourceSpec& inSpec, int inQueueSize);
  /// Subscribes to the latched scenery, static_boxes.
  void subscribeScenery(ros::NodeHandle& ioNode);
  /// Counts and logs a message of inTopic whose handling threw (inWhat): refused, not fatal.
  void refuseUnhandled(const std::string& inTopic, const std::string& inWhat);
  /// Callback of a source read through an adapter (another type, or a BoxArray with an
  /// id_offset, group or mask): converts the message, names new ids on ~id_names, delivers.
  void onAdaptedMessage(SourceAdapter& ioAdapter,
                        const ros::MessageEvent<topic_tools::ShapeShifter const>& inEvent);

  /// Counts a frame of inTopic from inPublisher received; refuses it when it cannot be placed
  /// in ~fixed_frame, else keeps it for the worker.
  void deliverFrame(const std::string& inTopic, const std::string& inPublisher,
                    std::shared_ptr<SourceFrame> inFrame);
  /// Keeps a checked frame for the worker, or aside while its transform is missing.
  void store(const SourceKey& inKey, Delivery inDelivery);
  /// Moves the waiting frames that tf2 can now place to pending_, skips those that waited too
  /// long (called with mutex_ held).
  void releaseWaiting(const ros::Time& inNow);
  /// With a ~fixed_frame, the reason a frame named inFrame cannot be placed at all (empty).
  std::optional<std::string> unplaceableFrame(const std::string& inFrame) const;
  /// True when tf2 can move frame inFrame into the fixed frame at inStamp now (no waiting).
  bool transformable(const std::string& inFrame, const ros::Time& inStamp) const;
  /// Moves ioBoxes from inFrame into the fixed frame at inStamp (time 0: latest). False, with
  /// outError, when tf2 has no such transform, or with outBadTransform too when the transform
  /// is not finite (tf2 takes infinities): the boxes are then left as they were.
  bool moveIntoFixedFrame(const std::string& inFrame, const ros::Time& inStamp, BoxSet& ioBoxes,
                          std::string& outError, bool& outBadTransform);

  NodeStatus& status_;
  Wake wake_;
  std::string fixed_frame_;
  double transform_timeout_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  boost::signals2::connection tf_changed_;  // wakes the worker while frames wait for tf
  std::vector<ros::Subscriber> subscribers_;
  std::vector<std::unique_ptr<SourceAdapter>> adapters_;  // sources read through an adapter
  ros::Publisher id_names_pub_;                           // latched, while adapters name ids
  std::mutex id_names_mutex_;
  std::size_t id_names_published_ = 0;  // names in the last ~id_names (under the mutex above)
  std_msgs::Header id_names_header_;    // of the last message an adapter converted
  BoxNames id_names_;                   // the names of the last ~id_names (worker thread)

  std::vector<std::pair<std::string, PublisherProbe::Check>> probed_topics_;  // resolved
  std::unique_ptr<PublisherProbe> publisher_probe_;  // after the subscriptions, stopped first
  std::vector<std::string> stateful_topics_;         // resolved names of the MarkerArray sources
  std::map<std::pair<std::string, int>, int> drops_seen_;  // by topic and connection id
  std::chrono::steady_clock::time_point loss_checked_;     // (worker thread)

  std::mutex mutex_;                       // guards what the worker takes
  std::map<SourceKey, Delivery> pending_;  // ready for the worker
  std::map<SourceKey, Delivery> waiting_;  // waiting for their transform
  std::atomic<bool> any_waiting_{false};
  BoxArrayConstPtr pending_scenery_;  // until tf2 can place it
  bool scenery_wait_logged_ = false;
};

}  // namespace sap_broadphase
