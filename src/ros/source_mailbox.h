// SourceMailbox: where the subscriber callbacks leave the sources' frames for the frame worker.
// Callbacks (any of roscpp's callback threads) post into it; the worker takes from it once a
// round; every member runs under the mailbox's one mutex, held only to move pointers. The
// latest frame of a source wins. A frame whose transform into ~fixed_frame has not arrived
// yet waits aside (the latest of its source, as a tf2_ros::MessageFilter with a queue of one
// per source would keep it) until it can be placed or ~transform_timeout passes, so a late
// source never holds up the others.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <ros/time.h>
#include <std_msgs/Header.h>

#include "sap_broadphase/BoxArray.h"
#include "source_placement.h"
#include "sources.h"

namespace sap_broadphase {

/// A source frame waiting for the worker. Its own until the worker stores it (moving it into
/// ~fixed_frame first, where there is one).
struct Delivery {
  std::shared_ptr<SourceFrame> frame;
  ros::Time received;  ///< ROS time of arrival: source time-outs follow /clock under sim time
};

/// What the mailbox tells the node's status: NodeStatus in the node, a recorder in the tests.
class MailboxReport {
 public:
  virtual ~MailboxReport() = default;
  /// A frame replaced by a newer one of its source before the worker took it.
  virtual void dropped() = 0;
  /// A frame that waited for its transform past ~transform_timeout, and why it was skipped.
  virtual void skipped(const std::string& inWhy) = 0;
};

class SourceMailbox {
 public:
  /// ROS time now (ros::Time::now in the node; a fake clock in the tests).
  using Clock = std::function<ros::Time()>;
  /// Wakes the worker: a frame or a scenery is ready (called without the mailbox's lock).
  using Wake = std::function<void()>;

  /// inPlacement says whether a frame can be placed yet; it and ioReport must outlive the
  /// mailbox. A frame waits for its transform at most inTransformTimeout seconds.
  SourceMailbox(const SourcePlacement& inPlacement, double inTransformTimeout, Clock inNow,
                MailboxReport& ioReport, Wake inWake);
  SourceMailbox(const SourceMailbox&) = delete;
  SourceMailbox& operator=(const SourceMailbox&) = delete;

  // ---- Subscriber callbacks (any thread) ----
  /// Keeps a checked frame of inKey, received now, for the worker (and wakes it), or aside
  /// while its transform is missing. A frame of inKey not taken yet is replaced (dropped).
  void post(const SourceKey& inKey, std::shared_ptr<SourceFrame> inFrame);
  /// Keeps the newest scenery (checked) until it can be placed; wakes the worker.
  void postScenery(BoxArrayConstPtr inScenery);
  /// Remembers the header of the last message an adapter converted (for ~id_names).
  void noteConverted(const std_msgs::Header& inHeader);

  // ---- tf2's listener thread ----
  /// True while a frame or the scenery waits for its transform.
  bool anyWaiting() const { return any_waiting_.load(std::memory_order_relaxed); }

  // ---- The frame worker ----
  /// Moves the frames ready for the worker (latest per source, placeable) into outDeliveries
  /// (replaced) and the newest scenery, once it can be placed, into ioScenery. Frames still
  /// waiting for their transform stay, or are skipped after ~transform_timeout; a scenery
  /// waits as long as it takes (it is latched: nothing replaces it).
  void take(std::map<SourceKey, Delivery>& outDeliveries, BoxArrayConstPtr& ioScenery);
  /// The header of the last message an adapter converted.
  std_msgs::Header lastConverted() const;
  /// The ROS clock went back to inNow: frames waiting for the worker or for their transform
  /// count as received now (their ~transform_timeout starts again).
  void restartClock(const ros::Time& inNow);

 private:
  /// Moves the waiting frames that can now be placed to pending_, skips those that waited too
  /// long (mutex_ held).
  void releaseWaiting(const ros::Time& inNow);
  /// The scenery into ioScenery once it can be placed (mutex_ held).
  void releaseScenery(BoxArrayConstPtr& ioScenery);

  const SourcePlacement& placement_;
  double transform_timeout_;
  Clock now_;
  MailboxReport& report_;
  Wake wake_;

  mutable std::mutex mutex_;               // guards everything below but any_waiting_
  std::map<SourceKey, Delivery> pending_;  // ready for the worker
  std::map<SourceKey, Delivery> waiting_;  // waiting for their transform
  BoxArrayConstPtr pending_scenery_;       // until it can be placed
  bool scenery_wait_logged_ = false;
  std_msgs::Header last_converted_;
  std::atomic<bool> any_waiting_{false};
};

}  // namespace sap_broadphase
