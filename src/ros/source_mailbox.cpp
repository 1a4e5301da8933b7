// SourceMailbox: the sources' frames between the callbacks and the worker.
#include "source_mailbox.h"

#include <utility>

#include <ros/console.h>

namespace sap_broadphase {

SourceMailbox::SourceMailbox(const SourcePlacement& inPlacement, double inTransformTimeout,
                             Clock inNow, MailboxReport& ioReport, Wake inWake)
    : placement_(inPlacement),
      transform_timeout_(inTransformTimeout),
      now_(std::move(inNow)),
      report_(ioReport),
      wake_(std::move(inWake)) {}

void SourceMailbox::post(const SourceKey& inKey, std::shared_ptr<SourceFrame> inFrame) {
  const std_msgs::Header& header = inFrame->header;
  // Asked before the lock: tf2 has its own, and a frame that turns placeable meanwhile is
  // released by the worker's next take().
  const bool ready = placement_.canPlace(header.frame_id, header.stamp);
  Delivery delivery{std::move(inFrame), now_()};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (ready) {
      // A frame of the same source still waiting for its transform is older: it goes.
      if (waiting_.erase(inKey) > 0) report_.dropped();
      Delivery& slot = pending_[inKey];
      if (slot.frame) report_.dropped();  // never started: the newer frame of the source wins
      slot = std::move(delivery);
    } else {
      Delivery& slot = waiting_[inKey];
      if (slot.frame) report_.dropped();
      slot = std::move(delivery);
      any_waiting_ = true;
    }
  }
  if (ready) wake_();
}

void SourceMailbox::postScenery(BoxArrayConstPtr inScenery) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_scenery_ = std::move(inScenery);
    scenery_wait_logged_ = false;
    any_waiting_ = true;
  }
  wake_();
}

void SourceMailbox::noteConverted(const std_msgs::Header& inHeader) {
  std::lock_guard<std::mutex> lock(mutex_);
  last_converted_ = inHeader;
}

std_msgs::Header SourceMailbox::lastConverted() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_converted_;
}

void SourceMailbox::releaseWaiting(const ros::Time& inNow) {
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    auto& [key, delivery] = *it;
    const std_msgs::Header& header = delivery.frame->header;
    if (placement_.canPlace(header.frame_id, header.stamp)) {
      Delivery& slot = pending_[key];
      if (slot.frame && slot.frame->header.stamp > header.stamp) {
        report_.dropped();  // a newer frame of the source is ready already
      } else {
        if (slot.frame) report_.dropped();
        slot = std::move(delivery);
      }
    } else if ((inNow - delivery.received).toSec() > transform_timeout_) {
      report_.skipped(sourceName(key) + " skipped: no transform into '" + placement_.fixedFrame() +
                      "' within ~transform_timeout (" + std::to_string(transform_timeout_) + " s)");
    } else {
      ++it;
      continue;
    }
    it = waiting_.erase(it);
  }
}

void SourceMailbox::releaseScenery(BoxArrayConstPtr& ioScenery) {
  const BoxArray& scenery = *pending_scenery_;
  // An empty scenery (clearing it) needs no frame; a scenery stays put: the latest transform.
  if (scenery.bounds.empty() || placement_.canPlace(scenery.header.frame_id, ros::Time(0))) {
    ioScenery = std::move(pending_scenery_);
    pending_scenery_.reset();
  } else if (!scenery_wait_logged_) {
    scenery_wait_logged_ = true;
    ROS_INFO("sap_broadphase: static_boxes waits for a transform from '%s' into '%s'",
             scenery.header.frame_id.c_str(), placement_.fixedFrame().c_str());
  }
}

void SourceMailbox::take(std::map<SourceKey, Delivery>& outDeliveries,
                         BoxArrayConstPtr& ioScenery) {
  outDeliveries.clear();
  const ros::Time now = now_();
  std::lock_guard<std::mutex> lock(mutex_);
  if (!waiting_.empty()) releaseWaiting(now);
  std::swap(outDeliveries, pending_);
  if (pending_scenery_) releaseScenery(ioScenery);
  any_waiting_ = !waiting_.empty() || pending_scenery_;
}

void SourceMailbox::restartClock(const ros::Time& inNow) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto* deliveries : {&pending_, &waiting_})
    for (auto& [key, delivery] : *deliveries) delivery.received = inNow;
}

}  // namespace sap_broadphase
